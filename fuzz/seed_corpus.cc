#include "fuzz/seed_corpus.h"

#include <fstream>

namespace fleetmap::fuzz {

void SeedCorpus::Add(const std::string& target, const std::string& name, std::string_view bytes) {
  const std::filesystem::path folder = out_ / target;
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  std::filesystem::path path = folder / name;
  for (int i = 2; std::filesystem::exists(path); ++i)
    path = folder / (name + "." + std::to_string(i));
  std::ofstream file(path, std::ios::binary);
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ok_ = ok_ && !ec && file.good();
  ++counts_[target];
}

}  // namespace fleetmap::fuzz
