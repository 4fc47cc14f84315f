// fleetmap-fuzz-seeds: writes the seed corpora of the fuzz targets (fuzz/*_fuzz.cc), one
// folder per target, from our own encoders and from the real recordings in the data folder
// (FLEETMAP_DATA_DIR).
// The recordings are read where they are and never copied into the repository; without them
// the corpora hold our own outputs only. The build runs it (fuzz/CMakeLists.txt).
#include <cstdio>
#include <cstring>

#include "fuzz/seed_sources.h"

namespace fleetmap::fuzz {
namespace {

constexpr char kUsage[] =
    "usage: fleetmap-fuzz-seeds --source REPO_DIR --data SHARED_DATA_DIR --out DIR\n"
    "Writes DIR/<target>/<seed> for every fuzz target and prints the count per target.\n";

int Run(int argc, char** argv) {
  SeedInputs in;
  std::filesystem::path out;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--source") == 0) {
      in.source_dir = argv[i + 1];
    } else if (std::strcmp(argv[i], "--data") == 0) {
      in.data_dir = argv[i + 1];
    } else if (std::strcmp(argv[i], "--out") == 0) {
      out = argv[i + 1];
    } else {
      break;
    }
  }
  if (argc != 7 || in.source_dir.empty() || out.empty()) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  if (!std::filesystem::is_directory(in.data_dir)) {
    std::fprintf(stderr, "fleetmap-fuzz-seeds: no %s: seeds from our own encoders only\n",
                 in.data_dir.c_str());
  }
  SeedCorpus corpus(out);
  const std::vector<core::LaserScan> real_scans = RealScans(in);
  AddTransportSeeds(corpus);
  AddMessageSeeds(corpus, real_scans);
  AddSickSeeds(corpus, in, real_scans);
  AddLogSeeds(corpus, in);
  AddMapSeeds(corpus, in);
  AddRegressionInputs(corpus, in);
  for (const auto& [target, count] : corpus.counts()) std::printf("%s %d\n", target.c_str(), count);
  if (!corpus.ok()) std::fprintf(stderr, "fleetmap-fuzz-seeds: could not write every seed\n");
  return corpus.ok() ? 0 : 1;
}

}  // namespace
}  // namespace fleetmap::fuzz

int main(int argc, char** argv) { return fleetmap::fuzz::Run(argc, argv); }
