# shellcheck shell=bash disable=SC2034  # sets variables for the scripts that source it
# Sourced by every script that starts the fleet's processes (scripts/fleet_run.sh, the LAN
# experiment, the benchmarks, the operations and fleet tests): the one place that writes the
# multicast URLs and the agent's and aggregator's command lines, so that a flag added to the
# fleet's launch is added once.

# fleet_url ADDRESS PORT [TTL]: an LCM multicast URL. TTL 0 (the default) keeps the traffic
# on this host, 1 crosses one LAN. The 8 MiB receive buffer holds a burst of map tiles: LCM
# loses a whole message for one lost packet (scripts/setup_multicast.sh raises rmem_max).
fleet_url() { printf 'udpm://%s:%s?ttl=%s&recv_buf_size=8388608\n' "$1" "$2" "${3:-0}"; }

# fleet_links PORT [TTL] [PREFIX]: sets `uplink`, `downlink` and `sensor`: the groups
# PREFIX.67, PREFIX.68 and PREFIX.69 (PREFIX 239.255.76 unless given) on ports PORT, PORT+1 and
# PORT+2. One group per direction: no vehicle receives the other vehicles' temporary maps, the
# aggregator not their scans. The sensor group stays on the vehicle: its TTL is always 0.
fleet_links() {
  local port=$1 ttl=${2:-0} prefix=${3:-239.255.76}
  uplink=$(fleet_url "$prefix.67" "$port" "$ttl")
  downlink=$(fleet_url "$prefix.68" $((port + 1)) "$ttl")
  sensor=$(fleet_url "$prefix.69" $((port + 2)) 0)
}

# fleet_static_map BIN SCENARIO [MAP]: the static map the scenario's vehicles start from.
fleet_static_map() {
  "$1/fleetmap-sim" --scenario "$2" ${3:+--map "$3"} --list-vehicles | sed -n 's/^map //p'
}

# fleet_vehicles BIN SCENARIO [MAP]: one line per vehicle, `ID X Y THETA MOUNT_X MOUNT_Y
# MOUNT_THETA` (metres, radians): where it starts and where its scanner sits on it.
fleet_vehicles() {
  "$1/fleetmap-sim" --scenario "$2" ${3:+--map "$3"} --list-vehicles | grep -v '^map '
}

# fleet_agent_command BIN VEHICLE_LINE MAP STATE_DIR: sets the array `agent_command`, the agent
# of one vehicle (a line of fleet_vehicles) on the links fleet_links set. Callers append their
# own flags (--final-map, --quiet, --key-file) and the way they run it (namespace, log file).
fleet_agent_command() {
  local id x y theta mx my mtheta
  read -r id x y theta mx my mtheta <<<"$2"
  agent_command=("$1/fleetmap-agent" --vehicle-id "$id" --map "$3" --initial-pose "$x,$y,$theta"
    --scanner-mount "$mx,$my,$mtheta" --sensor-url "$sensor" --uplink-url "$uplink"
    --downlink-url "$downlink" --state-dir "$4")
}

# fleet_aggregator_command BIN MAP [STATE_DIR]: sets the array `aggregator_command` likewise;
# without a state folder the aggregator keeps its map in memory only.
fleet_aggregator_command() {
  aggregator_command=("$1/fleetmap-aggregator" --map "$2" ${3:+--state-dir "$3"}
    --uplink-url "$uplink" --downlink-url "$downlink")
}
