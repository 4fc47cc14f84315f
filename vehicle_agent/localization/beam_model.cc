#include "vehicle_agent/localization/beam_model.h"

#include <cmath>
#include <optional>

#include "core/map/ray_caster.h"
#include "vehicle_agent/option_check.h"

namespace fleetmap::vehicle_agent {
namespace {

double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// eta N(z; expected, sigma^2), the Gaussian truncated to [0, z_max] and renormalised.
double HitDensity(double z, double expected, double sigma, double z_max) {
  const double mass = NormalCdf((z_max - expected) / sigma) - NormalCdf(-expected / sigma);
  if (!(mass > 0.0)) return 0.0;
  const double u = (z - expected) / sigma;
  return std::exp(-0.5 * u * u) / (sigma * std::sqrt(2.0 * M_PI) * mass);
}

// eta lambda e^(-lambda z) on [0, expected].
double ShortDensity(double z, double expected, double lambda) {
  if (z > expected || expected <= 0.0) return 0.0;
  return lambda * std::exp(-lambda * z) / (1.0 - std::exp(-lambda * expected));
}

// The longest jump of a beam through free space: a longer one saves few steps, and a cap lets a
// new map version recompute the caster's distance field only near its changes.
constexpr double kMaxJumpM = 2.0;

// 1 for each occupied cell of `window` (inside the map's grid), row-major in the window.
std::vector<uint8_t> OccupiedCells(const core::OccupancyGrid& map, const core::CellWindow& window) {
  const core::TriStateClassifier classify;
  std::vector<uint8_t> solid(static_cast<size_t>(window.num_cells()));
  const int w = map.geometry().width();
  for (int y = 0; y < window.height; ++y)
    for (int x = 0; x < window.width; ++x)
      solid[size_t(y) * window.width + x] =
          classify(map.cells()[size_t(y + window.y0) * w + (x + window.x0)]) ==
          core::CellState::kOccupied;
  return solid;
}

bool OnGrid(const core::GridGeometry& g, const Eigen::Vector2d& point) {
  const Eigen::Vector2d p = g.WorldToGrid(point);
  return p.x() >= 0.0 && p.y() >= 0.0 && p.x() < g.width() && p.y() < g.height();
}

class BeamModel final : public ScanLikelihood {
 public:
  explicit BeamModel(const BeamModelOptions& options) : options_(options) {
    assert(options.Validate().ok());
  }

  void SetMap(const core::OccupancyGrid& map) override {
    caster_.reset();
    if (map.geometry().num_cells() == 0) return;
    caster_.emplace(map.geometry(), kMaxJumpM);
    caster_->SetSolid(OccupiedCells(map, map.geometry().full_window()));
  }

  void UpdateMap(const core::OccupancyGrid& map, const core::CellWindow& changed) override {
    if (!caster_ || !(caster_->geometry() == map.geometry())) return SetMap(map);
    if (!map.geometry().Contains(changed)) return SetMap(map);
    caster_->UpdateSolid(changed, OccupiedCells(map, changed));
  }

  ScanScore Score(const core::LaserScan& scan, const core::Pose2& scanner_in_map) const override {
    if (!caster_ || !scanner_in_map.IsFinite() || !scan.Validate().ok()) return {};
    const double z_max = std::min(options_.max_range_m, scan.range_max_m);
    const Eigen::Vector2d origin = scanner_in_map.translation();
    // Off the grid every beam leaves it at once (and core::RayCaster needs a sane origin).
    const bool on_grid = OnGrid(caster_->geometry(), origin);
    ScanScoreAccumulator acc;
    for (size_t i = 0; i < scan.size(); i += static_cast<size_t>(options_.beam_stride)) {
      const BeamReading reading = ClassifyBeam(scan, i, z_max);
      if (reading == BeamReading::kInvalid) {
        acc.CountInvalid();
        continue;
      }
      if (reading == BeamReading::kNoReturn) acc.CountNoReturn();
      const double z = reading == BeamReading::kNoReturn ? z_max : scan.ranges_m[i];
      const double angle = scanner_in_map.theta_rad + scan.angle(i);
      const double expected = on_grid ? caster_->Cast(origin, angle, z_max).range_m : core::kNoHit;
      acc.AddBeam(BeamProbability(options_, z, expected, z_max));
    }
    return acc.Finish();
  }

 private:
  const BeamModelOptions options_;
  std::optional<core::RayCaster> caster_;
};

}  // namespace

core::Status BeamModelOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(CheckOption(z_hit >= 0, "BeamModelOptions.z_hit", z_hit, ">= 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(z_short >= 0, "BeamModelOptions.z_short", z_short, ">= 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(z_max >= 0, "BeamModelOptions.z_max", z_max, ">= 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(z_rand >= 0, "BeamModelOptions.z_rand", z_rand, ">= 0"));
  const double sum = z_hit + z_short + z_max + z_rand;
  FLEETMAP_RETURN_IF_ERROR(CheckOption(sum > 0 && std::isfinite(sum),
                                       "BeamModelOptions.z_hit + z_short + z_max + z_rand", sum,
                                       "> 0 and finite"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(sigma_hit_m > 0 && std::isfinite(sigma_hit_m),
                                       "BeamModelOptions.sigma_hit_m", sigma_hit_m, "> 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(lambda_short_per_m > 0 && std::isfinite(lambda_short_per_m),
                                       "BeamModelOptions.lambda_short_per_m", lambda_short_per_m,
                                       "> 0"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(beam_stride >= 1, "BeamModelOptions.beam_stride", beam_stride, ">= 1"));
  return CheckOption(max_range_m > 0 && std::isfinite(max_range_m), "BeamModelOptions.max_range_m",
                     max_range_m, "> 0 and finite");
}

double BeamProbability(const BeamModelOptions& o, double z_m, double expected_m,
                       double max_range_m) {
  const bool no_return = !(z_m < max_range_m);
  const double z = no_return ? max_range_m : z_m;
  const double expected = std::min(expected_m, max_range_m);
  double p = o.z_hit * HitDensity(z, expected, o.sigma_hit_m, max_range_m) +
             o.z_short * ShortDensity(z, expected, o.lambda_short_per_m);
  p += no_return ? o.z_max : o.z_rand / max_range_m;
  return p;
}

std::unique_ptr<ScanLikelihood> MakeBeamModel(const BeamModelOptions& options) {
  return std::make_unique<BeamModel>(options);
}

}  // namespace fleetmap::vehicle_agent
