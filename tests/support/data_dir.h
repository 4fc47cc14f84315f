// The folder of real recordings and public maps the tests read (SICK telegrams, CAN logs,
// CARMEN logs, occupancy-grid maps), which is never copied into the repository:
// $FLEETMAP_DATA_DIR when set, else the FLEETMAP_DATA_DIR the build was configured with
// (a CMake cache variable, default ../shared/data beside the source tree). A test that
// needs a part of it skips, naming the folder, when that part is absent.
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace fleetmap::testing {

inline std::filesystem::path DataDir() {
  const char* from_environment = std::getenv("FLEETMAP_DATA_DIR");
  if (from_environment != nullptr && *from_environment != '\0') return from_environment;
  return FLEETMAP_DATA_DIR_DEFAULT;
}

// DataDir()/relative, e.g. DataPath("sick/pysicktim/sim.dat").
inline std::string DataPath(const std::string& relative) { return (DataDir() / relative).string(); }

// Empty when DataDir()/relative exists; otherwise the reason to skip, naming the folder.
inline std::string MissingData(const std::string& relative) {
  const std::filesystem::path path = DataDir() / relative;
  std::error_code error;
  if (std::filesystem::exists(path, error)) return "";
  return path.string() + " is absent: the tests' data folder is " + DataDir().string() +
         " (FLEETMAP_DATA_DIR names it)";
}

}  // namespace fleetmap::testing

// Skips the current test when DataDir()/relative is absent.
#define FLEETMAP_SKIP_WITHOUT_DATA(relative)                                         \
  do {                                                                               \
    const std::string fleetmap_missing = ::fleetmap::testing::MissingData(relative); \
    if (!fleetmap_missing.empty()) GTEST_SKIP() << fleetmap_missing;                 \
  } while (0)
