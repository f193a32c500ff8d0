# Shell functions for building a QEMU guest's initramfs, sourced by
# tests/drivers/qemu/run_in_qemu.sh and scripts/measure_rt_in_qemu.sh.
# Both expect $root (the initramfs tree) to be set.

# Copies each binary to $root/bin and every shared library ldd names to the
# same path under $root.
copy_with_libs() {
  for bin in "$@"; do
    cp "$bin" "$root/bin/"
    copy_libs "$bin"
  done
}

copy_libs() {  # binary
  ldd "$1" | grep -o '/[^ ]*' | while read -r lib; do
    mkdir -p "$root$(dirname "$lib")"
    cp -L "$lib" "$root$lib"
  done
}

# Packs $root into the gzipped newc archive QEMU's -initrd takes.
pack_initramfs() {  # output.gz
  (cd "$root" && find . | /bin/busybox cpio -o -H newc 2>/dev/null | gzip -1 > "$1")
}
