// The agent's STATUS reports what the process costs: CPU time that grows with work, and the
// resident memory now (not the peak), which follows memory the process touches.
#include "vehicle_agent/node/process_usage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace fleetmap::vehicle_agent::node {
namespace {

int64_t Value(const NamedCounters& counters, const std::string& name) {
  const int64_t v = CounterValue(counters, name);
  EXPECT_GE(v, 0) << name << " missing";
  return v;
}

TEST(ProcessUsageTest, CpuTimeGrowsWithWork) {
  const int64_t before = Value(ProcessUsageCounters(), "cpu_time_us");
  volatile double sink = 0;
  int64_t after = before;
  // Work until the clock (10 ms ticks on some kernels) has moved: bounded by iterations.
  for (int round = 0; round < 2000 && after == before; ++round) {
    for (int i = 0; i < 200000; ++i) sink = sink + std::sqrt(static_cast<double>(i));
    after = Value(ProcessUsageCounters(), "cpu_time_us");
  }
  EXPECT_GT(after, before);
}

TEST(ProcessUsageTest, ResidentMemoryFollowsTouchedMemory) {
  const int64_t before_kb = Value(ProcessUsageCounters(), "rss_kb");
  EXPECT_GT(before_kb, 0);
  int64_t with_kb = 0;
  {
    std::vector<char> block(64 << 20, 1);  // 64 MB, every page written
    with_kb = Value(ProcessUsageCounters(), "rss_kb");
    EXPECT_EQ(block[block.size() / 2], 1);
  }
  EXPECT_GE(with_kb - before_kb, 60 * 1024);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
