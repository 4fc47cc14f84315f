// fleetmap-fuzz-seeds: writes the seed corpora of the fuzz targets (fuzz/*_fuzz.cc), one
// folder per target, from our own encoders and from the real recordings in the data folder
// (FLEETMAP_DATA_DIR).
// The recordings are read where they are and never copied into the repository; without them
// the corpora hold our own outputs only. The build runs it (fuzz/CMakeLists.txt).
#include <cstdio>
#include <string>

#include "core/command_line.h"
#include "fuzz/seed_sources.h"

namespace fleetmap::fuzz {
namespace {

int Run(int argc, char** argv) {
  SeedInputs in;
  std::string out;
  CLI::App app("Writes DIR/<target>/<seed> for every fuzz target and prints the count per target.",
               "fleetmap-fuzz-seeds");
  core::AddVersionFlag(app);
  app.add_option("--source", in.source_dir, "the repository")->required()->type_name("REPO_DIR");
  app.add_option("--data", in.data_dir, "the shared data folder (FLEETMAP_DATA_DIR)")
      ->required()
      ->type_name("SHARED_DATA_DIR");
  app.add_option("--out", out, "where the corpora go")->required()->type_name("DIR");
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
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
