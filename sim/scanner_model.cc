#include "sim/scanner_model.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace fleetmap::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

ScannerModel Model(const std::string& name, double fov_deg, double increment_deg, double hz,
                   double range_max_m, double sigma_m) {
  ScannerModel m;
  m.name = name;
  m.fov_rad = fov_deg * kDeg;
  m.increment_rad = increment_deg * kDeg;
  m.num_beams = static_cast<int>(std::lround(fov_deg / increment_deg)) + 1;
  m.frequency_hz = hz;
  m.range_max_m = range_max_m;
  m.range_sigma_m = sigma_m;
  return m;
}

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

}  // namespace

core::Status ScannerModel::Validate() const {
  if (!(fov_rad > 0 && fov_rad <= 2 * M_PI && increment_rad > 0 && num_beams >= 2 &&
        frequency_hz > 0 && range_min_m >= 0 && range_max_m > range_min_m && range_sigma_m >= 0 &&
        dropout_probability >= 0 && dropout_probability <= 1 && mixed_pixel_probability >= 0 &&
        mixed_pixel_probability <= 1)) {
    return core::InvalidArgument("scanner model '" + name + "' has out-of-range figures");
  }
  return core::OkStatus();
}

const std::vector<ScannerModel>& KnownScannerModels() {
  // 270 deg at 0.5 deg = 541 beams, 40 ms scan time (S300 data output, 500 kBaud).
  // microScan3: 275 deg at 0.39 deg, 40 ms. TiM571: 270 deg at 1/3 deg = 811 beams, 15 Hz,
  // 25 m. LMS111: 270 deg at 0.5 deg, 50 Hz, 20 m, 12 mm statistical error.
  static const std::vector<ScannerModel> models = {
      Model("S300", 270.0, 0.5, 25.0, 30.0, 0.02),
      Model("microScan3", 275.0, 0.39, 25.0, 40.0, 0.015),
      Model("TiM571", 270.0, 1.0 / 3.0, 15.0, 25.0, 0.02),
      Model("LMS111", 270.0, 0.5, 50.0, 20.0, 0.012),
  };
  return models;
}

core::Result<ScannerModel> FindScannerModel(const std::string& name) {
  std::string known;
  for (const ScannerModel& m : KnownScannerModels()) {
    if (Lower(m.name) == Lower(name)) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  return core::InvalidArgument("unknown scanner model '" + name + "' (known: " + known + ")");
}

}  // namespace fleetmap::sim
