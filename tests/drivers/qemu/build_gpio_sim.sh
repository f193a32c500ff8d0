#!/usr/bin/env bash
# Builds the kernel's GPIO simulator, gpio-sim, out of tree for the QEMU
# guest's kernel: Debian's kernel has neither CONFIG_GPIO_SIM nor
# CONFIG_GPIO_MOCKUP. The source is Debian's own (linux-source-6.1), built
# against the matching linux-headers so that the modules' vermagic and symbol
# versions are the guest kernel's.
#
# gpio-sim needs the interrupt simulator (kernel/irq/irq_sim.c), which the
# kernel builds in only with CONFIG_IRQ_SIM, also unset in Debian's kernel
# (and gpio-mockup needs it too). So irq_sim.c is built as a module of its own,
# irq_sim.ko, with two changes: a MODULE_LICENSE, and generic_handle_irq() in
# place of handle_simple_irq(irq_to_desc()), because irq_to_desc() is not
# exported to modules since Linux 5.11 (generic_handle_irq() ends in the same
# handle_simple_irq(), the handler irq_sim sets on each interrupt).
#
# Only the three files needed are taken out of the source tarball, and the
# result is kept: a second run with the same kernel and script does nothing.
#
# Usage: build_gpio_sim.sh OUT_DIR KERNEL_VERSION
# Output: OUT_DIR/irq_sim.ko and OUT_DIR/gpio-sim.ko (gpio-sim depends on
# configfs, from the kernel's own modules, and irq_sim).
# Exit: 0 built or up to date, 1 the build failed, 77 skipped (a package is
# missing; scripts/setup.sh installs linux-source-6.1 and linux-headers-amd64).
set -euo pipefail

out=$1
kver=$2
tarball=/usr/src/linux-source-6.1.tar.xz
kbuild=/lib/modules/$kver/build

skip() { echo "SKIP: $*"; exit 77; }
[ -f "$tarball" ] || skip "$tarball missing (package linux-source-6.1)"
[ -d "$kbuild" ] || skip "$kbuild missing (package linux-headers-$kver)"
command -v make >/dev/null || skip "make not installed (package build-essential)"

# The stamp names what the modules were built from; a match means up to date.
stamp="$kver $(stat -c %Y "$tarball") $(sha256sum "$0" | cut -c1-16)"
if [ -f "$out/gpio-sim.ko" ] && [ -f "$out/irq_sim.ko" ] && [ "$(cat "$out/stamp" 2>/dev/null)" = "$stamp" ]; then
  echo "gpio-sim: up to date in $out"
  exit 0
fi

start=$(date +%s)
rm -rf "$out"
mkdir -p "$out/src"
src=linux-source-6.1
tar -xf "$tarball" -C "$out/src" "$src/drivers/gpio/gpio-sim.c" "$src/drivers/gpio/gpiolib.h" \
  "$src/kernel/irq/irq_sim.c"
cp "$out/src/$src/drivers/gpio/gpio-sim.c" "$out/src/$src/drivers/gpio/gpiolib.h" "$out/"
sed 's/handle_simple_irq(irq_to_desc(irqnum))/generic_handle_irq(irqnum)/' \
  "$out/src/$src/kernel/irq/irq_sim.c" > "$out/irq_sim.c"
grep -q 'generic_handle_irq(irqnum)' "$out/irq_sim.c" || {
  echo "gpio-sim: irq_sim.c no longer calls handle_simple_irq(irq_to_desc(irqnum)); check the patch"
  exit 1
}
printf '\n#include <linux/module.h>\nMODULE_LICENSE("GPL");\n' >> "$out/irq_sim.c"
rm -rf "$out/src"
echo 'obj-m := irq_sim.o gpio-sim.o' > "$out/Kbuild"
if ! make -C "$kbuild" M="$(cd "$out" && pwd)" modules -j2 > "$out/build.log" 2>&1; then
  cat "$out/build.log"
  echo "gpio-sim: the module build failed"
  exit 1
fi
echo "$stamp" > "$out/stamp"
echo "gpio-sim: built irq_sim.ko and gpio-sim.ko for $kver in $(( $(date +%s) - start )) s"
