// How the agent's configuration file is read, section by section: each section refuses the
// keys it does not know (a misspelt key must not silently keep its default), an absent section
// leaves the defaults, and every error names the file, the line and the dotted key
// (core::YamlReader). Shared by the section readers (agent_config.cc, input_config.cc,
// pipeline_config.cc).
#pragma once

#include <initializer_list>
#include <string>
#include <utility>

#include "core/io/yaml_reader.h"
#include "core/result.h"

namespace fleetmap::vehicle_agent::node {

// Refuses keys outside `known`, naming the key, its line and the keys that exist.
core::Status CheckKeys(const core::YamlReader& r, const YAML::Node& node, const std::string& field,
                       std::initializer_list<const char*> known);

// An optional sub-map: absent gives an undefined node the readers skip.
YAML::Node Section(const YAML::Node& parent, const char* key);

// `out` from the word at `key` of `node`, one of `choices`; left as it is when the key is
// absent.
template <typename Enum>
core::Status ReadChoice(const core::YamlReader& r, const YAML::Node& node, const char* key,
                        const std::string& field,
                        std::initializer_list<std::pair<const char*, Enum>> choices, Enum& out) {
  if (!node[key]) return core::OkStatus();
  auto word = r.Get<std::string>(node, key, field);
  if (!word.ok()) return word.status();
  std::string list;
  for (const auto& [name, value] : choices) {
    if (*word == name) {
      out = value;
      return core::OkStatus();
    }
    list += (list.empty() ? "" : ", ") + std::string(name);
  }
  return r.Error(node[key], field, "must be one of " + list);
}

}  // namespace fleetmap::vehicle_agent::node

// `target` from the number (a finite one) or the scalar of `type` at `key` of `node`, when
// the key is there; errors name the field `prefix key` (both string literals). Returns the
// error from the enclosing function, whose reader `r` is.
#define FLEETMAP_READ_NUMBER(r, node, key, prefix, target) \
  FLEETMAP_ASSIGN_OR_RETURN(target, (r).Number(node, key, prefix key, target))
#define FLEETMAP_READ_AS(r, type, node, key, prefix, target) \
  FLEETMAP_ASSIGN_OR_RETURN(target, (r).GetOr<type>(node, key, prefix key, target))
