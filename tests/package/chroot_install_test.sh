#!/usr/bin/env bash
# The .deb as an integrator installs it: on a clean Debian 12 (a minimal
# bookworm made by debootstrap, with this machine's apt sources), `apt-get
# install ./lasercnc_*.deb` pulls what the package depends on and runs its
# postinst; then, inside that system, `lasercnc run` works from any folder,
# and the service's command runs as systemd would run it (as the user
# `lasercnc`, umask 0007, its options from /etc/default/lasercncd) and serves
# `lasercnc status` to an operator (user shiftop) in the group `lasercnc`.
#   chroot_install_test.sh BUILD_DIR WORK_DIR
# Needs root (chroot, mounts) and Debian's package mirror; exits 77 (a
# skip) only where it is not root, which CI always is.
set -euo pipefail
build=$1
work=$2
fail() { echo "FAIL: $*" >&2; exit 1; }
if [ "$(id -u)" -ne 0 ]; then
  echo "SKIP: the chroot install needs root" >&2
  exit 77
fi
command -v debootstrap >/dev/null || fail "debootstrap is not installed (scripts/deps.sh installs it)"

root=$work/root
mounts=()
cleanup() {
  # the daemon first (it holds the chroot's shm), then the mounts, innermost first
  [ -n "${daemon_pid:-}" ] && { kill "$daemon_pid" 2>/dev/null || true; wait "$daemon_pid" 2>/dev/null || true; }
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount -l "${mounts[i]}" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
cleanup
mkdir -p "$work"

# 1. the package, from the plain build
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/deb" >/dev/null
deb=$(ls "$work"/deb/lasercnc_*.deb)

# 2. a clean Debian 12, with the apt sources (updates, security) of this one
echo "chroot: debootstrap bookworm" >&2
mirror=$(sed -n 's/^URIs: *//p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -1)
debootstrap --variant=minbase bookworm "$root" "${mirror:-http://deb.debian.org/debian}" >"$work/debootstrap.log" 2>&1 ||
  fail "debootstrap: $(tail -5 "$work/debootstrap.log")"
if [ -d /etc/apt/sources.list.d ] && ls /etc/apt/sources.list.d/*.sources >/dev/null 2>&1; then
  rm -f "$root/etc/apt/sources.list"
  cp /etc/apt/sources.list.d/*.sources "$root/etc/apt/sources.list.d/"
fi
cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
for m in proc dev/pts dev/shm; do
  mkdir -p "$root/$m"
done
mount -t proc proc "$root/proc" && mounts+=("$root/proc")
mount -t devpts devpts "$root/dev/pts" && mounts+=("$root/dev/pts")
mount -t tmpfs -o mode=1777 tmpfs "$root/dev/shm" && mounts+=("$root/dev/shm")  # its own: no clash with this machine's /lasercnc
in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 "$@"; }

# 3. install the package as a user would
cp "$deb" "$root/tmp/"
echo "chroot: apt-get install ./$(basename "$deb")" >&2
in_root apt-get update -qq >"$work/apt.log" 2>&1 || fail "apt-get update: $(tail -5 "$work/apt.log")"
in_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "/tmp/$(basename "$deb")" \
  >>"$work/apt.log" 2>&1 || fail "apt-get install: $(tail -20 "$work/apt.log")"
in_root dpkg-query -W -f='${Status}\n' lasercnc | grep -q "install ok installed" || fail "lasercnc not installed"
in_root getent passwd lasercnc >/dev/null || fail "postinst made no user lasercnc"
in_root getent group lasercnc >/dev/null || fail "postinst made no group lasercnc"
for b in lasercnc lasercncd lasercnc-devices lasercnc-hmi; do
  [ -x "$root/usr/bin/$b" ] || fail "no /usr/bin/$b"
  in_root "/usr/bin/$b" --help >/dev/null 2>&1 || fail "$b --help: $(in_root "/usr/bin/$b" --help 2>&1 | tail -3)"
done
# every shared library the binaries need is there (the package's Depends are complete)
missing=$(in_root sh -c 'for b in /usr/bin/lasercnc*; do ldd "$b"; done' | grep "not found" || true)
[ -z "$missing" ] || fail "libraries the package does not pull in: $missing"

# 4. lasercnc run from a folder of no importance, by an operator
out=$(in_root adduser --disabled-password --gecos "" shiftop 2>&1) || fail "adduser shiftop: $out"
out=$(in_root adduser shiftop lasercnc 2>&1) || fail "adduser shiftop lasercnc: $out"
as_operator() { in_root setpriv --reuid shiftop --regid shiftop --init-groups env HOME=/home/shiftop "$@"; }
out=$(as_operator sh -c 'cd /home/shiftop && lasercnc run /usr/share/lasercnc/examples/bracket.ngc --json --no-progress --no-realtime') ||
  fail "lasercnc run in the installed system: $out"
grep -q '"steps_match": true' <<<"$out" || fail "the installed run's report: $out"

# 5. the service's command as systemd runs it (no systemd in a chroot):
# User/Group lasercnc, UMask 0007, EnvironmentFile /etc/default/lasercncd
unit=$root/usr/lib/systemd/system/lasercncd.service
[ -f "$unit" ] || unit=$root/lib/systemd/system/lasercncd.service
[ -f "$unit" ] || fail "no lasercncd.service installed"
grep -q "^User=lasercnc$" "$unit" || fail "the unit's User"
exec_start=$(sed -n 's/^ExecStart=//p' "$unit")
cp "$root/usr/share/doc/lasercnc/examples/default-lasercncd" "$root/etc/default/lasercncd"
sed -i 's/^LASERCNCD_ARGS=.*/LASERCNCD_ARGS="--no-realtime"/' "$root/etc/default/lasercncd"
# StateDirectory=lasercnc and Environment=XDG_DATA_HOME=/var/lib, as systemd does them
grep -q "^StateDirectory=lasercnc$" "$unit" || fail "the unit's StateDirectory"
grep -q "^Environment=XDG_DATA_HOME=/var/lib$" "$unit" || fail "the unit's XDG_DATA_HOME"
in_root install -d -o lasercnc -g lasercnc -m 0750 /var/lib/lasercnc
# shellcheck disable=SC2016  # $LASERCNCD_ARGS is the chroot shell's, as systemd expands it
chroot "$root" /usr/bin/env -i PATH=/usr/bin:/bin XDG_DATA_HOME=/var/lib sh -c \
  'set -a; . /etc/default/lasercncd; umask 0007; exec setpriv --reuid lasercnc --regid lasercnc --init-groups '"$exec_start" \
  >"$work/daemon.log" 2>&1 &
daemon_pid=$!
for _ in $(seq 100); do
  as_operator lasercnc status >/dev/null 2>&1 && break
  kill -0 "$daemon_pid" 2>/dev/null || fail "the service ended: $(cat "$work/daemon.log")"
  sleep 0.1
done
status=$(as_operator lasercnc status 2>&1) || fail "status as an operator: $status; daemon: $(cat "$work/daemon.log")"
grep -q "^state *idle" <<<"$status" || fail "status: $status"
# the segment is the group's, not the world's
perm=$(in_root stat -c "%U:%G %a" /dev/shm/lasercnc)
[ "$perm" = "lasercnc:lasercnc 660" ] || fail "the shared memory is $perm, not lasercnc:lasercnc 660"
# an operator runs a job through the service
out=$(as_operator sh -c 'cd /tmp && lasercnc send load /usr/share/lasercnc/examples/bracket.ngc && lasercnc send start --wait' 2>&1) ||
  fail "a job through the installed service: $out"
# a touch-off kept in the service's state folder (written when the offsets change)
out=$(as_operator sh -c 'cd /tmp && lasercnc send mdi "G10 L2 P1 X1"' 2>&1) || fail "a touch-off through the service: $out"
in_root grep -q "^5221	1$" /var/lib/lasercnc/lasercncd.var || fail "no G54 X1 in /var/lib/lasercnc/lasercncd.var after a touch-off"
kill -TERM "$daemon_pid"
wait "$daemon_pid" || fail "the service did not end cleanly on SIGTERM: $(cat "$work/daemon.log")"
daemon_pid=
echo "chroot: installed on a clean Debian 12; run, service and status work" >&2
