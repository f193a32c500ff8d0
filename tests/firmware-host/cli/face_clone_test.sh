#!/usr/bin/env bash
# `facectl face clone`: the default head cloned onto a warped copy of itself writes a
# library and visemes the loaders take, with every source pose, and a JSON report; heads
# that do not correspond, or are missing, exit 2 naming what.
# Usage: face_clone_test.sh FACECTL FACE_WARP_HEAD SOURCE_DIR FRAMES
set -euo pipefail
facectl=$1 warp=$2 src=$3 frames=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
head="$src/config/heads/default"
"$warp" "$head" "$tmp/warped"

# A few poses of each kind, so that the sanitizer trees can afford it.
cat > "$tmp/library.yaml" <<'YAML'
expressions:
  neutral: {}
  joy: { muscles: { zygomaticus_major_l: 0.7, zygomaticus_major_r: 0.7 }, mandible: { pitch_deg: 3 } }
  wink: { muscles: { orbicularis_oculi_l: 0.4 }, rigid: { eyelid_closure_l: 1 } }
sequences:
  smile: { period_s: 1, poses: [neutral, joy] }
YAML
cat > "$tmp/visemes.yaml" <<'YAML'
visemes:
  none: { index: 0, phonemes: "-" }
  a: { index: 10, phonemes: "A:", muscles: { depressor_labii_inferioris_l: 0.2 }, mandible: { pitch_deg: 14 } }
YAML
"$facectl" face clone --from "$head" --to "$tmp/warped" --out "$tmp/out" --library "$tmp/library.yaml" \
  --visemes "$tmp/visemes.yaml" --report "$tmp/report.json" --frames "$frames" --iterations 1 \
  > "$tmp/table.txt"
cat "$tmp/table.txt"
for name in neutral joy wink none a; do
  grep -q " $name " "$tmp/table.txt" || { echo "no row for $name"; exit 1; }
done
python3 - "$tmp" <<'PY'
import json, math, sys, yaml
tmp = sys.argv[1]
report = json.load(open(tmp + "/report.json"))
assert sorted(report["expressions"]) == ["joy", "neutral", "wink"], report
assert sorted(report["visemes"]) == ["a", "none"], report
for kind in report.values():
    for name, r in kind.items():
        for stage in ("copy", "refined"):
            for key in ("rms_mm", "max_mm", "percent"):
                v = r[stage][key]
                assert isinstance(v, (int, float)) and math.isfinite(v) and v >= 0, (name, r)
        # the refinement keeps the best pose it saw, the copy included
        assert r["refined"]["rms_mm"] <= r["copy"]["rms_mm"] + 1e-9, (name, r)
assert report["expressions"]["neutral"]["copy"]["rms_mm"] == 0, report
assert report["expressions"]["joy"]["copy"]["rms_mm"] > 0, report
lib = yaml.safe_load(open(tmp + "/out/library.yaml"))
assert sorted(lib["expressions"]) == ["joy", "neutral", "wink"], lib
assert lib["sequences"]["smile"]["poses"] == ["neutral", "joy"], lib
assert lib["expressions"]["wink"]["rigid"]["eyelid_closure_l"] > 0, lib
vis = yaml.safe_load(open(tmp + "/out/visemes.yaml"))["visemes"]
assert sorted(vis) == ["a", "none"] and vis["a"]["index"] == 10 and vis["a"]["phonemes"] == "A:", vis
assert 0 < vis["a"]["mandible"]["pitch_deg"] <= 18, vis
PY
# The cloned library loads for the target head (the expression library loader).
"$facectl" face export-obj --head "$tmp/warped" --library "$tmp/out/library.yaml" --expression joy \
  --frames 2 --out "$tmp/joy.obj"
# ... and the cloned visemes load with the viseme loader (cloned back onto the source).
"$facectl" face clone --from "$tmp/warped" --to "$head" --out "$tmp/back" --library "$tmp/out/library.yaml" \
  --visemes "$tmp/out/visemes.yaml" --frames 20 --iterations 0 > /dev/null

expect_2() {  # expect_2 PATTERN ARGS...: exit 2 with PATTERN on stderr
  local pattern=$1 status=0
  shift
  "$facectl" face clone "$@" --out "$tmp/bad" --library "$tmp/library.yaml" --visemes "$tmp/visemes.yaml" \
    --frames 20 > "$tmp/bad.txt" 2>&1 || status=$?
  [ "$status" = 2 ] || { echo "expected exit 2, got $status"; cat "$tmp/bad.txt"; exit 1; }
  grep -q -- "$pattern" "$tmp/bad.txt" || { echo "expected '$pattern'"; cat "$tmp/bad.txt"; exit 1; }
}
expect_2 "$tmp/missing" --from "$head" --to "$tmp/missing"
cp -r "$tmp/warped" "$tmp/renamed"
sed -i 's/^  fdp_9_3:/  fdp_9_99:/' "$tmp/renamed/landmarks.yaml"
grep -q "fdp_9_99" "$tmp/renamed/landmarks.yaml"
expect_2 "landmark names differ.*fdp_9_3.*fdp_9_99" --from "$head" --to "$tmp/renamed"
cp -r "$tmp/warped" "$tmp/muscles"
sed -i 's/name: mentalis_r\b/name: mentalis_right/' "$tmp/muscles/head.yaml" "$tmp/muscles/muscles.yaml"
expect_2 "commanded muscle names differ.*mentalis_r.*mentalis_right" --from "$head" --to "$tmp/muscles"
echo "clone: table, report, outputs and bad input as expected"
