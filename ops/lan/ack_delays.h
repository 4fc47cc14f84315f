// How long vehicles waited for the aggregator's answer to a temporary map, from recorded
// uplink and downlink logs: for each final TEMPMAP_ACK (MERGED, REJECTED or DUPLICATE), the
// time from the last tile of that map (vehicle, sequence) logged before it to the ack's own
// logging. Both logs must be recorded on one host (one clock). A final ack whose map has no
// tile in the logs (sent before the recording began) is counted apart, not timed.
#pragma once

#include <string>
#include <vector>

#include "ops/lan/lan_log.h"

namespace fleetmap::ops::lan {

struct AckDelays {
  std::vector<double> delays_s;  // one per final ack timed, in log order
  int untimed = 0;               // final acks of maps with no tile logged before them
};

AckDelays MeasureAckDelays(const std::vector<LogMessage>& messages);

// `acks.count`, `acks.untimed`, `acks.delay_s.median`, `.p95` and `.max` lines. With no ack
// timed, the delays are not printed: a figure over nothing is no figure.
std::string AckDelayFigureLines(const AckDelays& delays);

}  // namespace fleetmap::ops::lan
