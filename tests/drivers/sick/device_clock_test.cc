#include "drivers/sick/device_clock.h"

#include <gtest/gtest.h>

#include <random>

namespace fleetmap::drivers::sick {
namespace {

TEST(DeviceClockTest, MapsDeviceTimeThroughJitterAndTheWrapAround) {
  DeviceClock clock;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> latency_s(0.001, 0.008);
  const double offset_s = 1.7e9;  // host = device + offset
  // Start 10 s before the 32-bit microsecond counter wraps, 15 Hz for 60 s.
  const uint64_t start_us = (uint64_t{1} << 32) - 10'000'000;
  double worst = 0.0;
  for (int i = 0; i < 900; ++i) {
    const uint64_t device_us = start_us + static_cast<uint64_t>(i) * 66'667;
    const double true_host_s = offset_s + static_cast<double>(device_us) * 1e-6;
    const double mapped = clock.Map(static_cast<uint32_t>(device_us), true_host_s + latency_s(rng));
    if (i > 50) worst = std::max(worst, std::abs(mapped - true_host_s));
  }
  EXPECT_LT(worst, 0.0015);  // within the smallest latencies seen, far below the jitter
  EXPECT_EQ(clock.resets(), 0);
}

TEST(DeviceClockTest, RestartOfTheScannerResetsTheEstimate) {
  DeviceClock clock;
  for (int i = 0; i < 20; ++i) clock.Map(500'000'000 + i * 66'667, 100.0 + i * 0.066667);
  // The scanner rebooted: its counter starts again near zero, 5 s later on the host.
  const double mapped = clock.Map(1'000, 106.4);
  EXPECT_EQ(clock.resets(), 1);
  EXPECT_NEAR(mapped, 106.4, 1e-9);
  EXPECT_NEAR(clock.ToHost(67'667), 106.4 + 0.066667, 1e-6);
}

TEST(DeviceClockTest, OptionsNameTheBadField) {
  DeviceClockOptions o;
  o.window_samples = 0;
  EXPECT_NE(o.Validate().message().find("window_samples"), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::drivers::sick
