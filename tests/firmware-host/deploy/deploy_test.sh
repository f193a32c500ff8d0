#!/bin/bash
# The deployment (firmware-host/deploy/): `cmake --install` of this build tree
# into a temporary DESTDIR puts every file where the unit, the package and the
# binary expect it; the installed binary reads the installed configs, not
# this source tree; the installed unit passes `systemd-analyze verify`; the
# sysusers file makes the facectl user with its device groups; and
# `cpack -G DEB` packages it all, with the configs as conffiles and the
# maintainer scripts that do not start the service.
#
# It builds nothing: it needs the tree's facectl built (ctest runs after the
# build). Exit 77 (skipped) only for the .deb part, when the tree is not
# configured with the prefix /usr that a package needs.
#
# Usage: deploy_test.sh BUILD_DIR SOURCE_DIR PREFIX BINDIR CONFIG_DIR UNIT_DIR UDEV_DIR SYSUSERS_DIR
#   BINDIR and CONFIG_DIR absolute (CMAKE_INSTALL_FULL_BINDIR, FACECTL_INSTALL_CONFIG_DIR);
#   UNIT_DIR, UDEV_DIR, SYSUSERS_DIR relative to PREFIX.
set -uo pipefail
build=$1 source=$2 prefix=$3 bindir=$4 confdir=$5 unitdir=$prefix/$6 udevdir=$prefix/$7
sysusersdir=$prefix/$8

# Outside the build tree: a binary inside it counts as the build tree's
# (firmware-host/config/config_location.hpp).
tmp=$(mktemp -d /tmp/facectl-test-deploy-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
root=$tmp/root
fail() { echo "FAIL: $*"; exit 1; }

# ---- cmake --install into DESTDIR
DESTDIR=$root cmake --install "$build" > "$tmp/install.log" 2>&1 ||
  fail "cmake --install: $(tail -5 "$tmp/install.log")"
for f in "$bindir/facectl" "$confdir/facectl.yaml" "$confdir/heads/default/head.yaml" \
         "$confdir/fap/visemes.yaml" "$unitdir/facectl.service" "$sysusersdir/facectl.conf" \
         "$udevdir/60-facectl.rules"; do
  [ -f "$root$f" ] || fail "not installed: $f"
done
[ -x "$root$bindir/facectl" ] || fail "$bindir/facectl is not executable"
diff -r "$source/config" "$root$confdir" > "$tmp/diff" || fail "the installed configs differ from config/: $(head -5 "$tmp/diff")"
echo "install: binary, whole config tree, unit, sysusers and udev rules in place"

# ---- the installed binary defaults to the installed configs; the build tree's to the source's
installed_help=$(env -u FACECTL_CONFIG "$root$bindir/facectl" run --help 2>&1) ||
  fail "installed facectl run --help: $installed_help"
grep -qF "shipped $confdir/facectl.yaml" <<< "$installed_help" ||
  fail "the installed binary does not default to $confdir/facectl.yaml: $(grep -F -- --config <<< "$installed_help")"
build_help=$(env -u FACECTL_CONFIG "$build/firmware-host/facectl" run --help 2>&1)
grep -qF "shipped $source/config/facectl.yaml" <<< "$build_help" ||
  fail "the build tree's binary does not default to the source tree's config: $(grep -F -- --config <<< "$build_help")"
# The installed config tree is whole: the installed binary runs the default
# head from it (its paths are relative to the runtime file).
"$root$bindir/facectl" run --config "$root$confdir/facectl.yaml" --duration 0.3 \
  > "$tmp/run.log" 2>&1 || fail "installed facectl run on the installed configs: $(tail -5 "$tmp/run.log")"
grep -q "final state IDLE" "$tmp/run.log" || fail "no clean run: $(tail -5 "$tmp/run.log")"
echo "binary: the installed copy reads $confdir, the build tree's reads $source/config"

# ---- the unit. systemd 252's `verify --root` does not apply to the
# ExecStart= check (it looks for the binary on this machine), so verify a copy
# whose ExecStart= names the DESTDIR's binary, after checking the original
# names the installed one.
unit=$root$unitdir/facectl.service
grep -qx "ExecStart=$bindir/facectl serve --config $confdir/facectl.yaml" "$unit" ||
  fail "unexpected ExecStart: $(grep ExecStart "$unit")"
for key in Type=notify NotifyAccess=main User=facectl "AmbientCapabilities=CAP_SYS_NICE CAP_IPC_LOCK" \
           "CapabilityBoundingSet=CAP_SYS_NICE CAP_IPC_LOCK" LimitMEMLOCK=infinity \
           NoNewPrivileges=yes ProtectSystem=strict StateDirectory=facectl LogsDirectory=facectl; do
  grep -qx "$key" "$unit" || fail "the unit lacks $key"
done
mkdir -p "$tmp/verify"
sed "s|^ExecStart=$bindir/facectl|ExecStart=$root$bindir/facectl|" "$unit" > "$tmp/verify/facectl.service"
verify_out=$(systemd-analyze verify --man=no "$tmp/verify/facectl.service" 2>&1) ||
  fail "systemd-analyze verify: $verify_out"
# It exits 0 on some findings it only prints (an unknown key is a warning).
[ -z "$verify_out" ] || fail "systemd-analyze verify printed: $verify_out"
echo "unit: systemd-analyze verify passes"

# ---- sysusers: the user and its groups, in an empty root with Debian's groups.
# An empty /etc with Debian's dialout and plugdev groups (base-passwd).
seed_etc() {
  mkdir -p "$1/etc"
  printf 'dialout:x:20:\nplugdev:x:46:\n' > "$1/etc/group"
  : > "$1/etc/passwd"
}
seed_etc "$tmp/sysroot"
systemd-sysusers --root="$tmp/sysroot" "$root$sysusersdir/facectl.conf" > "$tmp/sysusers.log" 2>&1 ||
  fail "systemd-sysusers: $(cat "$tmp/sysusers.log")"
grep -q '^facectl:x:[0-9]*:[0-9]*:.*:/var/lib/facectl:/usr/sbin/nologin$' "$tmp/sysroot/etc/passwd" ||
  fail "no facectl user: $(cat "$tmp/sysroot/etc/passwd")"
for g in dialout plugdev gpio; do
  grep -qE "^$g:x:[0-9]+:(.*,)?facectl(,.*)?$" "$tmp/sysroot/etc/group" ||
    fail "facectl is not in group $g: $(cat "$tmp/sysroot/etc/group")"
done
grep -qE '^facectl:x:[0-9]+:' "$tmp/sysroot/etc/group" || fail "no facectl group"
grep -q '^dialout:x:20:' "$tmp/sysroot/etc/group" || fail "sysusers changed dialout's gid"
# Every group the udev rules give devices to exists after sysusers.
for g in $(grep -oE 'GROUP="[^"]+"' "$root$udevdir/60-facectl.rules" | cut -d'"' -f2 | sort -u); do
  grep -q "^$g:" "$tmp/sysroot/etc/group" || fail "udev rules name group $g, which sysusers does not make"
done
echo "sysusers: facectl in dialout, plugdev, gpio; every udev rule's group exists"

# ---- cpack -G DEB
if [ "$prefix" != /usr ]; then
  echo "deb: skipped: this tree's prefix is $prefix, a package needs -DCMAKE_INSTALL_PREFIX=/usr"
  exit 77
fi
(cd "$tmp" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$tmp/pkg") > "$tmp/cpack.log" 2>&1 ||
  fail "cpack: $(tail -10 "$tmp/cpack.log")"
deb=$(ls "$tmp"/pkg/facectl_*.deb 2>/dev/null | head -1)
[ -n "$deb" ] || fail "cpack made no facectl_*.deb: $(tail -5 "$tmp/cpack.log")"
dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./|/|' > "$tmp/contents"
for f in "$bindir/facectl" "$unitdir/facectl.service" "$udevdir/60-facectl.rules" \
         "$sysusersdir/facectl.conf" "$confdir/facectl.yaml" "$confdir/heads/default/skin.obj"; do
  grep -qx "$f" "$tmp/contents" || fail "$f is not in $(basename "$deb")"
done
grep -q "^$root\|/usr/local" "$tmp/contents" && fail "the package holds staging or /usr/local paths"
info=$(dpkg-deb -I "$deb") || fail "dpkg-deb -I"
grep -q '^ Package: facectl$' <<< "$info" || fail "package name: $info"
grep -qE '^ Depends: .*libc6' <<< "$info" || fail "no computed Depends (shlibdeps): $info"
grep -qE '^ Depends: .*systemd' <<< "$info" || fail "Depends lacks systemd: $info"
mkdir "$tmp/control"
dpkg-deb -e "$deb" "$tmp/control"
(cd "$source/config" && find . -type f | sed "s|^\.|$confdir|" | sort) > "$tmp/want-conffiles"
sort "$tmp/control/conffiles" | diff "$tmp/want-conffiles" - > "$tmp/diff" ||
  fail "conffiles is not every installed config: $(cat "$tmp/diff")"
for s in postinst prerm postrm; do
  [ -x "$tmp/control/$s" ] || fail "no executable $s"
  sh -n "$tmp/control/$s" || fail "$s: syntax"
done
grep -q 'systemd-sysusers' "$tmp/control/postinst" || fail "postinst does not run systemd-sysusers"
grep -q 'udevadm control --reload' "$tmp/control/postinst" || fail "postinst does not reload udev"
grep -vE '^[[:space:]]*#' "$tmp/control/postinst" | grep -qE 'systemctl (start|restart|enable|try-restart)|deb-systemd-invoke' &&
  fail "postinst enables, starts or restarts the service"
echo "deb: $(basename "$deb"): binary, unit, udev rules, configs as conffiles; postinst starts nothing"

# ---- the maintainer scripts for real: install, upgrade over an edited
# conffile, purge, all into a temporary root (dpkg --root with the scripts
# run outside a chroot, DPKG_ROOT set: they touch only that root).
if [ "$(id -u)" -ne 0 ]; then
  echo "dpkg --root: not run (needs root)"
  exit 0
fi
dr=$tmp/dpkgroot
mkdir -p "$dr/var/lib/dpkg/info" "$dr/var/lib/dpkg/updates"
: > "$dr/var/lib/dpkg/status"
seed_etc "$dr"
dpkg_r() { dpkg --root="$dr" --force-script-chrootless --force-depends --log=/dev/null "$@"; }
dpkg_r -i "$deb" > "$tmp/dpkg.log" 2>&1 || fail "dpkg -i: $(tail -5 "$tmp/dpkg.log")"
grep -q '^facectl:' "$dr/etc/passwd" || fail "postinst made no facectl user"
grep -qE '^gpio:x:[0-9]+:facectl$' "$dr/etc/group" || fail "postinst: facectl not in gpio"
echo "# edited on site" >> "$dr$confdir/facectl.yaml"
dpkg_r --force-confold -i "$deb" > "$tmp/dpkg.log" 2>&1 || fail "dpkg -i again: $(tail -5 "$tmp/dpkg.log")"
grep -q '^# edited on site$' "$dr$confdir/facectl.yaml" || fail "the upgrade lost an edited conffile"
mkdir -p "$dr/var/log/facectl" "$dr/var/lib/facectl"
dpkg_r --purge facectl > "$tmp/dpkg.log" 2>&1 || fail "dpkg --purge: $(tail -5 "$tmp/dpkg.log")"
for gone in "$bindir/facectl" "$confdir/facectl.yaml" /var/log/facectl /var/lib/facectl; do
  [ ! -e "$dr$gone" ] || fail "$gone is left after purge"
done
echo "dpkg --root: install makes the user, an upgrade keeps an edited conffile, purge removes all"
