// Laser scanner models with the figures of the real devices (SICK data sheets), and the
// noise the simulator applies: Gaussian range noise, missing returns, mixed pixels.
#pragma once

#include <string>
#include <vector>

#include "core/result.h"

namespace fleetmap::sim {

struct ScannerModel {
  std::string name;
  double fov_rad = 0.0;                // total opening angle, centred on the scanner's x axis
  double increment_rad = 0.0;          // angle between neighbouring beams
  int num_beams = 0;                   // fov / increment + 1
  double frequency_hz = 0.0;           // scans per second
  double range_min_m = 0.05;           // closer returns are not reported
  double range_max_m = 30.0;           // farther surfaces give no return (range reported as max)
  double range_sigma_m = 0.02;         // standard deviation of Gaussian range noise
  double dropout_probability = 0.002;  // chance that a beam returns nothing at all
  // At a depth jump between neighbouring beams, the chance that a beam reports a range in
  // between (the "mixed pixel" of a beam that straddles an edge).
  double mixed_pixel_probability = 0.3;
  double mixed_pixel_min_jump_m = 0.3;  // depth jump that counts as an edge

  double angle_min_rad() const { return -fov_rad / 2.0; }
  double period_s() const { return 1.0 / frequency_hz; }
  core::Status Validate() const;
};

// SICK S300 (the paper's safety scanner), microScan3, TiM571 and LMS111.
const std::vector<ScannerModel>& KnownScannerModels();
// Looks a model up by name, case-insensitively ("S300", "tim571", ...).
core::Result<ScannerModel> FindScannerModel(const std::string& name);

}  // namespace fleetmap::sim
