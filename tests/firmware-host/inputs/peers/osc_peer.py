#!/usr/bin/env python3
"""OSC datagrams built by python-osc (pythonosc/ beside this file, public
domain, see SOURCES.md), an independent implementation of OSC 1.0, for
facectl's tests of `facectl serve`'s OSC control.

  osc_peer.py send PORT   sends, to 127.0.0.1:PORT, one datagram each:
    1. /facectl/expression "joy" 0.5                  (a message, ,sf)
    2. a bundle: /facectl/signal/jaw_pitch_deg 12.0 (,f) and
                 /facectl/signal/neck_pan_deg 10 (,i)
    3. /facectl/no_such_thing 1                        (an unknown address)
    4. /facectl/signal/jaw_pitch_deg 30.0              (outside -4..18: refused)
    5. b"not osc"                                      (malformed)
  osc_peer.py write DIR   writes those datagrams and a few more (a nested
    bundle, double, int64 and string arguments) as files: the seeds of the
    osc_datagram fuzz target (scripts/fuzz.sh)
"""
import os
import socket
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pythonosc import osc_bundle_builder, osc_message_builder  # noqa: E402


def message(address, *args):
    b = osc_message_builder.OscMessageBuilder(address=address)
    for a in args:
        b.add_arg(*a) if isinstance(a, tuple) else b.add_arg(a)
    return b.build()


def datagrams():
    bundle = osc_bundle_builder.OscBundleBuilder(osc_bundle_builder.IMMEDIATELY)
    bundle.add_content(message("/facectl/signal/jaw_pitch_deg", (12.0, "f")))
    bundle.add_content(message("/facectl/signal/neck_pan_deg", (10, "i")))
    return [
        message("/facectl/expression", "joy", (0.5, "f")).dgram,
        bundle.build().dgram,
        message("/facectl/no_such_thing", (1, "i")).dgram,
        message("/facectl/signal/jaw_pitch_deg", (30.0, "f")).dgram,
        b"not osc",
    ]


def more_datagrams():
    inner = osc_bundle_builder.OscBundleBuilder(osc_bundle_builder.IMMEDIATELY)
    inner.add_content(message("/facectl/show/queue", "demo"))
    outer = osc_bundle_builder.OscBundleBuilder(osc_bundle_builder.IMMEDIATELY)
    outer.add_content(message("/facectl/show/play", "idle"))
    outer.add_content(inner.build())
    return [
        outer.build().dgram,
        message("/facectl/signal/eye_yaw_left_deg", (3.5, "d")).dgram,
        message("/facectl/signal/neck_tilt_deg", (2**40, "h")).dgram,
        message("/facectl/neutral").dgram,
        message("/facectl/show/stop").dgram,
    ]


def write(out):
    os.makedirs(out, exist_ok=True)
    for i, d in enumerate(datagrams() + more_datagrams()):
        with open(os.path.join(out, "python_osc_%02d.osc" % i), "wb") as f:
            f.write(d)


if __name__ == "__main__":
    if sys.argv[1] == "write":
        write(sys.argv[2])
        sys.exit(0)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    port = int(sys.argv[2])
    for d in datagrams():
        sock.sendto(d, ("127.0.0.1", port))
    print("sent 5 datagrams")
