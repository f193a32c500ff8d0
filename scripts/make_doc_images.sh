#!/usr/bin/env bash
# Regenerates the pictures in docs/images from real runs of the default head on
# simulated hardware. Usage: scripts/make_doc_images.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
facectl="./${1:-build}/firmware-host/facectl"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$facectl" run --record "$tmp/demo.csv" --quiet
"$facectl" plot "$tmp/demo.csv" --actuator jaw_digastric --actuator lip_corner_up_l \
  --actuator eye_yaw_l --out docs/images/demo

# Verify's show check: the default rig's lip corner, which follows the
# reduced face model's lip-corner point, through the demo show.
"$facectl" verify config/rigs/default.yaml --ticks 1000 --show config/shows/demo.yaml \
  --plots "$tmp/verify" > /dev/null
mkdir -p docs/images/verify
cp "$tmp/verify/lip_corner_up_l.svg" docs/images/verify/

# An e-stop at 3 s: outputs drop on the tick that reads it (exit code 3 by design).
"$facectl" run --duration 5 --inject estop@3 --record "$tmp/estop.csv" --quiet || [ $? -eq 3 ]
"$facectl" plot "$tmp/estop.csv" --actuator jaw_digastric --out docs/images/estop

# facectl simulate with --render: one frame of the side-by-side pair (left the
# full face model, right the skin driven by the simulated actuators through the
# inverse mapping) and the digastric strut's plot of command, simulated
# position and limits.
"$facectl" simulate --rig config/rigs/default.yaml --show config/shows/demo.yaml \
  --out "$tmp/simulate" --duration 6 --render --quiet
mkdir -p docs/images/simulate
cp "$tmp/simulate/frames/frame_00100.png" docs/images/simulate/render_pair.png
cp "$tmp/simulate/plots/jaw_digastric.svg" docs/images/simulate/

# The expression library's contact sheet (README, docs/FACE_MODEL.md): each
# expression simulated from rest to steady state on the full face model.
"$facectl" face contact-sheet --out docs/images/expressions.png --columns 6

# The operator console of `facectl serve` just after ENABLE: the browser
# test's screenshot (tests/firmware-host/serve/console_browser_test.py, chromium).
python3 tests/firmware-host/serve/console_browser_test.py "$facectl" config/facectl.yaml \
  docs/images/console.png > /dev/null

# fit-head on the whole CGAL head (looking along -x): the face it finds, with the
# landmarks it places.
"$facectl" face fit-head --obj tests/data/heads/cgal_head/head.obj --out "$tmp/cgal" \
  --picture docs/images/fit_head_cgal.png > /dev/null
