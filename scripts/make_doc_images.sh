#!/usr/bin/env bash
# Regenerates the pictures in docs/images from real runs of the default head on
# simulated hardware. Usage: scripts/make_doc_images.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
facectl="./${1:-build}/firmware-host/facectl"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$facectl" run --record "$tmp/demo.csv" --quiet
"$facectl" plot "$tmp/demo.csv" --actuator jaw_pitch --actuator lip_corner_up_l \
  --actuator eye_yaw_l --out docs/images/demo

# An e-stop at 3 s: outputs drop on the tick that reads it (exit code 3 by design).
"$facectl" run --duration 5 --inject estop@3 --record "$tmp/estop.csv" --quiet || [ $? -eq 3 ]
"$facectl" plot "$tmp/estop.csv" --actuator jaw_pitch --out docs/images/estop
