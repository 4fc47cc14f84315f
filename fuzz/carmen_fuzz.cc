// CARMEN logs (eval/carmen/carmen_log.h), the format of the SLAM benchmark datasets: any text,
// line by line as ReadCarmenLog reads a file, then odometry interpolated at the scan times.
#include "eval/carmen/carmen_log.h"
#include "fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  const std::string text(reinterpret_cast<const char*>(data), size);
  eval::carmen::CarmenLog log;
  const eval::carmen::CarmenReadOptions options;
  int line_number = 0;
  for (size_t pos = 0; pos < text.size();) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    const size_t lasers = log.lasers.size(), odometry = log.odometry.size();
    const core::Status s = eval::carmen::ParseCarmenLine(line, line_number, options, log);
    // A refused line adds nothing.
    if (!s.ok()) FUZZ_REQUIRE(log.lasers.size() == lasers && log.odometry.size() == odometry);
  }
  (void)eval::carmen::InterpolateOdometryAtScans(log);
  return 0;
}
