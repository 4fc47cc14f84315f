// POSE_<vehicle> (and EXTPOSE_, TRUTH_): one pose_with_covariance_t payload, decoded and
// validated (lcmtypes/convert.h).
#include "fuzz/fuzz_check.h"
#include "lcmtypes/convert.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  auto msg = lcmtypes::Decode<fleetmap::pose_with_covariance_t>(data, static_cast<int>(size));
  if (!msg.ok()) return 0;
  core::Result<core::PoseEstimate> pose = lcmtypes::FromMessage(*msg);
  if (pose.ok()) FUZZ_REQUIRE(pose->Validate().ok());
  return 0;
}
