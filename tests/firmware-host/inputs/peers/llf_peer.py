#!/usr/bin/env python3
"""Live Link Face packets encoded by PyLiveLinkFace (pylivelinkface.py beside
this file, MIT; peers/SOURCES.md), an independent implementation of the app's
UDP format, for facectl's tests.

  llf_peer.py write DIR          the fixture packets of tests/.../real/live_link_face_udp
  llf_peer.py send PORT SECONDS  a performance at 60 fps to 127.0.0.1:PORT, then
                                 one malformed datagram; prints what it sent

PyLiveLinkFace imports numpy (unused by encode) and timecode (for the frame
number); Debian 12 has no python3-timecode, so both are stood in for here.
The stand-in Timecode gives the frame count of 'h:m:s:f' as the timecode
package does (1-based); facectl does not read the frame number.
"""
import os
import socket
import sys
import time
import types

numpy = types.ModuleType("numpy")
sys.modules.setdefault("numpy", numpy)
timecode = types.ModuleType("timecode")


class Timecode:
    def __init__(self, fps, text):
        h, m, s, f = (float(x) for x in text.split(":"))
        self.frames = int(((h * 60 + m) * 60 + s) * fps + f) + 1


timecode.Timecode = Timecode
sys.modules["timecode"] = timecode
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "pylivelinkface"))
from pylivelinkface import FaceBlendShape, PyLiveLinkFace  # noqa: E402

DEVICE = "4B3A1C2D-5E6F-4071-8293-A4B5C6D7E8F9"


def face(**values):
    f = PyLiveLinkFace(name="facectl-test", uuid=DEVICE, fps=60)
    for name, v in values.items():
        f.set_blendshape(FaceBlendShape[name], v)
    return f


def write(out):
    os.makedirs(out, exist_ok=True)
    shapes = {
        "neutral": face(),
        # Left and right kept apart: Unreal's order has JawLeft before JawRight.
        "jaw_open_smile_left": face(JawOpen=0.6, MouthSmileLeft=0.8, JawLeft=0.5,
                                    BrowInnerUp=0.7, HeadYaw=0.2, HeadPitch=-0.1),
    }
    for name, f in shapes.items():
        with open(os.path.join(out, "pylivelinkface_" + name + ".bin"), "wb") as fh:
            fh.write(f.encode())


def send(port, seconds):
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    n = int(seconds * 60)
    start = time.monotonic()
    for i in range(n):
        sock.sendto(face(JawOpen=0.6, BrowInnerUp=0.7).encode(), ("127.0.0.1", port))
        time.sleep(max(0.0, start + (i + 1) / 60 - time.monotonic()))
    sock.sendto(b"\x06not a packet", ("127.0.0.1", port))
    print("sent %d packets and 1 malformed" % n)


if __name__ == "__main__":
    if sys.argv[1] == "write":
        write(sys.argv[2])
    else:
        send(int(sys.argv[2]), float(sys.argv[3]))
