// Scenario YAML (sim/scenario.h, docs/scenario.md): any text through ParseScenario, which
// must turn every malformed document into a Status naming the field (yaml-cpp exceptions
// included) and accept only what the simulator can run.
#include "fuzz/fuzz_check.h"
#include "sim/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  const std::string text(reinterpret_cast<const char*>(data), size);
  core::Result<sim::Scenario> scenario = sim::ParseScenario(text, "fuzz.yaml");
  if (!scenario.ok()) return 0;
  FUZZ_REQUIRE(!scenario->vehicles.empty() && scenario->duration_s > 0);
  for (const sim::VehicleSpec& v : scenario->vehicles) FUZZ_REQUIRE(v.route_m.size() >= 2);
  return 0;
}
