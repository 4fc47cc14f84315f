// Seeds that replay every input a fuzz target once failed on: tests/data/fuzz/<target>/ holds
// them (the regression tests in tests/<library>/ read the same files).
#include <fstream>
#include <sstream>

#include "fuzz/seed_sources.h"

namespace fleetmap::fuzz {

void AddRegressionInputs(SeedCorpus& corpus, const SeedInputs& in) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& folder : fs::directory_iterator(in.source_dir / "tests/data/fuzz", ec)) {
    for (const auto& file : fs::directory_iterator(folder.path(), ec)) {
      std::ifstream stream(file.path(), std::ios::binary);
      std::ostringstream bytes;
      bytes << stream.rdbuf();
      corpus.Add(folder.path().filename().string(), "regression_" + file.path().filename().string(),
                 bytes.str());
    }
  }
}

}  // namespace fleetmap::fuzz
