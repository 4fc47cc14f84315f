// For tests that talk over real LCM UDP multicast on loopback: makes sure the host can (a
// route for 224.0.0.0/4 on lo and a large enough receive buffer, set up by
// scripts/setup_multicast.sh when the test runs as root) and says why not otherwise, so that
// a test skips with a clear message instead of failing or hanging.
#pragma once
#include <cstdlib>
#include <lcm/lcm-cpp.hpp>
#include <string>

namespace fleetmap::testing {

// Returns true when `url` can be used; otherwise fills `why`.
inline bool MulticastReady(const std::string& url, std::string* why) {
  {
    lcm::LCM probe(url);
    if (probe.good()) return true;
  }
  const std::string script = std::string(FLEETMAP_SOURCE_DIR) + "/scripts/setup_multicast.sh";
  const int rc = std::system((script + " >/dev/null 2>&1").c_str());
  lcm::LCM probe(url);
  if (probe.good()) return true;
  *why = "LCM multicast is not usable on this host (" + url + "): " + script +
         (rc == 0 ? " ran but LCM still fails" : " failed (it needs root)");
  return false;
}

}  // namespace fleetmap::testing

// In a TEST body: skips the test, with the reason, when multicast is not usable.
#define FLEETMAP_REQUIRE_MULTICAST(url)                                     \
  do {                                                                      \
    std::string fleetmap_multicast_why;                                     \
    if (!::fleetmap::testing::MulticastReady(url, &fleetmap_multicast_why)) \
      GTEST_SKIP() << fleetmap_multicast_why;                               \
  } while (0)
