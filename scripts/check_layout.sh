#!/bin/bash
# Fails on an #include that goes against the layout's one direction
# (CONTRIBUTING.md): firmware-host -> sim -> drivers -> control.
#   control/  includes nothing from drivers/, sim/ (facectl/face/) or firmware-host/;
#   drivers/  nothing from sim/ or firmware-host/;
#   sim/      nothing from firmware-host/;
# and control/actuator_model.hpp, the seam's vocabulary, includes nothing of ours.
# Usage: scripts/check_layout.sh [ROOT]   (default: this checkout)
set -uo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
status=0

# check FOLDER REGEX WHAT: no include under FOLDER may match REGEX.
check() {
  local hits
  hits=$(grep -rnE "^[[:space:]]*#[[:space:]]*include[[:space:]]*\"($2)" "$root/$1" \
           --include='*.hpp' --include='*.cpp' --include='*.h' 2>/dev/null)
  if [ -n "$hits" ]; then
    echo "layout: $1/ must not include $3:"
    echo "$hits" | sed "s|^$root/|  |"
    status=1
  fi
}

check control 'drivers/|sim/|facectl/face/|firmware-host/|\.\./' "drivers/, sim/, facectl/face/ or firmware-host/"
check drivers 'sim/|facectl/face/|firmware-host/|\.\./' "sim/ or firmware-host/"
check sim 'firmware-host/|\.\./' "firmware-host/"
if [ -f "$root/control/actuator_model.hpp" ] &&
   grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$root/control/actuator_model.hpp"; then
  echo "layout: control/actuator_model.hpp must include nothing of facectl's"
  status=1
fi
[ $status -eq 0 ] && echo "layout: includes go one way (firmware-host -> sim -> drivers -> control)"
exit $status
