#!/bin/bash
# Checks that two facectl binaries give the same `facectl simulate` outputs,
# byte for byte (telemetry.csv, plots, summaries, index.html): 60 s of the
# demo show on the default and hobby rigs, and the FAP demo on the default
# rig. A change meant only to be faster must pass it (docs/PERFORMANCE.md).
# Usage: scripts/compare_simulate_outputs.sh REFERENCE_FACECTL CANDIDATE_FACECTL
set -uo pipefail
reference=$1
candidate=$2
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cases=("--rig $root/config/rigs/default.yaml --show $root/config/shows/demo.yaml --duration 60"
       "--rig $root/config/rigs/hobby.yaml --show $root/config/shows/demo.yaml --duration 60"
       "--rig $root/config/rigs/default.yaml --fap $root/config/fap/demo.fap")
status=0
for k in "${!cases[@]}"; do
  for side in reference candidate; do
    # shellcheck disable=SC2086 # the case's words are separate arguments
    if ! "${!side}" simulate ${cases[$k]} --out "$work/$side$k" --quiet >/dev/null 2>&1; then
      echo "FAILED TO RUN ($side): ${cases[$k]}"
      status=1
    fi
  done
  if diff -r "$work/reference$k" "$work/candidate$k" >/dev/null; then
    echo "IDENTICAL: ${cases[$k]}"
  else
    echo "DIFFERENT: ${cases[$k]}"
    diff -rq "$work/reference$k" "$work/candidate$k" | head
    status=1
  fi
done
exit $status
