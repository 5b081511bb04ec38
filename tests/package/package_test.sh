#!/usr/bin/env bash
# The installed LaserCNC, as a user gets it: `cmake --install` into a fresh
# prefix and `cpack -G DEB`, then the binaries run from another folder and
# find their share/ from their prefix, and the package's service unit, run
# by hand as systemd would run it, serves `lasercnc status`.
#   package_test.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

# 1. cmake --install: the layout, and share/ found from the prefix
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" --strip >/dev/null
for f in bin/lasercnc bin/lasercncd bin/lasercnc-devices lib/systemd/system/lasercncd.service \
         share/lasercnc/machines/default.toml share/lasercnc/examples/bracket.ngc \
         share/lasercnc/modbus/register_map.toml share/lasercnc/hal/sim/lasercnc_sim.hal \
         share/doc/lasercnc/README.md share/doc/lasercnc/docs/operator_guide.md \
         share/doc/lasercnc/docs/integrator_guide.md share/doc/lasercnc/docs/process_guide.md \
         share/doc/lasercnc/docs/hal.md share/doc/lasercnc/docs/reference/cli.md; do
  [ -e "$prefix/$f" ] || fail "cmake --install: no $f"
done
cd /
# the installed tree's machine is the one read: break it and the error names it
cp "$prefix/share/lasercnc/machines/default.toml" "$work/default.toml"
echo "period_us = = 1" > "$prefix/share/lasercnc/machines/default.toml"
if out=$("$prefix/bin/lasercnc" check "$prefix/share/lasercnc/examples/bracket.ngc" 2>&1); then
  fail "a broken installed machine config was not read: $out"
fi
grep -q "$prefix/share/lasercnc/machines/default.toml:1:" <<<"$out" || fail "error does not name the installed config: $out"
cp "$work/default.toml" "$prefix/share/lasercnc/machines/default.toml"
# lasercnc run from any folder: the sample job, its report a success
out=$("$prefix/bin/lasercnc" run "$prefix/share/lasercnc/examples/bracket.ngc" --json --no-progress --no-realtime) ||
  fail "installed lasercnc run failed: $out"
grep -q '"steps_match": true' <<<"$out" || fail "installed run's report: $out"

# 2. the .deb: control fields and contents
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/deb" >/dev/null
deb=$(ls "$work"/deb/lasercnc_*.deb)
info=$(dpkg-deb -I "$deb")
grep -q "^ Package: lasercnc$" <<<"$info" || fail "package name: $info"
grep -q "^ Depends: .*libqt5sql5-sqlite" <<<"$info" || fail "Depends: $info"
grep -q "postinst" <<<"$info" || fail "no postinst: $info"
contents=$(dpkg-deb -c "$deb")
for f in ./usr/bin/lasercnc ./usr/bin/lasercncd ./usr/lib/systemd/system/lasercncd.service \
         ./usr/share/lasercnc/machines/default.toml ./usr/share/applications/lasercnc-hmi.desktop; do
  grep -q " $f\$" <<<"$contents" || fail "the .deb has no $f"
done
if [ -e "$build/drivers/lasercnc.so" ]; then
  grep -q " ./usr/lib/linuxcnc/modules/lasercnc.so\$" <<<"$contents" || fail "the .deb has no HAL component"
fi

# 3. the unit's command, run by hand from the unpacked package (no systemd
# here): the daemon serves `lasercnc status`
root=$work/root
dpkg-deb -x "$deb" "$root"
exec_start=$(sed -n 's/^ExecStart=//p' "$root/usr/lib/systemd/system/lasercncd.service")
[ "${exec_start%% *}" = /usr/bin/lasercncd ] || fail "ExecStart: $exec_start"
shm=/lcnc_pkg_$$
LASERCNCD_ARGS="--no-realtime --shm $shm"
# shellcheck disable=SC2086  # the unit splits $LASERCNCD_ARGS into words, so does this
"$root${exec_start%% *}" $LASERCNCD_ARGS 2>"$work/daemon.log" &
pid=$!
trap 'kill $pid 2>/dev/null || true; wait $pid 2>/dev/null || true' EXIT
for _ in $(seq 100); do
  "$root/usr/bin/lasercnc" status --shm "$shm" >/dev/null 2>&1 && break
  sleep 0.1
done
status=$("$root/usr/bin/lasercnc" status --shm "$shm") || fail "status: $(cat "$work/daemon.log")"
grep -q "^state *idle" <<<"$status" || fail "status: $status"
kill -TERM $pid
wait $pid || fail "the daemon did not end cleanly on SIGTERM: $(cat "$work/daemon.log")"
trap - EXIT
[ ! -e "/dev/shm${shm}" ] || fail "the daemon left its segment"
echo "package: $(basename "$deb"), $(stat -c %s "$deb") bytes; installed tree and unpacked package run from /"
