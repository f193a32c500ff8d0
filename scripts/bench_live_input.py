#!/usr/bin/env python3
"""Packet to actuator command, and the loop's deadlines under a UDP flood
(docs/PERFORMANCE.md, "Live inputs: packet to actuator command").

Runs `facectl run --live-link-face` on the default head (simulated hardware)
with per-tick telemetry, twice:

  quiet  a sender at 60 fps that steps jawOpen between 0 and 0.6 every 0.5 s;
  flood  the same sender, while a second process floods the same port with
         100,000 datagrams in 20 s: one in ten a good packet (held back: the
         playing sender has the stream), one in ten 9,000 bytes, the rest a
         good packet with a byte changed and cut short.

Each packet's send time is taken from CLOCK_MONOTONIC, and the run's summary
says which CLOCK_MONOTONIC time its telemetry's time_s 0 is, so each jaw step
is timed from the packet that carried it to the ticks that answered it: the
shaped face command (face.jaw_pitch) and the actuator command of the
jaw's opening strut (cmd.jaw_digastric) first moving, then reaching 50% and
90% of the step. Prints the run summaries' loop figures and stream counters.

Usage: scripts/bench_live_input.py [FACECTL] [--steps N] [--rounds N]
"""
import argparse
import csv
import multiprocessing
import os
import random
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests/firmware-host/inputs/peers"))
import llf_peer  # noqa: E402  (PyLiveLinkFace, an independent encoder)

OPEN = 0.6
STEP_S = 0.5
FPS = 60


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def now():
    return time.clock_gettime_ns(time.CLOCK_MONOTONIC) * 1e-9


def send_steps(port, steps, cpus, result):
    """1 s neutral, then `steps` jaw steps of STEP_S; puts [(t_sent, jaw_open)]."""
    if cpus:
        os.sched_setaffinity(0, cpus)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    packets = {v: llf_peer.face(JawOpen=v).encode() for v in (0.0, OPEN)}
    frames = FPS + steps * int(STEP_S * FPS) + FPS
    sent = []
    start = now()
    value = 0.0
    for i in range(frames):
        k = i - FPS
        want = OPEN if 0 <= k < steps * int(STEP_S * FPS) and (k // int(STEP_S * FPS)) % 2 == 0 \
            else 0.0
        t = now()
        sock.sendto(packets[want], ("127.0.0.1", port))
        if want != value:
            sent.append((t, want))
            value = want
        time.sleep(max(0.0, start + (i + 1) / FPS - now()))
    result.put(sent)


def flood(port, count, seconds, cpus, result):
    if cpus:
        os.sched_setaffinity(0, cpus)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    good = llf_peer.face(JawOpen=0.3, BrowInnerUp=0.9).encode()
    big = bytes(9000)
    rng = random.Random(7)
    start = now()
    for i in range(count):
        if i % 10 == 0:
            d = good
        elif i % 10 == 1:
            d = big
        else:
            b = bytearray(good)
            b[rng.randrange(len(b))] ^= 0xFF
            d = bytes(b[: rng.randrange(1, len(b))])
        sock.sendto(d, ("127.0.0.1", port))
        if i % 50 == 49:
            time.sleep(max(0.0, start + (i + 1) * seconds / count - now()))
    result.put(now() - start)


def run_phase(facectl, work, name, steps, flooding, cpus):
    port = free_port()
    # The shipped runtime file (SCHED_FIFO 80 on CPU 1, memory locked), on a free port.
    cfg = os.path.join(work, name + ".yaml")
    config = os.path.join(ROOT, "config")
    with open(os.path.join(config, "facectl.yaml")) as f:
        text = f.read()
    text = re.sub(r"^(\w+): (\S+\.yaml)$", lambda m: f"{m[1]}: {config}/{m[2]}", text,
                  flags=re.M)
    text = text.replace("port: 11111", f"port: {port}")
    with open(cfg, "w") as f:
        f.write(text)
    tele = os.path.join(work, name + ".csv")
    log = open(os.path.join(work, name + ".log"), "w+")
    proc = subprocess.Popen([facectl, "run", "--quiet", "--config", cfg, "--live-link-face",
                             "--duration", "600", "--record", tele], stdout=log, stderr=log)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        log.seek(0)
        if f"listening on UDP port {port}" in log.read():
            break
        time.sleep(0.05)
    else:
        proc.kill()
        sys.exit(f"{name}: facectl did not start listening")
    time.sleep(1.0)  # ENABLING: the head homes before it follows input
    stepped = multiprocessing.Queue()
    stepper = multiprocessing.Process(target=send_steps, args=(port, steps, cpus, stepped))
    stepper.start()
    flooder = None
    if flooding:
        time.sleep(0.5)  # the stepping sender has the stream; the flood's good packets wait
        flooded = multiprocessing.Queue()
        flooder = multiprocessing.Process(target=flood, args=(port, 100_000, 20.0, cpus, flooded))
        flooder.start()
    sent = stepped.get()
    stepper.join()
    flood_s = None
    if flooder:
        flood_s = flooded.get()
        flooder.join()
    time.sleep(0.3)
    proc.send_signal(2)
    proc.wait(timeout=60)
    log.seek(0)
    out = log.read()
    m = re.search(r"telemetry time_s 0 is CLOCK_MONOTONIC ([0-9.]+) s", out)
    if not m:
        sys.exit(f"{name}: no loop clock in the summary:\n{out}")
    return sent, tele, float(m.group(1)), out, flood_s


def step_latencies(sent, tele, t0):
    with open(tele) as f:
        rows = list(csv.DictReader(f))
    t = [t0 + float(r["time_s"]) for r in rows]
    series = {k: [float(r[k]) for r in rows] for k in ("face.jaw_pitch", "cmd.jaw_digastric")}
    out = {k: {"first": [], "50%": [], "90%": []} for k in series}
    for (ts, _), nxt in zip(sent, [s[0] for s in sent[1:]] + [t[-1]]):
        i0 = next(i for i, x in enumerate(t) if x >= ts)
        for k, v in series.items():
            before, after = v[i0 - 1], v[max(i for i, x in enumerate(t) if x < nxt)]
            span = after - before
            if abs(span) < 1e-9:
                continue
            for label, frac in (("first", 0.005), ("50%", 0.5), ("90%", 0.9)):
                j = next((i for i in range(i0, len(v)) if (v[i] - before) / span >= frac), None)
                if j is not None and t[j] < nxt:
                    out[k][label].append((t[j] - ts) * 1e3)
    return out


def summary_lines(out):
    keep = ("wake latency", "tick compute", "overruns", "Live Link Face stream", "stale-input",
            "final state")
    return [line.strip() for line in out.splitlines() if any(k in line for k in keep)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("facectl", nargs="?", default=os.path.join(ROOT, "build/firmware-host/facectl"))
    ap.add_argument("--steps", type=int, default=40)
    ap.add_argument("--loop-cpu", type=int, default=1, help="runtime.realtime.cpu of the config")
    ap.add_argument("--rounds", type=int, default=1,
                    help="run the three phases this many times, alternating (the machine varies)")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as work:
        others = os.sched_getaffinity(0) - {a.loop_cpu}
        phases = (("quiet", False, others), ("flood, senders off the loop's CPU", True, others),
                  ("flood, senders on any CPU", True, None))
        for name, flooding, cpus in [p for _ in range(a.rounds) for p in phases]:
            sent, tele, t0, out, flood_s = run_phase(a.facectl, work, name.split(",")[0] + str(
                len(name)), a.steps, flooding, cpus)
            lat = step_latencies(sent, tele, t0)
            print(f"== {name}: {len(sent)} jaw steps"
                  + (f", 100000 flood datagrams sent in {flood_s:.1f} s" if flood_s else ""))
            print("| signal | first move p50 / max | 50% p50 / max | 90% p50 / max |  (ms)")
            for k, v in lat.items():
                cells = [f"{statistics.median(v[c]):.1f} / {max(v[c]):.1f} (n={len(v[c])})"
                         if v[c] else "-" for c in ("first", "50%", "90%")]
                print(f"| {k} | " + " | ".join(cells) + " |")
            for line in summary_lines(out):
                print("  " + line)


if __name__ == "__main__":
    main()
