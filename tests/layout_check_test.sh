#!/bin/bash
# The layout check passes on this tree and fails on a tree with an include
# that goes the wrong way (control/ including sim/), naming the file.
set -uo pipefail
check=$1
tree=$(mktemp -d)
trap 'rm -rf "$tree"' EXIT
mkdir -p "$tree/control" "$tree/drivers" "$tree/sim" "$tree/firmware-host"
printf '#include "control/units.hpp"\n' > "$tree/sim/ok.cpp"
printf '#include "control/units.hpp"\n' > "$tree/control/ok.hpp"
bash "$check" "$tree" > /dev/null || { echo "FAIL: a clean tree was refused"; exit 1; }
printf '#include "sim/plant/servo_plant.hpp"\n' > "$tree/control/upward.hpp"
out=$(bash "$check" "$tree") && { echo "FAIL: control/ including sim/ passed"; exit 1; }
grep -q 'control/upward.hpp:1' <<< "$out" || { echo "FAIL: the report does not name the file: $out"; exit 1; }
rm "$tree/control/upward.hpp"
printf '#include "firmware-host/config/rig_config.hpp"\n' > "$tree/drivers/upward.cpp"
bash "$check" "$tree" > /dev/null && { echo "FAIL: drivers/ including firmware-host/ passed"; exit 1; }
echo "layout check: clean tree passes, upward includes fail"
