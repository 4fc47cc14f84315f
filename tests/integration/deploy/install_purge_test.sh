#!/usr/bin/env bash
# Installs the Debian packages with dpkg into a throw-away root (an overlay over the host's
# own filesystem, where their libraries are already installed: nothing is downloaded and the
# host is not touched), as an operator would: runs every installed program's --help inside
# it, checks the units with systemd-analyze verify, then purges the packages and checks that
# they left nothing behind (the upper layer holds only dpkg's own records). A second round
# keeps the maps through the purge with /var/lib/fleetmap/keep-on-purge (docs/deployment.md).
#   tests/integration/deploy/install_purge_test.sh SOURCE_DIR BUILD_DIR
# Exit status: 0 passed, 1 failed, 77 skipped (not root, or no overlay file system).
set -uo pipefail
src=$(cd "${1:?usage: install_purge_test.sh SOURCE_DIR BUILD_DIR}" && pwd)
build=$(cd "${2:?usage: install_purge_test.sh SOURCE_DIR BUILD_DIR}" && pwd)
[[ $(id -u) == 0 ]] || { echo "SKIP: needs root (mount, chroot)"; exit 77; }
grep -qw overlay /proc/filesystems || { echo "SKIP: no overlay file system in this kernel"; exit 77; }
work=$(mktemp -d "${TMPDIR:-/tmp}/fleetmap_purge.XXXXXX")
root=$work/root
cleanup() {
  umount "$root/dev" 2>/dev/null
  umount "$root/proc" 2>/dev/null
  umount "$root" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }

"$src/scripts/make_debs.sh" "$build" "$work/deb" >/dev/null || { echo "FAIL: CPack"; exit 1; }
mkdir -p "$work/upper" "$work/overlay_work" "$root"
if ! mount -t overlay overlay -o "lowerdir=/,upperdir=$work/upper,workdir=$work/overlay_work" "$root"; then
  echo "SKIP: cannot mount an overlay over / here"
  exit 77
fi
mount --bind /dev "$root/dev" && mount -t proc proc "$root/proc" || { fail "cannot mount /dev, /proc"; exit 1; }
in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin "$@"; }
packages=(fleetmap-common fleetmap-agent fleetmap-aggregator fleetmap-tools fleetmap-lcmtypes-java)
mkdir -p "$root/tmp/fleetmap-debs"
cp "$work"/deb/*.deb "$root/tmp/fleetmap-debs/"
# Whatever an earlier version of the packages left on the host does not count.
for p in "${packages[@]}"; do
  dpkg-query -W "$p" >/dev/null 2>&1 && { echo "SKIP: $p is installed on this host"; exit 77; }
done
getent passwd fleetmap >/dev/null && { echo "SKIP: a fleetmap user exists on this host"; exit 77; }
[[ -e /var/lib/fleetmap ]] && { echo "SKIP: /var/lib/fleetmap exists on this host"; exit 77; }

install_all() {
  local debs=()
  for d in "$root"/tmp/fleetmap-debs/*.deb; do debs+=("/tmp/fleetmap-debs/$(basename "$d")"); done
  in_root dpkg -i "${debs[@]}" >"$work/dpkg_install.log" 2>&1 ||
    { fail "dpkg -i: $(tail -5 "$work/dpkg_install.log")"; return 1; }
  grep -qi "warning" "$work/dpkg_install.log" && fail "dpkg -i warns: $(grep -i warning "$work/dpkg_install.log")"
  return 0
}
purge_all() {
  in_root dpkg --purge "${packages[@]}" >"$work/dpkg_purge.log" 2>&1 ||
    fail "dpkg --purge: $(tail -5 "$work/dpkg_purge.log")"
}

# Round 1: install, use, purge; nothing may stay.
install_all || exit 1
in_root getent passwd fleetmap >/dev/null || fail "no fleetmap user after install"
[[ $(in_root stat -c %U "/var/lib/fleetmap/maps") == fleetmap ]] || fail "/var/lib/fleetmap/maps not the fleetmap user's"
n=0
for f in "$root"/usr/bin/fleetmap-*; do
  name=$(basename "$f")
  out=$(in_root "/usr/bin/$name" --help 2>&1) || fail "$name --help exits $? in the installed root"
  [[ ${#out} -gt 40 ]] || fail "$name --help prints too little: '$out'"
  in_root man -w "$name" >/dev/null 2>&1 || [[ -s $root/usr/share/man/man1/$name.1.gz ]] ||
    fail "no manual page for $name"
  n=$((n + 1))
done
pass "installed with dpkg; --help of $n programs inside the root"
out=$(in_root systemd-analyze verify --man=no /lib/systemd/system/fleetmap-aggregator.service \
  /lib/systemd/system/fleetmap-multicast.service 2>&1)
[[ -z $out ]] && pass "systemd-analyze verify of the installed units" || fail "systemd-analyze verify: $out"
# An aggregator's state and a map, as after a run.
in_root mkdir -p /var/lib/fleetmap/aggregator
echo map >"$root/var/lib/fleetmap/maps/static.pgm"
purge_all
# run/systemd is systemd's own runtime state: systemd-analyze verify above may leave a file
# there (systemd-units-load), a trace of the check, not of the packages.
left=$(cd "$work/upper" && find . -mindepth 1 \( -path ./tmp -o -path ./var/lib/dpkg -o -path ./var/log \
  -o -path ./var/cache -o -path ./proc -o -path ./dev -o -path ./run/systemd \) -prune -o -print |
  sed 's|^\./||' |
  grep -vxE 'var|var/lib|tmp|etc|etc/(passwd|group|shadow|gshadow|subuid|subgid)-?|usr|usr/share|usr/share/man|lib' || true)
# A file that came back to its original content (passwd after the user's removal) is no trace.
trace=""
for f in $left; do
  if [[ -f $work/upper/$f && -f /$f ]] && cmp -s "$work/upper/$f" "/$f"; then continue; fi
  [[ -d $work/upper/$f ]] && [[ -d /$f ]] && continue
  trace+="$f "
done
[[ -z $trace ]] && pass "purge left nothing behind" || fail "purge left: $trace"
for f in passwd group shadow gshadow; do
  grep -q '^fleetmap:' "$root/etc/$f" 2>/dev/null && fail "/etc/$f still names fleetmap"
done

# Round 2: the operator keeps the maps through the purge.
install_all || exit 1
echo map >"$root/var/lib/fleetmap/maps/static.pgm"
in_root chown fleetmap:fleetmap /var/lib/fleetmap/maps/static.pgm
touch "$root/var/lib/fleetmap/keep-on-purge"
purge_all
if [[ -s $root/var/lib/fleetmap/maps/static.pgm ]]; then
  owner=$(in_root stat -c %U:%G /var/lib/fleetmap/maps/static.pgm /var/lib/fleetmap/maps | sort -u)
  [[ $owner == root:root ]] && pass "keep-on-purge: the maps stay, owned by root" ||
    fail "kept maps owned by '$owner', expected root:root"
else
  fail "keep-on-purge: the maps are gone"
fi
in_root getent passwd fleetmap >/dev/null && fail "the fleetmap user survived the purge"

[[ $failures == 0 ]] && echo "PASS" || echo "FAILED: $failures"
exit $((failures > 0))
