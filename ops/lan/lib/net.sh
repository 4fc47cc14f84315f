# shellcheck shell=bash
# The LAN of network namespaces for the LAN experiments (sourced by fleetmap-lan-experiment).
#
#   bridge namespace  <prefix>-br:  bridge br0 (mcast_snooping 0), one port p<k> per host
#   host namespaces   <prefix>-srv, <prefix>-v1 ...: interface lan0 (the other end of p<k>),
#                     address 10.213.0.<k>/24 (server .1, vehicle i .(10+i)), lo up, and the
#                     multicast route 224.0.0.0/4 dev lan0
# Nothing touches the host's own network: every interface lives in a namespace made here,
# and the addresses exist only inside them.
#
# Link profiles (tc on both ends of a vehicle's veth pair: lan0 egress is its uplink, p<k>
# egress in the bridge namespace what reaches it; the server's link is always wired, the
# aggregator being cabled to the access point):
#   wired  1 Gbit/s (tbf)
#   wifi   20 Mbit/s (tbf) and 2% of the packets dropped
#   bad    20 Mbit/s (tbf) and 30% of the packets dropped
# Without tc netem, which not every kernel has ("Specified qdisc kind is unknown"): the rate
# is a tbf below an HTB root, and the loss an HTB class whose pfifo holds 0 packets, fed by a
# classic-BPF filter that matches a random share of packets (as scripts/fleet_run.sh --loss).
# No delay or jitter: see docs/lan_experiments.md.

LAN_NAMESPACES=()  # every namespace made, deleted by lan_destroy
LAN_SHAPED=()      # "NS DEV" of every shaped interface

lan_ns() { echo "$LAN_PREFIX-$1"; }  # lan_ns br|srv|v1 ...

# lan_netns_add NS: a namespace without IPv6, whose router solicitations and multicast
# listener reports would otherwise add a few packets to the counters.
lan_netns_add() {
  ip netns add "$1" || return 1
  LAN_NAMESPACES+=("$1")
  ip netns exec "$1" sysctl -q -w net.ipv6.conf.all.disable_ipv6=1 \
    net.ipv6.conf.default.disable_ipv6=1 >/dev/null 2>&1 || true
}

# lan_create N: the bridge, the server and N vehicle hosts.
lan_create() {
  local n=$1 br k
  br=$(lan_ns br)
  lan_netns_add "$br" || return 1
  ip -n "$br" link set lo up
  ip -n "$br" link add name br0 type bridge mcast_snooping 0 || return 1
  ip -n "$br" link set br0 up
  lan_add_host srv 1 || return 1
  for ((k = 1; k <= n; ++k)); do lan_add_host "v$k" $((10 + k)) || return 1; done
}

# lan_add_host NAME OCTET
lan_add_host() {
  local name=$1 octet=$2 ns br
  ns=$(lan_ns "$name")
  br=$(lan_ns br)
  lan_netns_add "$ns" || return 1
  ip -n "$br" link add name "p$name" type veth peer name lan0 netns "$ns" || return 1
  ip -n "$br" link set "p$name" master br0
  ip -n "$br" link set "p$name" up
  ip -n "$ns" link set lo up
  ip -n "$ns" addr add "10.213.0.$octet/24" dev lan0
  ip -n "$ns" link set lan0 multicast on
  ip -n "$ns" link set lan0 up
  ip -n "$ns" route add 224.0.0.0/4 dev lan0
}

# The profile's rate and loss share: "RATE LOSS".
lan_profile() {
  case $1 in
    wired) echo "1gbit 0" ;;
    wifi) echo "20mbit 0.02" ;;
    bad) echo "20mbit 0.30" ;;
    *) return 1 ;;
  esac
}

# lan_shape NS DEV PROFILE: HTB root; class 1:10 (default) -> tbf at the rate; with loss,
# class 1:20 -> pfifo of 0 packets, fed by a random classic-BPF filter.
lan_shape() {
  local ns=$1 dev=$2 rate loss threshold burst
  read -r rate loss < <(lan_profile "$3") || return 1
  burst=$([ "$rate" = 1gbit ] && echo 1mb || echo 64kb)
  ip netns exec "$ns" tc qdisc add dev "$dev" root handle 1: htb default 10 r2q 10000 || return 1
  ip netns exec "$ns" tc class add dev "$dev" parent 1: classid 1:10 htb rate 10gbit
  ip netns exec "$ns" tc qdisc add dev "$dev" parent 1:10 handle 10: tbf rate "$rate" \
    burst "$burst" latency 200ms || return 1
  LAN_SHAPED+=("$ns $dev")
  [ "$loss" != 0 ] || return 0
  threshold=$(awk -v p="$loss" 'BEGIN { printf "%.0f", p * 4294967296 }')
  ip netns exec "$ns" tc class add dev "$dev" parent 1: classid 1:20 htb rate 10gbit
  ip netns exec "$ns" tc qdisc add dev "$dev" parent 1:20 handle 20: pfifo limit 0
  # ld rand (SKF_AD_OFF + SKF_AD_RANDOM); jge threshold ? no match : match.
  ip netns exec "$ns" tc filter add dev "$dev" parent 1: prio 1 bpf bytecode \
    "4,32 0 0 4294963256,53 1 0 $threshold,6 0 0 4294967295,6 0 0 0" classid 1:20
}

# lan_shape_all N PROFILE: every vehicle link both ways; the server's link wired.
lan_shape_all() {
  local n=$1 profile=$2 k br
  br=$(lan_ns br)
  lan_shape "$(lan_ns srv)" lan0 wired && lan_shape "$br" psrv wired || return 1
  for ((k = 1; k <= n; ++k)); do
    lan_shape "$(lan_ns "v$k")" lan0 "$profile" && lan_shape "$br" "pv$k" "$profile" || return 1
  done
}

# Packets the tc qdiscs dropped, all shaped interfaces together: "LOSS_DROPS RATE_DROPS"
# (the random filter's pfifo 20:, and tbf 10: when the rate was exceeded).
lan_tc_drops() {
  local entry loss=0 rate=0 l r
  for entry in "${LAN_SHAPED[@]}"; do
    read -r l r < <(ip netns exec ${entry% *} tc -s qdisc show dev ${entry#* } | awk '
      /^qdisc / { q = $2 " " $3 }
      /dropped/ { for (i = 1; i <= NF; ++i) if ($i == "(dropped") d = $(i + 1); gsub(",", "", d)
                  if (q == "pfifo 20:") l += d; if (q == "tbf 10:") r += d }
      END { print l + 0, r + 0 }')
    loss=$((loss + l)) rate=$((rate + r))
  done
  echo "$loss $rate"
}

# lan_counters HOST...: a line "HOST tx_bytes rx_bytes tx_packets rx_packets" per host, from
# the kernel's counters of its lan0 (/sys/class/net/lan0/statistics inside its namespace).
lan_counters() {
  local host
  for host in "$@"; do
    # shellcheck disable=SC2016
    echo "$host $(ip netns exec "$(lan_ns "$host")" sh -c 'cd /sys/class/net/lan0/statistics &&
      echo $(cat tx_bytes) $(cat rx_bytes) $(cat tx_packets) $(cat rx_packets)')"
  done
}

# lan_destroy: ends the processes still in our namespaces (by pid: they can only be ours),
# then deletes the namespaces, which takes the veths and the bridge with them.
lan_destroy() {
  local ns pids
  for ns in "${LAN_NAMESPACES[@]}"; do
    pids=$(ip netns pids "$ns" 2>/dev/null)
    [ -z "$pids" ] || kill -KILL $pids 2>/dev/null || true
  done
  for ns in "${LAN_NAMESPACES[@]}"; do ip netns del "$ns" 2>/dev/null || true; done
  LAN_NAMESPACES=() LAN_SHAPED=()
}

# lan_remove_stale: namespaces fmlan-<pid>-* of runs whose process is gone (killed with
# SIGKILL, which no trap sees).
lan_remove_stale() {
  local ns pid
  for ns in $(ip netns list 2>/dev/null | awk '{ print $1 }' | grep '^fmlan-[0-9]*-'); do
    pid=${ns#fmlan-}
    pid=${pid%%-*}
    kill -0 "$pid" 2>/dev/null && continue
    echo "fleetmap-lan-experiment: removing stale namespace $ns" >&2
    ip netns del "$ns" 2>/dev/null || true
  done
}
