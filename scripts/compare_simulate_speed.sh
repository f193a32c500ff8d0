#!/bin/bash
# Compares `facectl bench simulate` between facectl binaries on a shared,
# noisy machine: runs them alternately N times (short runs at nice -20, which
# needs root) and prints each variant's fastest tick, which load inflates
# least. Usage: scripts/compare_simulate_speed.sh N BINARY...
set -euo pipefail
n=$1
shift
declare -A best
for ((i = 0; i < n; i++)); do
  for bin in "$@"; do
    out=$(nice -n -20 "$bin" bench simulate --duration 20 --runs 1 2>&1)
    for variant in "simulate (no render)" "loop without outputs"; do
      us=$(grep -F "$variant" <<<"$out" | sed -E 's/.* ([0-9.]+) us per tick.*/\1/')
      key="$bin | $variant"
      if [[ -z "${best[$key]:-}" ]] || awk -v a="$us" -v b="${best[$key]}" 'BEGIN { exit !(a < b) }'; then
        best[$key]=$us
      fi
    done
  done
done
for key in "${!best[@]}"; do printf '%6s us a tick  %s\n' "${best[$key]}" "$key"; done | sort -t'|' -k2
