#!/usr/bin/env bash
# Measures what facectl's 1 kHz loop needs to survive load (docs/REALTIME.md),
# by running `facectl bench loop` in a QEMU/KVM guest under four kernel
# set-ups: Debian's stock kernel and its PREEMPT_RT kernel, each booted with
# and without the isolation cmdline, and in each boot idle and then under
# `stress-ng --cpu 2 --io 1 --vm 1`.
#
# Why a guest: the kernel and its command line are what is measured, and
# trying them on this machine would mean installing kernels into /boot (other
# scripts boot the newest /boot/vmlinuz) and rebooting. The kernels are
# downloaded as .debs and unpacked with `dpkg -x` into WORK_DIR only; nothing
# is installed.
#
# Caveat baked into every number: the guest's vCPUs are ordinary threads of
# the host, so host scheduling noise (compile jobs, the host's own non-RT
# kernel) shows up in the guest's latencies. A guest figure is an upper
# bound of what the same kernel does on bare metal, and comparisons are only
# fair between cells measured at similar host load; the script prints the
# host's `uptime` before each boot for that reason.
#
# This is a measurement tool, not part of CI. It needs no root: apt-get
# download and dpkg -x work unprivileged; /dev/kvm must be read-writable.
#
# Usage: measure_rt_in_qemu.sh WORK_DIR
#   env DURATION  seconds per variant of each bench loop (default 15; each
#                 run takes about twice that: bare and pipeline interleave)
#   env REPEAT    runs of each cell per boot (default 1)
#   env FACECTL_BIN     facectl binary (default build/firmware-host/facectl)
#   env FACECTL_CONFIG  config folder (default config/); must match the binary
#   env ACCEL     kvm (default) or tcg (plumbing check only, see below)
#   env TABLE_ONLY=1  print the table again from WORK_DIR's console logs
# Exit: 0 when every cell ran, 1 otherwise, 77 when a tool is missing.
set -euo pipefail

work=${1:?usage: measure_rt_in_qemu.sh WORK_DIR}
repo=$(cd "$(dirname "$0")/.." && pwd)
facectl_bin=${FACECTL_BIN:-$repo/build/firmware-host/facectl}
config_dir=${FACECTL_CONFIG:-$repo/config}
duration=${DURATION:-15}
repeat=${REPEAT:-1}
# The loop's CPU is runtime.realtime.cpu in the shipped config; the
# isolation cmdline takes it away from the scheduler, the tick, RCU
# callbacks and device interrupts.
iso_args="isolcpus=1 nohz_full=1 rcu_nocbs=1 irqaffinity=0"

skip() { echo "SKIP: $*"; exit 77; }
command -v qemu-system-x86_64 >/dev/null || skip "qemu-system-x86_64 not installed (package qemu-system-x86)"
# ACCEL=kvm (default) is the only setting whose numbers mean anything.
# ACCEL=tcg runs the same matrix under QEMU's emulator, which only shows that
# the plumbing works: emulated time makes every cell miss deadlines.
accel=${ACCEL:-kvm}
if [ "$accel" = kvm ]; then
  [ -r /dev/kvm ] && [ -w /dev/kvm ] || skip "/dev/kvm not usable (ACCEL=tcg runs the plumbing, but its latencies measure the emulator)"
  # PVM (kvm_pvm, the pagetable-based nested KVM of some cloud VMs) provides
  # /dev/kvm without VT-x/AMD-V, and runs only kernels built as PVM guests
  # (CONFIG_PVM_GUEST). Debian's kernels hang right after the decompressor.
  [ ! -d /sys/module/kvm_pvm ] || skip "/dev/kvm here is PVM (kvm_pvm): it boots only PVM guest kernels, not Debian's; run on a host with VT-x/AMD-V KVM (or ACCEL=tcg for the plumbing only)"
  cpu_args=(-cpu "host,-arch-capabilities")
else
  echo "WARNING: ACCEL=$accel: the guest's latencies measure the emulator, not the kernels"
  cpu_args=(-cpu max)
fi
command -v stress-ng >/dev/null || skip "stress-ng not installed (apt-get install stress-ng; measurement only)"
[ -x /bin/busybox ] && ! ldd /bin/busybox >/dev/null 2>&1 || skip "static /bin/busybox missing (package busybox-static)"
command -v apt-get >/dev/null && command -v dpkg >/dev/null || skip "apt-get/dpkg missing (Debian host expected)"
[ -x "$facectl_bin" ] || skip "no facectl binary at $facectl_bin (build it, or set FACECTL_BIN)"
[ -f "$config_dir/facectl.yaml" ] || skip "no $config_dir/facectl.yaml (set FACECTL_CONFIG)"

mkdir -p "$work"
work=$(cd "$work" && pwd)

# --- Table -------------------------------------------------------------------
# From the console logs, so TABLE_ONLY=1 can print it again without booting.
print_table() {
  echo
  echo "accel=$accel; wake-up latency in us (p50/p99/p99.9/max); overruns and missed deadlines bare/pipeline"
  printf '%-6s %-4s %-6s %-3s | %-30s | %-30s | %-9s | %-9s | %s\n' \
    kernel iso load rep "bare p50/p99/p99.9/max" "pipeline p50/p99/p99.9/max" overruns missed state
  for kname in stock rt; do
    for iso in 0 1; do
      tr -d '\r' < "$work/console-$kname-iso$iso.log" | awk -v k="$kname" -v i="$iso" '
        /^FACECTL-RT-BEGIN/ { split($2, a, "="); load = a[2]; split($3, b, "="); rep = b[2];
                              bare = full = ov = ms = ""; state = "?"; lat = 0; stopped = 0 }
        /wake-up latency/ { lat = 1 }
        /tick compute/ { lat = 0 }
        lat && /bare clock_nanosleep/ { bare = $3 "/" $5 "/" $6 "/" $7 }
        lat && /full pipeline/ { full = $3 "/" $5 "/" $6 "/" $7 }
        /over all chunks/ {
          match($0, /bare [0-9]+, pipeline [0-9]+; missed/); s = substr($0, RSTART, RLENGTH)
          gsub(/[^0-9 ]/, "", s); gsub(/^ +/, "", s); split(s, o, " +"); ov = o[1] "/" o[2]
          match($0, /missed deadlines bare [0-9]+, pipeline [0-9]+/); s = substr($0, RSTART, RLENGTH)
          gsub(/[^0-9 ]/, "", s); gsub(/^ +/, "", s); split(s, m, " +"); ms = m[1] "/" m[2]
          match($0, /controller state [A-Z_]+/); state = substr($0, RSTART + 17, RLENGTH - 17) }
        /MEASUREMENT STOPPED/ { stopped = 1 }
        /^FACECTL-RT-END/ { printf "%-6s %-4s %-6s %-3s | %-30s | %-30s | %-9s | %-9s | %s%s\n",
                              k, i, load, rep, bare, full, ov, ms, state, stopped ? " (stopped)" : "" }'
    done
  done
}
if [ "${TABLE_ONLY:-0}" = 1 ]; then print_table; exit 0; fi

# --- Kernels -----------------------------------------------------------------
# The current ones: whatever the metapackages' candidates depend on, so the
# stock and RT kernels are the same upstream version and differ by config.
kernel_package() {
  { apt-cache show --no-all-versions "$1" 2>/dev/null || true; } |
    sed -n 's/^Depends: \(linux-image-[^ ,]*\).*/\1/p' | head -n 1
}
stock_pkg=$(kernel_package linux-image-amd64)
rt_pkg=$(kernel_package linux-image-rt-amd64)
[ -n "$stock_pkg" ] && [ -n "$rt_pkg" ] || skip "apt-cache knows no linux-image-amd64 / linux-image-rt-amd64 (apt-get update?)"
echo "Kernels: $stock_pkg (stock) and $rt_pkg (PREEMPT_RT)"

mkdir -p "$work/debs"
for pkg in "$stock_pkg" "$rt_pkg"; do
  if ! ls "$work/debs/${pkg}"_*.deb >/dev/null 2>&1; then
    (cd "$work/debs" && apt-get download "$pkg")
  fi
done
declare -A vmlinuz
for name in stock rt; do
  pkg=$stock_pkg
  [ "$name" = rt ] && pkg=$rt_pkg
  dir=$work/kernels/$name
  rm -rf "$dir"
  mkdir -p "$dir"
  dpkg -x "$(ls "$work/debs/${pkg}"_*.deb | head -n 1)" "$dir"
  vmlinuz[$name]=$(ls "$dir"/boot/vmlinuz-* | head -n 1)
done
# The guest needs no modules: the serial console, devtmpfs, the initramfs
# and kvm-clock are built in, and there are no disks.

# --- Initramfs ---------------------------------------------------------------
# busybox for the shell and taskset; facectl (stripped: only the size
# matters) and stress-ng with every library ldd names; the config folder.
root=$work/root
rm -rf "$root"
mkdir -p "$root"/{bin,proc,sys,dev,tmp,cfg}
# shellcheck source=tests/drivers/qemu/initramfs.sh
source "$repo/tests/drivers/qemu/initramfs.sh"
cp /bin/busybox "$root/bin/busybox"
copy_with_libs "$facectl_bin" "$(command -v stress-ng)"
if command -v strip >/dev/null; then strip "$root/bin/$(basename "$facectl_bin")"; fi
[ "$(basename "$facectl_bin")" = facectl ] || mv "$root/bin/$(basename "$facectl_bin")" "$root/bin/facectl"
cp -a "$config_dir"/. "$root/cfg/"

# The guest's init. Parameters come on the kernel command line (facectl_dur=,
# facectl_rep=, facectl_iso=) so one initramfs serves every boot.
cat > "$root/init" <<'INIT'
#!/bin/busybox sh
/bin/busybox --install -s /bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
cd /tmp
arg() { sed -n "s/.*\b$1=\([^ ]*\).*/\1/p" /proc/cmdline; }
dur=$(arg facectl_dur); rep=$(arg facectl_rep); iso=$(arg facectl_iso)
echo "FACECTL-RT: kernel $(uname -r) realtime=$(cat /sys/kernel/realtime 2>/dev/null || echo 0)" \
  "isolated='$(cat /sys/devices/system/cpu/isolated)' irq_default=$(cat /proc/irq/default_smp_affinity)" \
  "cpus=$(nproc) cmdline='$(cat /proc/cmdline)'"
# What `facectl run` itself says about this machine's readiness.
timeout 30 facectl run --config /cfg/facectl.yaml --duration 1 2>&1 | grep -E '^(warning|  - )' | sed 's/^/FACECTL-RT: run says: /'
r=1
while [ "$r" -le "$rep" ]; do
  for load in idle stress; do
    echo "FACECTL-RT-BEGIN load=$load rep=$r guest_loadavg=$(cut -d' ' -f1-3 /proc/loadavg)"
    pid=
    if [ "$load" = stress ]; then
      # Outlasts the bench (bare and pipeline variants, each $dur s). With
      # isolation it is pinned to CPU 0 (mask 1) explicitly, as an operator
      # would keep other work off the loop's CPU; isolcpus alone would also
      # keep it off, since CPU 1 leaves every default affinity.
      if [ "$iso" = 1 ]; then
        taskset 1 stress-ng --cpu 2 --io 1 --vm 1 --timeout $((2 * dur + 20))s >/tmp/stress.log 2>&1 &
      else
        stress-ng --cpu 2 --io 1 --vm 1 --timeout $((2 * dur + 20))s >/tmp/stress.log 2>&1 &
      fi
      pid=$!
      sleep 2
    fi
    facectl bench loop --config /cfg/facectl.yaml --duration "$dur" --chunk 1 2>&1
    echo "FACECTL-RT-END rc=$?"
    if [ -n "$pid" ]; then kill -INT "$pid" 2>/dev/null; wait "$pid" 2>/dev/null; fi
  done
  r=$((r + 1))
done
echo "FACECTL-RT-DONE"
poweroff -f
INIT
chmod +x "$root/init"
pack_initramfs "$work/initramfs.gz"
echo "Initramfs: $(du -h "$work/initramfs.gz" | cut -f1)"

# --- Boots -------------------------------------------------------------------
# -cpu host -smp 2 -m 2G: the loop's CPU 1 and a housekeeping CPU 0, as on
# the smallest target; 2G leaves stress-ng's --vm worker room.
# -arch-capabilities: when this host is itself a guest, plain `-cpu host`
# aborts in QEMU ("failed to set MSR 0x10a"); the MSR only reports CPU
# vulnerability mitigations and plays no part in the timing measured here.
per_boot=$(( repeat * 2 * (2 * duration + 40) + 120 ))
ok=1
for kname in stock rt; do
  for iso in 0 1; do
    extra=""
    [ "$iso" = 1 ] && extra=$iso_args
    log=$work/console-$kname-iso$iso.log
    echo "=== boot: kernel=$kname isolation=$iso; host uptime: $(uptime)"
    timeout "$per_boot" qemu-system-x86_64 -accel "$accel" "${cpu_args[@]}" -smp 2 -m 2G \
      -nographic -no-reboot -kernel "${vmlinuz[$kname]}" -initrd "$work/initramfs.gz" \
      -append "console=ttyS0 panic=-1 quiet $extra facectl_dur=$duration facectl_rep=$repeat facectl_iso=$iso" \
      </dev/null > "$log" 2>&1 || true
    tr -d '\r' < "$log" | grep -a -E '^FACECTL-RT|^facectl bench|^  ' || true
    if ! grep -aq 'FACECTL-RT:' "$log"; then
      echo "boot kernel=$kname isolation=$iso: the guest never reached init (see $log)"; ok=0
    elif ! grep -aq FACECTL-RT-DONE "$log"; then
      echo "boot kernel=$kname isolation=$iso did not finish (see $log)"; ok=0
    fi
  done
done

print_table
[ "$ok" = 1 ] && exit 0 || exit 1
