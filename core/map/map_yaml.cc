#include "core/map/map_yaml.h"

#include <yaml-cpp/yaml.h>

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>

namespace fleetmap::core {
namespace {

namespace fs = std::filesystem;

Status KeyError(const std::string& key, const std::string& what) {
  return InvalidArgument("key '" + key + "' " + what);
}

Result<YAML::Node> RequiredKey(const YAML::Node& doc, const std::string& key) {
  YAML::Node node = doc[key];
  if (!node.IsDefined()) return InvalidArgument("missing key '" + key + "'");
  return node;
}

Result<double> ReadFiniteNumber(const YAML::Node& node, const std::string& key) {
  double value = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, value)) {
    return KeyError(key, "must be a number");
  }
  if (!std::isfinite(value)) return KeyError(key, "must be finite, got " + node.Scalar());
  return value;
}

Result<double> ReadNumberKey(const YAML::Node& doc, const std::string& key) {
  Result<YAML::Node> node = RequiredKey(doc, key);
  if (!node.ok()) return node.status();
  return ReadFiniteNumber(*node, key);
}

Result<Pose2> ReadOrigin(const YAML::Node& doc) {
  Result<YAML::Node> node = RequiredKey(doc, "origin");
  if (!node.ok()) return node.status();
  if (!node->IsSequence() || node->size() != 3) {
    return KeyError("origin", "must be a list of 3 numbers [x, y, yaw]");
  }
  std::array<double, 3> v{};
  for (size_t i = 0; i < 3; ++i) {
    Result<double> number = ReadFiniteNumber((*node)[i], "origin");
    if (!number.ok()) return number.status();
    v[i] = *number;
  }
  return Pose2(v[0], v[1], v[2]);
}

Result<bool> ReadNegate(const YAML::Node& doc) {
  Result<YAML::Node> node = RequiredKey(doc, "negate");
  if (!node.ok()) return node.status();
  int as_int = -1;
  bool as_bool = false;
  if (node->IsScalar() && YAML::convert<int>::decode(*node, as_int)) {
    if (as_int == 0 || as_int == 1) return as_int == 1;
  } else if (node->IsScalar() && YAML::convert<bool>::decode(*node, as_bool)) {
    return as_bool;
  }
  return KeyError("negate", "must be 0 or 1");
}

Result<MapMode> ReadMode(const YAML::Node& doc) {
  const YAML::Node node = doc["mode"];
  if (!node.IsDefined()) return MapMode::kTrinary;
  const std::string name = node.IsScalar() ? node.Scalar() : "";
  for (MapMode mode : {MapMode::kTrinary, MapMode::kScale, MapMode::kRaw}) {
    if (name == MapModeName(mode)) return mode;
  }
  return KeyError("mode", "must be trinary, scale or raw, got '" + name + "'");
}

Result<std::string> ReadImagePath(const YAML::Node& doc, const std::string& yaml_path) {
  Result<YAML::Node> node = RequiredKey(doc, "image");
  if (!node.ok()) return node.status();
  if (!node->IsScalar() || node->Scalar().empty()) {
    return KeyError("image", "must be a non-empty file name");
  }
  const fs::path image(node->Scalar());
  if (image.is_absolute()) return image.string();
  return (fs::path(yaml_path).parent_path() / image).string();
}

Result<OccupancyThresholds> ReadThresholds(const YAML::Node& doc) {
  Result<double> occupied = ReadNumberKey(doc, "occupied_thresh");
  if (!occupied.ok()) return occupied.status();
  Result<double> free = ReadNumberKey(doc, "free_thresh");
  if (!free.ok()) return free.status();
  OccupancyThresholds t;
  t.occupied_probability = *occupied;
  t.free_probability = *free;
  if (!t.Validate().ok()) {
    return InvalidArgument("keys 'free_thresh' (" + std::to_string(*free) +
                           ") and 'occupied_thresh' (" + std::to_string(*occupied) +
                           ") need 0 < free_thresh < occupied_thresh < 1");
  }
  return t;
}

Result<MapMetadata> ParseMapDocument(const YAML::Node& doc, const std::string& yaml_path) {
  if (!doc.IsMap()) return InvalidArgument("is not a YAML mapping of map_server keys");
  MapMetadata m;
  Result<std::string> image = ReadImagePath(doc, yaml_path);
  if (!image.ok()) return image.status();
  m.image_path = *image;
  Result<double> resolution = ReadNumberKey(doc, "resolution");
  if (!resolution.ok()) return resolution.status();
  if (*resolution <= 0.0)
    return KeyError("resolution", "must be positive, got " + std::to_string(*resolution));
  m.resolution_m = *resolution;
  Result<Pose2> origin = ReadOrigin(doc);
  if (!origin.ok()) return origin.status();
  m.origin = *origin;
  Result<bool> negate = ReadNegate(doc);
  if (!negate.ok()) return negate.status();
  m.negate = *negate;
  Result<OccupancyThresholds> thresholds = ReadThresholds(doc);
  if (!thresholds.ok()) return thresholds.status();
  m.thresholds = *thresholds;
  Result<MapMode> mode = ReadMode(doc);
  if (!mode.ok()) return mode.status();
  m.mode = *mode;
  return m;
}

// Shortest text that reads back as exactly `v`, independent of the locale.
std::string FormatNumber(double v) {
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

Result<std::string> YamlScalar(const std::string& text) {
  YAML::Emitter emitter;
  emitter << text;
  if (!emitter.good()) return InvalidArgument("cannot write '" + text + "' as YAML");
  return std::string(emitter.c_str());
}

}  // namespace

Result<std::string> MapYamlText(const GridGeometry& g, const std::string& image_name, MapMode mode,
                                const OccupancyThresholds& thresholds) {
  Result<std::string> image = YamlScalar(image_name);
  if (!image.ok()) return image;
  const bool trinary = mode == MapMode::kTrinary;
  const double occupied = trinary ? kTrinaryOccupiedThreshold : thresholds.occupied_probability;
  const double free = trinary ? kTrinaryFreeThreshold : thresholds.free_probability;
  const Pose2& o = g.origin();
  return "image: " + *image + "\nmode: " + MapModeName(mode) +
         "\nresolution: " + FormatNumber(g.resolution_m()) + "\norigin: [" + FormatNumber(o.x_m) +
         ", " + FormatNumber(o.y_m) + ", " + FormatNumber(o.theta_rad) +
         "]\nnegate: 0\noccupied_thresh: " + FormatNumber(occupied) +
         "\nfree_thresh: " + FormatNumber(free) + "\n";
}

const char* MapModeName(MapMode mode) {
  switch (mode) {
    case MapMode::kTrinary:
      return "trinary";
    case MapMode::kScale:
      return "scale";
    case MapMode::kRaw:
      return "raw";
  }
  return "unknown";
}

Result<MapMetadata> ParseMapYaml(const std::string& yaml_text, const std::string& yaml_path) {
  Result<MapMetadata> m = InvalidArgument("unparsed");
  try {
    m = ParseMapDocument(YAML::Load(yaml_text), yaml_path);
  } catch (const std::exception& e) {  // YAML::ParserException and anything yaml-cpp throws
    m = InvalidArgument(std::string("is not valid YAML: ") + e.what());
  }
  if (!m.ok()) return m.status().WithContext(yaml_path);
  return m;
}

}  // namespace fleetmap::core
