#!/usr/bin/env bash
# Runs facectl's SocketCAN, HID, MIDI, audio and I2C tests inside a QEMU
# guest, because this machine's kernel has neither CAN, uhid, sound nor
# i2c-stub. The guest is Debian's own kernel
# (linux-image-amd64) under software emulation (-accel tcg) with an initramfs
# holding busybox, the guest test binary and its libraries (hidapi, libudev),
# can-utils (candump, cansend), iproute2's ip, alsa-utils' aplaymidi with
# ALSA's configuration, and the modules can, can-raw, can-dev, vcan, hid,
# hid-generic, uhid, and soundcore, snd, snd-timer, snd-pcm, snd-aloop (the
# loopback sound card), snd-seq-device and snd-seq, and i2c-dev and i2c-stub
# (an SMBus adapter with register files at 0x40 and 0x41).
#
# Inside: vcan0 is created, candump records the wire, the gtest binary runs
# the real CAN buses against simulated drives and boards and a virtual uhid
# gamepad against the hidapi reader, MidiInput against aplaymidi playing
# midi/cc_and_notes.mid and AudioPlayback into the loopback card, captured
# at its other end, Pca9685Bus on the i2c-stub adapter through i2c-dev;
# and the recorded frames are checked for
# the driver's own, byte for byte.
#
# GPIO: build_gpio_sim.sh builds the gpio-sim simulator (and irq_sim, which
# it needs) for the guest's kernel; the guest loads them with configfs, and
# the GPIO safety I/O tests make gpio-sim chips through configfs.
#
# With FACECTL_BINARY and HEAD_YAML, the guest also holds a stripped
# `facectl` and the head file, and the guest test runs `facectl bus doctor`
# on a vcan rig.
#
# Usage: run_can_in_qemu.sh GUEST_TEST_BINARY WORK_DIR [FACECTL_BINARY HEAD_YAML]
# Exit: 0 pass, 1 fail, 77 skipped (a tool is missing; scripts/setup.sh installs them).
set -euo pipefail

test_bin=$1
work=$2
facectl_bin=${3:-}
head_yaml=${4:-}

skip() { echo "SKIP: $*"; exit 77; }
command -v qemu-system-x86_64 >/dev/null || skip "qemu-system-x86_64 not installed (package qemu-system-x86)"
command -v candump >/dev/null || skip "candump not installed (package can-utils)"
command -v cansend >/dev/null || skip "cansend not installed (package can-utils)"
[ -x /bin/busybox ] && ! ldd /bin/busybox >/dev/null 2>&1 || skip "static /bin/busybox missing (package busybox-static)"
ip_bin=$(command -v ip || true)
[ -n "$ip_bin" ] || skip "ip not installed (package iproute2)"
kernel=$(ls /boot/vmlinuz-*-amd64 2>/dev/null | sort -V | tail -n 1 || true)
[ -n "$kernel" ] || skip "no /boot/vmlinuz-*-amd64 (package linux-image-amd64)"
kver=${kernel#/boot/vmlinuz-}

rm -rf "$work"
root=$work/root
mkdir -p "$root"/{bin,sbin,proc,sys,dev,tmp,lib/modules}

# shellcheck source=tests/drivers/qemu/initramfs.sh
source "$(dirname "$0")/initramfs.sh"
cp /bin/busybox "$root/bin/busybox"
copy_with_libs "$test_bin" "$(command -v candump)" "$(command -v cansend)"
# Without alsa-utils the guest's MIDI test skips itself; CAN and HID still run.
if command -v aplaymidi >/dev/null; then copy_with_libs "$(command -v aplaymidi)"; fi
mkdir -p "$root/usr/share" "$root/midi"
cp -r /usr/share/alsa "$root/usr/share/alsa"  # snd_seq_open("default") reads alsa.conf
cp "$(dirname "$0")/midi/cc_and_notes.mid" "$root/midi/"
cp "$ip_bin" "$root/sbin/iproute2-ip"
copy_libs "$ip_bin"
modules="can can-raw can-dev vcan hid hid-generic uhid soundcore snd snd-timer snd-pcm snd-aloop snd-seq-device snd-seq"
for m in $modules; do
  cp "$(modinfo -k "$kver" -n "$m")" "$root/lib/modules/$m.ko"
done
# PCA9685 over i2c-dev: i2c-dev and the SMBus stub adapter (neither depends
# on another module), loaded with two chips at 0x40 and 0x41 in the INIT.
for m in i2c-dev i2c-stub; do
  cp "$(modinfo -k "$kver" -n "$m")" "$root/lib/modules/$m.ko"
done
# GPIO: the gpio-sim simulator, built out of tree for this kernel (it has no
# CONFIG_GPIO_SIM) and kept next to $work; without linux-source-6.1 and
# linux-headers-amd64 the guest's GPIO tests skip themselves.
gpio_sim_dir=$(dirname "$work")/gpio-sim
gpio_modules=""
if bash "$(dirname "$0")/build_gpio_sim.sh" "$gpio_sim_dir" "$kver"; then
  cp "$(modinfo -k "$kver" -n configfs)" "$root/lib/modules/configfs.ko"
  cp "$gpio_sim_dir/irq_sim.ko" "$gpio_sim_dir/gpio-sim.ko" "$root/lib/modules/"
  gpio_modules="configfs irq_sim gpio-sim"
elif [ $? -ne 77 ]; then
  echo "FAIL: gpio-sim did not build"
  exit 1
fi
guest_test=$(basename "$test_bin")
if [ -n "$facectl_bin" ]; then
  copy_with_libs "$facectl_bin"
  # Stripping only shrinks the initramfs; the guest test needs the binary either way.
  if command -v strip >/dev/null; then strip "$root/bin/$(basename "$facectl_bin")"; fi
  mkdir -p "$root/cfg"
  cp "$head_yaml" "$root/cfg/head.yaml"
fi

cat > "$root/init" <<INIT
#!/bin/busybox sh
/bin/busybox --install -s /bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
echo "FACECTL-QEMU: kernel \$(uname -r)"
for m in $modules; do
  insmod /lib/modules/\$m.ko && echo "FACECTL-QEMU: loaded \$m" || echo "FACECTL-QEMU: insmod \$m FAILED"
done
insmod /lib/modules/i2c-dev.ko && echo "FACECTL-QEMU: loaded i2c-dev" || echo "FACECTL-QEMU: insmod i2c-dev FAILED"
insmod /lib/modules/i2c-stub.ko chip_addr=0x40,0x41 && echo "FACECTL-QEMU: loaded i2c-stub chip_addr=0x40,0x41 (\$(cat /sys/class/i2c-adapter/*/name))" || echo "FACECTL-QEMU: insmod i2c-stub FAILED"
for m in $gpio_modules; do
  insmod /lib/modules/\$m.ko && echo "FACECTL-QEMU: loaded \$m" || echo "FACECTL-QEMU: insmod \$m FAILED"
done
[ -n "$gpio_modules" ] && mount -t configfs none /sys/kernel/config
# facectl run's GPIO test drives a Modbus TCP board on 127.0.0.1.
/sbin/iproute2-ip link set lo up
/sbin/iproute2-ip link add dev vcan0 type vcan
/sbin/iproute2-ip link set up vcan0
/sbin/iproute2-ip link add dev vcan1 type vcan
/sbin/iproute2-ip link set vcan1 mtu 72
/sbin/iproute2-ip link set up vcan1
candump -L any > /tmp/candump.log 2>&1 &
dump=\$!
sleep 0.3
/bin/$guest_test --gtest_color=no
rc=\$?
sleep 0.3
kill \$dump
frames=\$(wc -l < /tmp/candump.log)
echo "FACECTL-QEMU: candump recorded \$frames frames on vcan0 and vcan1"
echo "FACECTL-QEMU: the first frames to and from drive 1:"
grep -E " vcan0 (000|080|181|201|581|601|701|77F)#" /tmp/candump.log | head -n 40 | sed 's/^/FACECTL-QEMU: wire /'
ok=PASS
check() {
  if grep -q " \$1" /tmp/candump.log; then
    echo "FACECTL-QEMU: candump saw \$2: \$(grep -m1 " \$1" /tmp/candump.log)"
  else
    echo "FACECTL-QEMU: candump did NOT see \$2 (\$1)"
    ok=FAIL
  fi
}
check 'vcan0 601#2300140101020080' 'SDO: drive 1 RPDO1 invalidated for its remapping'
check 'vcan0 601#23001A0110004160' 'SDO: drive 1 TPDO1 entry 1 = statusword 0x6041, 16 bits'
check 'vcan0 601#2F60600008000000' 'SDO: drive 1 mode of operation = 8 (CSP)'
check 'vcan0 601#2B17100014000000' 'SDO: drive 1 producer heartbeat = 20 ms'
check 'vcan0 000#8001\$' 'NMT drive 1 to pre-operational before its remap'
check 'vcan0 601#4061600000000000' 'SDO: drive 1 mode display 0x6061 read back'
check 'vcan0 201#0200' 'RPDO1 to drive 1 with controlword quick stop on disable'
check 'vcan0 000#0101\$' 'NMT start node 1'
check 'vcan0 201#0F00' 'RPDO1 to drive 1 with controlword enable operation'
check 'vcan0 080#\$' 'SYNC'
check 'vcan0 77F#05\$' 'host heartbeat (node 127, operational)'
check 'vcan0 181#3702' 'TPDO1 from drive 1, statusword operation enabled'
check 'vcan0 101#' 'custom command frame to board 1'
check 'vcan0 184#' 'custom feedback frame from board 4'
check 'vcan0 083#1023040000000000' 'EMCY sent by cansend'
check 'vcan1 101##[0-9A-F]0103\\(9001\\)\\{12\\}000000000000\$' 'CAN FD command to board 1: seq 1, enable+reset, 12 x 4.00 deg, padded to 32 bytes'
echo "FACECTL-QEMU-RESULT: tests=\$rc candump=\$ok"
poweroff -f
INIT
chmod +x "$root/init"
pack_initramfs "$work/initramfs.gz"

# no_timer_check: on a busy host the emulated CPU can miss the kernel's
# IO-APIC timer check at boot and panic ("IO-APIC + timer doesn't work!").
echo "Booting $kernel in qemu-system-x86_64 -accel tcg with $(du -h "$work/initramfs.gz" | cut -f1) initramfs"
start=$(date +%s)
timeout 900 qemu-system-x86_64 -accel tcg -m 512 -smp 2 -nographic -no-reboot \
  -kernel "$kernel" -initrd "$work/initramfs.gz" \
  -append "console=ttyS0 panic=-1 quiet no_timer_check" </dev/null | tee "$work/console.log" | grep -aE "FACECTL|^\[ |vcan\]|uhid\]" || true
echo "QEMU ran $(( $(date +%s) - start )) s; console log: $work/console.log"
result=$(grep -a "FACECTL-QEMU-RESULT" "$work/console.log" | tr -d '\r' || true)
if [ "$result" = "FACECTL-QEMU-RESULT: tests=0 candump=PASS" ]; then
  echo "PASS: SocketCAN tests on vcan0, the hidraw gamepad test on uhid, the ALSA sequencer MIDI test, the loopback audio test, the PCA9685 test on i2c-stub and the GPIO safety I/O tests on gpio-sim in a QEMU guest; candump saw the driver's frames"
  exit 0
fi
# The filter above shows progress only; a failing assertion's message and
# the test's own figures are in the full log, so show them here.
grep -a -B3 -A8 ": Failure" "$work/console.log" | tr -d '\r' || true
echo "FAIL: ${result:-the guest did not report a result}"
exit 1
