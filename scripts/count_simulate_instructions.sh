#!/bin/bash
# Counts the instructions `facectl simulate` spends in its loop (run_simulation:
# the ticks, the simulated servos and buses, the outputs) on 10 s of the demo
# show on the default rig, 11,001 ticks, with valgrind's callgrind. Unlike wall
# time, the count does not depend on what else the machine is doing, so it
# compares two builds reliably on a shared host (docs/PERFORMANCE.md).
# Usage: scripts/count_simulate_instructions.sh FACECTL_BINARY [TOP_FUNCTIONS]
set -euo pipefail
bin=$1
top=${2:-20}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$work/callgrind.out" \
  '--toggle-collect=facectl::run_simulation*' "$bin" simulate \
  --rig "$root/config/rigs/default.yaml" --show "$root/config/shows/demo.yaml" \
  --duration 10 --out "$work/out" --quiet >/dev/null 2>"$work/valgrind.log"
refs=$(grep -o 'refs: .*' "$work/valgrind.log" || true)
# A count of 0 means the toggle found no run_simulation (inlined away, renamed).
if [[ -z "$refs" || "$refs" =~ refs:\ +0$ ]]; then
  echo "no instructions counted in facectl::run_simulation: $refs" >&2
  exit 1
fi
echo "$refs"
callgrind_annotate "$work/callgrind.out" 2>/dev/null | sed -n '/file:function/,$p' |
  sed -n "3,$((top + 2))p" | cut -c1-140
