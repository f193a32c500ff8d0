#!/bin/bash
# The event log in the journal: `facectl serve` under systemd (JOURNAL_STREAM
# set, as systemd sets it for a unit whose output the journal takes) sends
# every entry to journald, with PRIORITY and FACECTL_EVENT, and no longer
# prints it on stderr. A real systemd-journald runs in a private mount
# namespace whose /run/systemd/journal and /run/log are fresh tmpfs, so the
# machine's own journal, if it has one, sees nothing of this test.
#
# Needs root (unshare --mount); exit 77 (skipped) otherwise.
# Usage: journal_test.sh FACECTL SOURCE_DIR
set -uo pipefail
facectl=$1 source=$2
fail() { echo "FAIL: $*"; exit 1; }

if [ "${1:-}" != --inside ]; then
  [ "$(id -u)" = 0 ] || { echo "skipped: unshare --mount needs root"; exit 77; }
  exec unshare --mount --propagation private bash "$0" --inside "$@"
fi
shift
facectl=$1 source=$2

tmp=$(mktemp -d /tmp/facectl-test-journal-XXXXXX)
journald_pid=
serve_pid=
cleanup() {
  [ -n "$serve_pid" ] && kill "$serve_pid" 2>/dev/null
  [ -n "$journald_pid" ] && kill "$journald_pid" 2>/dev/null
  rm -rf "$tmp"
}
trap cleanup EXIT

# journald keeps a volatile journal under /run/log/journal unless
# /var/log/journal exists; a tmpfs over each keeps both private.
mkdir -p /run/systemd/journal /run/log
mount -t tmpfs tmpfs /run/systemd/journal || fail "mount tmpfs on /run/systemd/journal"
mount -t tmpfs tmpfs /run/log || fail "mount tmpfs on /run/log"
[ -d /var/log/journal ] && mount -t tmpfs tmpfs /var/log/journal
/lib/systemd/systemd-journald > "$tmp/journald.log" 2>&1 &
journald_pid=$!
for _ in $(seq 100); do
  [ -S /run/systemd/journal/socket ] && break
  sleep 0.05
done
[ -S /run/systemd/journal/socket ] || fail "systemd-journald did not start: $(cat "$tmp/journald.log")"

JOURNAL_STREAM=8:1 "$facectl" serve --config "$source/config/facectl.yaml" \
  --listen 127.0.0.1:0 --event-log "$tmp/events.jsonl" > "$tmp/serve.out" 2>&1 &
serve_pid=$!

# The port is in the "listening on" entry, which now goes to the journal only.
port=
for _ in $(seq 200); do
  port=$(journalctl --no-pager -o cat FACECTL_EVENT=service 2>/dev/null |
         sed -n 's|.*listening on http://127.0.0.1:\([0-9]*\)/.*|\1|p' | head -1)
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || fail "no 'listening on' entry in the journal; serve said: $(cat "$tmp/serve.out")"

python3 - "$port" <<'EOF' || fail "the API calls failed"
import http.client, json, sys, time
port = int(sys.argv[1])
def call(method, path):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    c.request(method, path, body=b"" if method == "POST" else None)
    r = c.getresponse()
    return r.status, json.loads(r.read() or b"{}")
def wait(state):
    for _ in range(200):
        if call("GET", "/api/v1/state")[1].get("state") == state:
            return
        time.sleep(0.05)
    sys.exit("never reached " + state)
assert call("POST", "/api/v1/enable")[0] == 200
wait("RUNNING")
assert call("POST", "/api/v1/disable")[0] == 200
wait("IDLE")
EOF

kill -TERM "$serve_pid"
wait "$serve_pid"
rc=$?
serve_pid=
[ "$rc" = 0 ] || fail "facectl serve exited $rc: $(cat "$tmp/serve.out")"

journalctl --sync || fail "journalctl --sync failed"
journalctl --no-pager -o json --output-fields=MESSAGE,PRIORITY,FACECTL_EVENT,_COMM \
  > "$tmp/journal.json" || fail "journalctl failed"
python3 - "$tmp/journal.json" "$tmp/events.jsonl" <<'EOF' || exit 1
import json, sys
journal = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
ours = [e for e in journal if "FACECTL_EVENT" in e]
events = [json.loads(l) for l in open(sys.argv[2])]
def fail(msg):
    sys.exit("FAIL: " + msg)
if not ours:
    fail("no FACECTL_EVENT entries in the journal")
# Every line of the file is in the journal, in order, as "source: text".
want = [(e["kind"], "%s: %s" % (e["source"], e["text"])) for e in events]
got = [(e["FACECTL_EVENT"], e["MESSAGE"]) for e in ours]
if got != want:
    fail("journal and file differ:\n journal %r\n file    %r" % (got, want))
for e in ours:
    if e.get("_COMM") != "facectl":
        fail("entry from %r, expected facectl: %r" % (e.get("_COMM"), e))
    priority = "3" if e["FACECTL_EVENT"] == "fault" else "6"
    if e.get("PRIORITY") != priority:
        fail("%s entry at priority %r, expected %s" % (e["FACECTL_EVENT"], e.get("PRIORITY"), priority))
for kind, text in (("command", ": enable"), ("transition", "IDLE -> ENABLING"),
                   ("transition", "ENABLING -> RUNNING"), ("command", ": disable"),
                   ("service", "stopped in IDLE")):
    if not any(k == kind and text in m for k, m in got):
        fail("no %s entry with %r in the journal" % (kind, text))
print("journal: %d entries, the same as the file's, priority info" % len(ours))
EOF
# Under the journal the entries are not printed on stderr as well.
grep -q "IDLE -> ENABLING" "$tmp/serve.out" && fail "entries also printed on stderr"
echo "journal: PASS"
