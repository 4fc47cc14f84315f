# Sourced by ops/spy/fleetmap-spy and ops/spy/logplayer.sh: what Debian's LCM Java tools need to run
# with the fleetmap types (docs/lcm_spy.md).

# fleetmap_java_display NAME: an X display, or NAME's error.
fleetmap_java_display() {
  [[ -n "${DISPLAY:-}" ]] && return 0
  echo "$1: no X display (DISPLAY is unset): run in a desktop session or under xvfb-run" >&2
  exit 1
}

# fleetmap_java_env JAR: the LCM Java tools discover message classes in the jars named by
# CLASSPATH. Debian's lcm-spy and lcm-logplayer-gui pass -Xincgc, which Java 17 rejects unless
# told to ignore unknown VM options.
fleetmap_java_env() {
  export CLASSPATH="$1${CLASSPATH:+:${CLASSPATH}}"
  export JAVA_TOOL_OPTIONS="-XX:+IgnoreUnrecognizedVMOptions${JAVA_TOOL_OPTIONS:+ ${JAVA_TOOL_OPTIONS}}"
}
