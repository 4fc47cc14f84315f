// Every other LCM type (DIVERGENCE_, MAP_REQUEST, MERGE_REPORT, STATUS_, TEMPMAP_ACK and the
// embedded structs): lcmtypes::Decode<T> for each. These types have no shared validation in
// lcmtypes/ yet, so decoding without a crash, a leak or an unbounded allocation is the property.
// Each Decode<T> checks its type's fingerprint first, so a payload seeds the decoder of its
// own type and costs the others one comparison.
#include "fleetmap/divergence_t.hpp"
#include "fleetmap/line_match_t.hpp"
#include "fleetmap/map_request_t.hpp"
#include "fleetmap/map_tile_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/pose2d_t.hpp"
#include "fleetmap/status_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"
#include "lcmtypes/convert.h"

namespace fleetmap::fuzz {
namespace {

template <typename... T>
void DecodeEach(const uint8_t* data, size_t size) {
  (void)(lcmtypes::Decode<T>(data, static_cast<int>(size)).ok() + ...);
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fleetmap::fuzz::DecodeEach<
      fleetmap::divergence_t, fleetmap::line_match_t, fleetmap::map_request_t, fleetmap::map_tile_t,
      fleetmap::merge_report_t, fleetmap::pose2d_t, fleetmap::status_t, fleetmap::tempmap_ack_t>(
      data, size);
  return 0;
}
