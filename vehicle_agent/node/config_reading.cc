#include "vehicle_agent/node/config_reading.h"

namespace fleetmap::vehicle_agent::node {

using core::YamlReader;

core::Status CheckKeys(const YamlReader& r, const YAML::Node& node, const std::string& field,
                       std::initializer_list<const char*> known) {
  if (!node.IsMap()) return r.Error(node, field, "must be a map");
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string key = it->first.IsScalar() ? it->first.Scalar() : "?";
    bool ok = false;
    std::string list;
    for (const char* k : known) {
      ok |= key == k;
      list += (list.empty() ? "" : ", ") + std::string(k);
    }
    if (!ok)
      return r.Error(it->first, field.empty() ? key : field + "." + key,
                     "unknown key (known: " + list + ")");
  }
  return core::OkStatus();
}

YAML::Node Section(const YAML::Node& parent, const char* key) {
  return parent[key] ? parent[key] : YAML::Node(YAML::NodeType::Undefined);
}

}  // namespace fleetmap::vehicle_agent::node
