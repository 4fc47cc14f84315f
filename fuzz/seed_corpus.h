// Where the seed writer (fleetmap-fuzz-seeds) puts its seeds: one file per seed under
// <out>/<target>/, named after what it holds.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace fleetmap::fuzz {

class SeedCorpus {
 public:
  explicit SeedCorpus(std::filesystem::path out) : out_(std::move(out)) {}

  // Writes <out>/<target>/<name>; a second seed of the same name gets a numbered suffix.
  void Add(const std::string& target, const std::string& name, std::string_view bytes);
  void Add(const std::string& target, const std::string& name, const std::vector<uint8_t>& bytes) {
    Add(target, name, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  }

  const std::map<std::string, int>& counts() const { return counts_; }
  bool ok() const { return ok_; }

 private:
  std::filesystem::path out_;
  std::map<std::string, int> counts_;  // seeds per target
  bool ok_ = true;                     // every write succeeded
};

}  // namespace fleetmap::fuzz
