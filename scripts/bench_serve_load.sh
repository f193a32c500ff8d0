#!/usr/bin/env bash
# What an API under load costs the real-time loop (docs/PERFORMANCE.md,
# "Control API under load"). Runs `facectl serve` on the default head,
# enabled, playing the demo show, then `facectl bench loop` beside it twice:
# once with the API idle, once while 50 clients hammer it on loopback (state,
# rig, events, poses, show plays, and five telemetry streams at 100 Hz).
# Reports both wake-up latency tables and serve's own overruns in each phase.
#
# Usage: scripts/bench_serve_load.sh [FACECTL] [SECONDS]   (defaults: build/firmware-host/facectl, 60)
set -euo pipefail
cd "$(dirname "$0")/.."
facectl="${1:-build/firmware-host/facectl}"
seconds="${2:-60}"
work="$(mktemp -d)"
trap 'kill "$serve_pid" 2>/dev/null || true; rm -rf "$work"' EXIT

"$facectl" serve --listen 127.0.0.1:0 --event-log "$work/events.jsonl" >"$work/serve.log" 2>&1 &
serve_pid=$!
for _ in $(seq 100); do
  port=$(sed -n 's|.*listening on http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$work/serve.log")
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || { cat "$work/serve.log"; exit 1; }
api="http://127.0.0.1:$port/api/v1"
curl -sf -d '' "$api/enable" >/dev/null
sleep 2
curl -sf -d '{"name":"demo"}' "$api/show/play" >/dev/null

overruns() { curl -sf "$api/state" | python3 -c 'import json,sys; print(json.load(sys.stdin)["loop"]["overruns"])'; }

echo "== API idle: facectl bench loop --duration $seconds beside facectl serve"
before=$(overruns)
nice -n -20 "$facectl" bench loop --duration "$seconds"
echo "serve overruns while idle: $(( $(overruns) - before ))"

echo "== API under load: 50 clients for the same time"
before=$(overruns)
python3 - "$api" "$((seconds * 2 + 5))" >"$work/load.txt" <<'PY' &
import http.client, json, sys, threading, time, urllib.parse
api, seconds = sys.argv[1], float(sys.argv[2])
u = urllib.parse.urlparse(api)
end = time.monotonic() + seconds
counts = {"requests": 0, "errors": 0, "events": 0}
lock = threading.Lock()
ops = [("GET", "/state", None), ("GET", "/rig", None), ("GET", "/events?limit=100", None),
       ("POST", "/pose", json.dumps({"signals": {"jaw_pitch_deg": 4}})),
       ("POST", "/show/play", json.dumps({"name": "demo"})), ("GET", "/shows", None)]
def client(i):
    conn = http.client.HTTPConnection(u.hostname, u.port, timeout=10)
    n = e = 0
    while time.monotonic() < end:
        method, path, body = ops[(i + n) % len(ops)]
        try:
            conn.request(method, u.path + path, body=body,
                         headers={"Content-Type": "application/json"} if body else {})
            r = conn.getresponse(); r.read()
            if r.status >= 300: e += 1
        except Exception:
            e += 1; conn.close(); conn = http.client.HTTPConnection(u.hostname, u.port, timeout=10)
        n += 1
    with lock: counts["requests"] += n; counts["errors"] += e
def stream():
    conn = http.client.HTTPConnection(u.hostname, u.port, timeout=10)
    conn.request("GET", u.path + "/telemetry?rate_hz=100")
    r = conn.getresponse(); n = 0
    while time.monotonic() < end:
        line = r.fp.readline()
        if not line: break
        if line.startswith(b"data: "): n += 1
    with lock: counts["events"] += n
threads = [threading.Thread(target=client, args=(i,)) for i in range(45)]
threads += [threading.Thread(target=stream) for _ in range(5)]
for t in threads: t.start()
for t in threads: t.join()
print(f"{counts['requests']} requests ({counts['errors']} refused or failed), "
      f"{counts['events']} telemetry events, over {seconds:.0f} s")
PY
load_pid=$!
sleep 3
nice -n -20 "$facectl" bench loop --duration "$seconds"
echo "serve overruns under load: $(( $(overruns) - before ))"
wait "$load_pid"
echo "load: $(cat "$work/load.txt")"
kill -TERM "$serve_pid"
wait "$serve_pid" && echo "serve stopped: exit 0"
