#include "aggregator/persistence/recovery_marker.h"

#include <cinttypes>
#include <cstdio>
#include <filesystem>

#include "core/io/file_io.h"

namespace fleetmap::aggregator {

core::Status WriteRecoveryMarker(const std::string& folder, const RecoveryMarker& marker) {
  char text[160];
  std::snprintf(text, sizeof(text),
                "recovery_id %" PRId64 "\nrecovered_version %" PRIu64 "\nrecovered_at_s %.3f\n",
                marker.id, marker.version, marker.at_s);
  return core::WriteFileAtomically(folder + "/" + kRecoveryMarkerName, text);
}

core::Result<std::optional<RecoveryMarker>> ReadRecoveryMarker(const std::string& folder) {
  const std::string path = folder + "/" + kRecoveryMarkerName;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::optional<RecoveryMarker>();
  std::string text;
  FLEETMAP_ASSIGN_OR_RETURN(text, core::ReadFileBytes(path, 4096));
  RecoveryMarker m;
  char tail = 0;
  if (std::sscanf(text.c_str(),
                  "recovery_id %" SCNd64 " recovered_version %" SCNu64 " recovered_at_s %lf %c",
                  &m.id, &m.version, &m.at_s, &tail) != 3 ||
      m.id <= 0) {
    return core::DataLoss(path + ": not a recovery marker (written by fleetmap-mapctl recover)");
  }
  return std::optional<RecoveryMarker>(m);
}

}  // namespace fleetmap::aggregator
