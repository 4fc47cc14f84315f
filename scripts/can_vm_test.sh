#!/usr/bin/env bash
# Runs a SocketCAN test binary against a real Linux vcan interface.
#   scripts/can_vm_test.sh TEST_BINARY [ARGS...]
# Where the host kernel has AF_CAN and we may create interfaces, a host vcan is used. Otherwise
# the binary runs inside a minimal VM: Debian's linux-image-amd64 kernel under
# qemu-system-x86_64 (software emulation, no KVM needed) with a busybox initramfs holding the
# can, can-raw, can-dev and vcan modules, iproute2's ip, canplayer and candump, and the binary
# with the shared libraries it needs. The binary sees FLEETMAP_VCAN (the interface) and
# FLEETMAP_CANPLAYER (canplayer's path) in its environment.
# Prints one line "can_vm_test: PASS|FAIL|SKIP (...)" and exits 0 (pass), 1 (fail) or
# 77 (cannot run here, with the reason; ctest reports it as skipped).
# Environment: FLEETMAP_VM_TIMEOUT_S (default 480), FLEETMAP_VM_MEMORY_MB (default 1024),
# FLEETMAP_CAN_FORCE_VM=1 to use the VM even where the host has vcan.
set -euo pipefail

skip() { echo "can_vm_test: SKIP ($*)"; exit 77; }
fail() { echo "can_vm_test: FAIL ($*)"; exit 1; }

[[ $# -ge 1 ]] || { sed -n '2,12p' "$0"; exit 2; }
binary=$(readlink -f "$1")
shift
[[ -x $binary ]] || fail "test binary $binary does not exist"
timeout_s=${FLEETMAP_VM_TIMEOUT_S:-480}
memory_mb=${FLEETMAP_VM_MEMORY_MB:-1024}
canplayer=$(command -v canplayer || true)

# --- Host vcan, where the kernel has one and we are allowed to add links. ---------------------
host_vcan() {
  [[ ${FLEETMAP_CAN_FORCE_VM:-0} == 1 ]] && return 1
  [[ -n $canplayer ]] || return 1
  modprobe vcan 2>/dev/null || true
  local name=fmvcan$$
  ip link add dev "$name" type vcan 2>/dev/null || return 1
  ip link set up "$name" || { ip link delete "$name"; return 1; }
  echo "can_vm_test: host kernel has vcan; running on $name"
  local rc=0
  GTEST_COLOR=no FLEETMAP_VCAN=$name FLEETMAP_CANPLAYER=$canplayer FLEETMAP_CANDUMP=$(command -v candump) "$binary" "$@" || rc=$?
  ip link delete "$name" || true
  if ((rc == 0)); then echo "can_vm_test: PASS (host vcan)"; exit 0; fi
  fail "test binary exited with $rc on host vcan"
}
host_vcan "$@" || true

# --- Minimal VM. ----------------------------------------------------------------------------
qemu=$(command -v qemu-system-x86_64 || true)
[[ -n $qemu ]] || skip "host has no vcan and qemu-system-x86_64 is missing (apt package qemu-system-x86)"
[[ -n $canplayer ]] || skip "canplayer is missing (apt package can-utils)"
busybox=/bin/busybox
[[ -x $busybox && $(ldd "$busybox" 2>&1 || true) == *"not a dynamic"* ]] ||
  skip "a static busybox is missing (apt package busybox-static)"
command -v cpio >/dev/null || skip "cpio is missing (apt package cpio)"

# The newest installed Debian kernel whose modules are present (the running kernel may differ).
kernel=""
for k in $(ls -1 /boot/vmlinuz-* 2>/dev/null | sort -V -r); do
  version=${k#/boot/vmlinuz-}
  if [[ -d /lib/modules/$version/kernel/net/can ]]; then kernel=$k; break; fi
done
[[ -n $kernel ]] || skip "no /boot/vmlinuz-* with CAN modules in /lib/modules (apt package linux-image-amd64)"
[[ -r $kernel ]] || skip "$kernel is not readable (run as root)"
moddir=/lib/modules/$version/kernel

work=$(mktemp -d /tmp/fleetmap-canvm.XXXXXX)
trap 'rm -rf "$work"' EXIT
root=$work/root
mkdir -p "$root"/{bin,sbin,proc,sys,dev,tmp,modules,lib64,etc}

copy_with_libs() {  # copies an executable and every shared library ldd names, keeping paths
  local exe=$1 dest=$2
  cp -L "$exe" "$root$dest"
  { ldd "$exe" 2>/dev/null || true; } | { grep -o '/[^ ]*' || true; } | while read -r lib; do
    mkdir -p "$root$(dirname "$lib")"
    [[ -e $root$lib ]] || cp -L "$lib" "$root$lib"
  done
}

cp "$busybox" "$root/bin/busybox"
for applet in sh mount mkdir insmod poweroff cat echo sleep ls dmesg; do
  ln -s busybox "$root/bin/$applet"
done
copy_with_libs "$(command -v ip || echo /sbin/ip)" /sbin/ip
copy_with_libs "$canplayer" /bin/canplayer
copy_with_libs "$(command -v candump)" /bin/candump
copy_with_libs "$binary" /bin/test_binary

for module in net/can/can net/can/can-raw drivers/net/can/dev/can-dev drivers/net/can/vcan; do
  name=$(basename "$module")
  if [[ -f $moddir/$module.ko ]]; then
    cp "$moddir/$module.ko" "$root/modules/$name.ko"
  elif [[ -f $moddir/$module.ko.xz ]]; then
    xz -dc "$moddir/$module.ko.xz" >"$root/modules/$name.ko"
  elif [[ -f $moddir/$module.ko.zst ]]; then
    zstd -qdc "$moddir/$module.ko.zst" >"$root/modules/$name.ko"
  else
    skip "module $module is missing from $moddir"
  fi
done

args=""
for a in "$@"; do args+=" '${a//\'/}'"; done
cat >"$root/init" <<EOF
#!/bin/sh
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev 2>/dev/null
mount -t tmpfs tmp /tmp
for m in can can-raw can-dev vcan; do insmod /modules/\$m.ko || echo "insmod \$m failed"; done
/sbin/ip link add dev vcan0 type vcan && /sbin/ip link set up vcan0
cd /tmp
GTEST_COLOR=no FLEETMAP_VCAN=vcan0 FLEETMAP_CANPLAYER=/bin/canplayer FLEETMAP_CANDUMP=/bin/candump ASAN_OPTIONS='${ASAN_OPTIONS:-}' \
  UBSAN_OPTIONS='${UBSAN_OPTIONS:-}' /bin/test_binary $args
echo "FLEETMAP_VM_RESULT rc=\$?"
poweroff -f
EOF
chmod +x "$root/init"
(cd "$root" && find . | cpio -o -H newc --quiet | gzip -1) >"$work/initramfs.gz"

echo "can_vm_test: booting $kernel in qemu (software emulation) for $(basename "$binary")"
start=$(date +%s)
log=$work/console.log
timeout "$timeout_s" "$qemu" -nographic -no-reboot -m "$memory_mb" -smp 1 \
  -kernel "$kernel" -initrd "$work/initramfs.gz" \
  -append "console=ttyS0 quiet loglevel=3 panic=-1 rdinit=/init" </dev/null >"$log" 2>&1 || true
elapsed=$(($(date +%s) - start))
tr -d '\r' <"$log" | grep -v -e '^\s*$' -e 'SeaBIOS' -e 'iPXE' -e 'Booting from' || true
rc=$(tr -d '\r' <"$log" | sed -n 's/.*FLEETMAP_VM_RESULT rc=\([0-9]*\).*/\1/p' | tail -1)
[[ -n $rc ]] || fail "the VM gave no result within ${timeout_s} s (see the console above)"
((rc == 0)) || fail "test binary exited with $rc inside the VM (${elapsed} s)"
echo "can_vm_test: PASS (VM, kernel $version, ${elapsed} s)"
