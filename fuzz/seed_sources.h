// The seed writer's sources, one function per family of targets. Each adds the seeds of its
// targets to the corpus: outputs of our own encoders (seeds_transport.cc, seeds_messages.cc,
// seeds_maps.cc) and, where real recordings exist, extracts of them (seeds_sensors.cc: SICK
// captures, the candump log and the CARMEN logs of the data folder, never copied into the repo).
#pragma once

#include <filesystem>
#include <vector>

#include "core/scan.h"
#include "fuzz/seed_corpus.h"

namespace fleetmap::fuzz {

struct SeedInputs {
  std::filesystem::path source_dir;  // the repository (shipped worlds and maps)
  std::filesystem::path data_dir;    // FLEETMAP_DATA_DIR; may be missing
};

// Real laser scans (SICK recordings and CARMEN logs), a few per file, for the scan messages
// and the S300 telegrams; empty without the data folder.
std::vector<core::LaserScan> RealScans(const SeedInputs& in);

// lcm_tempmap_tile, lcm_map_keyframe, lcm_map_delta, temp_map_assembler, map_replica,
// map_codec, tile_delta, temp_map_file.
void AddTransportSeeds(SeedCorpus& corpus);
// lcm_laser_scan, lcm_odometry, lcm_pose, lcm_messages.
void AddMessageSeeds(SeedCorpus& corpus, const std::vector<core::LaserScan>& real_scans);
// cola_a, cola_b, lmd_scandata, s300.
void AddSickSeeds(SeedCorpus& corpus, const SeedInputs& in,
                  const std::vector<core::LaserScan>& real_scans);
// candump, carmen.
void AddLogSeeds(SeedCorpus& corpus, const SeedInputs& in);
// pgm, map_load, scenario.
void AddMapSeeds(SeedCorpus& corpus, const SeedInputs& in);
// Every input a target once crashed on (tests/data/fuzz/<target>/), so that each fuzz run
// replays them before mutating anything.
void AddRegressionInputs(SeedCorpus& corpus, const SeedInputs& in);

}  // namespace fleetmap::fuzz
