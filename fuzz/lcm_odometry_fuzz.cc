// ODOM_<vehicle>: one odometry_t payload, decoded and validated (lcmtypes/convert.h).
#include "fuzz/fuzz_check.h"
#include "lcmtypes/convert.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  auto msg = lcmtypes::Decode<fleetmap::odometry_t>(data, static_cast<int>(size));
  if (!msg.ok()) return 0;
  core::Result<core::OdometrySample> odom = lcmtypes::FromMessage(*msg);
  if (odom.ok()) FUZZ_REQUIRE(odom->Validate().ok());
  return 0;
}
