// Typed reading of YAML files whose every error names the file, the line and the field:
// "scenario.yaml:12: vehicles[0].speed_mps: must be positive". yaml-cpp exceptions are caught
// here and never escape; a node looked up in a missing one (IsDefined() false, and yaml-cpp
// throws on any other question to it) reads as missing.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"

namespace fleetmap::core {

class YamlReader {
 public:
  // Parses `path`; a syntax error reports its line.
  static Result<YamlReader> Load(const std::string& path);
  static Result<YamlReader> FromString(const std::string& text, const std::string& name);

  const YAML::Node& root() const { return root_; }
  const std::string& path() const { return path_; }

  // An error located at `node` (its line) about `field`.
  Status Error(const YAML::Node& node, const std::string& field, const std::string& what) const;

  // Required scalar `key` of map `parent`; `field` is the dotted path used in messages.
  template <typename T>
  Result<T> Get(const YAML::Node& parent, const std::string& key, const std::string& field) const {
    if (!parent.IsDefined() || !parent.IsMap() || !parent[key]) {
      return Error(parent, field, "missing");
    }
    return Convert<T>(parent[key], field);
  }
  // Optional scalar: `fallback` when absent, an error when present but malformed.
  template <typename T>
  Result<T> GetOr(const YAML::Node& parent, const std::string& key, const std::string& field,
                  T fallback) const {
    if (!parent.IsDefined() || !parent.IsMap() || !parent[key]) return fallback;
    return Convert<T>(parent[key], field);
  }
  // A finite number.
  Result<double> Number(const YAML::Node& parent, const std::string& key, const std::string& field,
                        std::optional<double> fallback = std::nullopt) const;
  // A sequence of numbers of the given length (length 0: any).
  Result<std::vector<double>> Numbers(const YAML::Node& node, const std::string& field,
                                      size_t length = 0) const;
  // [x, y] in metres.
  Result<Eigen::Vector2d> Point(const YAML::Node& node, const std::string& field) const;
  // A sequence of [x, y] points with at least `min_points`.
  Result<std::vector<Eigen::Vector2d>> Points(const YAML::Node& node, const std::string& field,
                                              size_t min_points) const;
  // A path relative to this file's folder (absolute paths stay as they are).
  std::string Resolve(const std::string& relative) const;

 private:
  YamlReader(YAML::Node root, std::string path) : root_(std::move(root)), path_(std::move(path)) {}
  template <typename T>
  Result<T> Convert(const YAML::Node& node, const std::string& field) const {
    try {
      return node.as<T>();
    } catch (const YAML::Exception&) {
      return Error(node, field, "has the wrong type");
    }
  }

  YAML::Node root_;
  std::string path_;
};

}  // namespace fleetmap::core
