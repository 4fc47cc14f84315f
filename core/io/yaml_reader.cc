#include "core/io/yaml_reader.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fleetmap::core {

Result<YamlReader> YamlReader::Load(const std::string& path) {
  std::ifstream in(path);
  if (!in) return NotFound(path + ": cannot open");
  std::stringstream text;
  text << in.rdbuf();
  return FromString(text.str(), path);
}

Result<YamlReader> YamlReader::FromString(const std::string& text, const std::string& name) {
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) return InvalidArgument(name + ": the document must be a YAML map");
    return YamlReader(root, name);
  } catch (const YAML::Exception& e) {
    return InvalidArgument(name + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

Status YamlReader::Error(const YAML::Node& node, const std::string& field,
                         const std::string& what) const {
  // -1 for nodes made up by yaml-cpp (missing keys). A lookup in a node that does not exist
  // (rect["center"] when rect is null) gives an invalid node, whose Mark() throws.
  const int line = node.IsDefined() ? node.Mark().line : -1;
  const std::string where = line >= 0 ? path_ + ":" + std::to_string(line + 1) : path_;
  return InvalidArgument(where + ": " + field + ": " + what);
}

Result<double> YamlReader::Number(const YAML::Node& parent, const std::string& key,
                                  const std::string& field, std::optional<double> fallback) const {
  if (!parent.IsDefined() || !parent.IsMap() || !parent[key]) {
    if (fallback) return *fallback;
    return Error(parent, field, "missing");
  }
  auto v = Convert<double>(parent[key], field);
  if (v.ok() && !std::isfinite(*v)) return Error(parent[key], field, "must be a finite number");
  return v;
}

Result<std::vector<double>> YamlReader::Numbers(const YAML::Node& node, const std::string& field,
                                                size_t length) const {
  if (!node.IsDefined() || !node.IsSequence()) {
    return Error(node, field, "must be a list of numbers");
  }
  if (length != 0 && node.size() != length) {
    return Error(node, field, "must have " + std::to_string(length) + " numbers");
  }
  std::vector<double> out;
  for (size_t i = 0; i < node.size(); ++i) {
    auto v = Convert<double>(node[i], field);
    if (!v.ok()) return v.status();
    if (!std::isfinite(*v)) return Error(node[i], field, "must be finite");
    out.push_back(*v);
  }
  return out;
}

Result<Eigen::Vector2d> YamlReader::Point(const YAML::Node& node, const std::string& field) const {
  auto xy = Numbers(node, field, 2);
  if (!xy.ok()) return xy.status();
  return Eigen::Vector2d((*xy)[0], (*xy)[1]);
}

Result<std::vector<Eigen::Vector2d>> YamlReader::Points(const YAML::Node& node,
                                                        const std::string& field,
                                                        size_t min_points) const {
  if (!node.IsDefined() || !node.IsSequence() || node.size() < min_points) {
    return Error(node, field,
                 "must be a list of at least " + std::to_string(min_points) + " [x, y] points");
  }
  std::vector<Eigen::Vector2d> out;
  for (size_t i = 0; i < node.size(); ++i) {
    auto p = Point(node[i], field + "[" + std::to_string(i) + "]");
    if (!p.ok()) return p.status();
    out.push_back(*p);
  }
  return out;
}

std::string YamlReader::Resolve(const std::string& relative) const {
  const std::filesystem::path p(relative);
  if (p.is_absolute()) return relative;
  return (std::filesystem::path(path_).parent_path() / p).lexically_normal().string();
}

}  // namespace fleetmap::core
