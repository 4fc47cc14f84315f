#!/usr/bin/env bash
# Prepares this host for LCM UDP multicast on loopback (docs/channels.md, "What LCM needs"):
#  - a route for 224.0.0.0/4: without one, lcm::LCM is not good() ("LCM requires a valid
#    multicast route"), and on a host with no default route there is none;
#  - multicast enabled on lo, so that the kernel loops our datagrams back to local sockets;
#  - net.core.rmem_max raised to 8 MiB, so that LCM's recv_buf_size=8388608 is granted; with
#    the default 208 KiB, a burst of map tiles overflows the socket and whole messages are lost.
# Safe to run again. Needs root; without it, says what to run and exits 1.
set -u
have_route() { ip route show table all 2>/dev/null | grep -qE '^(multicast )?224\.0\.0\.0/4|^default'; }
rmem=$(cat /proc/sys/net/core/rmem_max 2>/dev/null || echo 0)
if [ "$(id -u)" != 0 ]; then
  if have_route && [ "$rmem" -ge 8388608 ]; then exit 0; fi
  echo "setup_multicast: needs root; run: sudo $0" >&2
  exit 1
fi
ip link set lo multicast on
# Two tests may run this at once: a lost race to add the route is fine if the route is there.
ip route show 224.0.0.0/4 dev lo 2>/dev/null | grep -q . || ip route add 224.0.0.0/4 dev lo 2>/dev/null ||
  ip route show 224.0.0.0/4 dev lo | grep -q .
if [ "$rmem" -lt 8388608 ]; then sysctl -q -w net.core.rmem_max=8388608; fi
if [ "$(cat /proc/sys/net/core/rmem_default)" -lt 2097152 ]; then
  sysctl -q -w net.core.rmem_default=2097152
fi
echo "setup_multicast: lo carries multicast (224.0.0.0/4), rmem_max $(cat /proc/sys/net/core/rmem_max) B"
