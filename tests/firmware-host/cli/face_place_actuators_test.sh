#!/usr/bin/env bash
# `facectl face place-actuators`: the YAML (paste-able rig points) and the JSON report on a
# small run, and exit 2 with a message for a bad budget or an unknown head.
# Usage: face_place_actuators_test.sh FACECTL FRAMES CANDIDATES
set -euo pipefail
facectl=$1 frames=$2 candidates=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$facectl" face place-actuators --budget 3 --expressions joy,surprise --candidates "$candidates" \
  --frames "$frames" --out "$tmp/rig.yaml" --report "$tmp/report.json" > "$tmp/table.txt" 2> "$tmp/log.txt"
grep -q "^joy " "$tmp/table.txt" && grep -q "^surprise " "$tmp/table.txt"
python3 - "$tmp/rig.yaml" "$tmp/report.json" <<'PY'
import json, math, sys, yaml
rig = yaml.safe_load(open(sys.argv[1]))
rep = json.load(open(sys.argv[2]))
assert len(rig["actuators"]) == 3 == len(rep["actuators"]), rig
for a in rig["actuators"]:
    assert isinstance(a["point"], str) and a["point"].startswith("fdp_"), a
    assert abs(math.hypot(*a["axis"]) - 1) < 1e-2, a
    assert a["travel_mm"][0] <= a["travel_mm"][1] and len(a["position_mm"]) == 3, a
assert sorted(rig["errors"]) == ["joy", "surprise"], rig["errors"]
for name, e in rep["expressions"].items():
    assert 0 <= e["rms_mm"] <= e["max_mm"] and e["rms_mm_no_actuators"] > 0, (name, e)
    # Three actuators leave less than the jaw and lids alone.
    assert e["rms_mm"] < e["rms_mm_no_actuators"], (name, e)
assert rep["budget"] == 3 and rep["candidates"] > 3, rep
PY

expect_2() {  # expect_2 MESSAGE ARGS...: exit code 2 and MESSAGE on stderr
  local msg=$1 status=0
  shift
  "$facectl" face place-actuators "$@" > "$tmp/out.txt" 2> "$tmp/err.txt" || status=$?
  [ "$status" = 2 ] || { echo "expected exit 2 for $*, got $status"; cat "$tmp/err.txt"; exit 1; }
  grep -q -- "$msg" "$tmp/err.txt" || { echo "no '$msg' for $*"; cat "$tmp/err.txt"; exit 1; }
}
expect_2 "--budget" --budget 0
expect_2 "--budget" --budget -3
expect_2 "--budget" --head "$tmp"
expect_2 "no-such-head" --budget 2 --head "$tmp/no-such-head"
mkdir "$tmp/empty-head"
expect_2 "empty-head" --budget 2 --head "$tmp/empty-head"
expect_2 "nothing" --budget 2 --expressions nothing --frames 5
expect_2 "named twice" --budget 2 --expressions joy,surprise,joy --frames 5
echo ok
