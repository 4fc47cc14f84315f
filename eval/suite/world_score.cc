#include "eval/suite/world_score.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/io/file_io.h"

namespace fleetmap::eval::suite {
namespace {

core::Result<double> Number(const nlohmann::json& report, const char* key) {
  const auto it = report.find(key);
  if (it == report.end()) return core::DataLoss(std::string("no \"") + key + "\"");
  if (it->is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!it->is_number()) return core::DataLoss(std::string("\"") + key + "\" is not a number");
  return it->get<double>();
}

// A figure read where the report gives it (older reports do not), NaN where it does not.
double Given(const nlohmann::json& report, const char* key) {
  const core::Result<double> v = Number(report, key);
  return v.ok() ? *v : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

double WorldScore::RejectedShare() const {
  const int merges = merges_accepted + merges_rejected;
  return merges > 0 ? static_cast<double>(merges_rejected) / merges
                    : std::numeric_limits<double>::quiet_NaN();
}

core::Result<WorldScore> ReadWorldScore(const std::string& path) {
  auto text = core::ReadFileBytes(path, 16 << 20);
  if (!text.ok()) return text.status();
  const nlohmann::json report = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
  if (report.is_discarded() || !report.is_object())
    return core::DataLoss(path + ": not a JSON object");
  WorldScore s;
  struct Field {
    const char* key;
    double* value;
  };
  double erased = 0, actors = 0, accepted = 0, rejected = 0, added = 0, removed = 0;
  const Field fields[] = {{"changed_cells.f1", &s.changed_f1},
                          {"changed_cells.added.recall", &s.added_recall},
                          {"changed_cells.removed.recall", &s.removed_recall},
                          {"static_cells_erased", &erased},
                          {"actor_cells_mapped", &actors},
                          {"alignment.translation_cells.p95", &s.align_trans_p95_cells},
                          {"merges.accepted", &accepted},
                          {"merges.rejected", &rejected},
                          {"changed_cells.added.true", &added},
                          {"changed_cells.removed.true", &removed}};
  for (const Field& f : fields) {
    auto v = Number(report, f.key);
    if (!v.ok()) return v.status().WithContext(path);
    *f.value = *v;
  }
  s.anchor_trans_p95_cells = Given(report, "alignment.anchor_translation_cells.p95");
  s.anchor_nees_p95 = Given(report, "alignment.anchor_nees.p95");
  s.localization_p95_m = Given(report, "localization.error_m.p95");
  s.tempmap_drift_p95_m = Given(report, "tempmap.drift_m.p95");
  s.tempmap_drift_p95_deg = Given(report, "tempmap.drift_deg.p95");
  s.added_lost_seen_free = added > 0 ? Given(report, "seen_free.added_missed") / added
                                     : std::numeric_limits<double>::quiet_NaN();
  if (!std::isfinite(s.changed_f1) || !std::isfinite(erased) || !std::isfinite(actors) ||
      !std::isfinite(accepted) || !std::isfinite(rejected))
    return core::DataLoss(path + ": a count or the F1 is null");
  // An F1 over no changed cell would read as 0 (or 1): the world scored nothing.
  if (!(added + removed > 0))
    return core::FailedPrecondition(path + ": no cell of the world changed where a scanner saw it");
  s.static_erased = static_cast<int64_t>(erased);
  s.actor_mapped = static_cast<int64_t>(actors);
  s.merges_accepted = static_cast<int>(accepted);
  s.merges_rejected = static_cast<int>(rejected);
  return s;
}

}  // namespace fleetmap::eval::suite
