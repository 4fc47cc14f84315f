#include "bench/localization_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/localization_bench_util.h"
#include "vehicle_agent/localization/localizer.h"

namespace fleetmap::bench {
namespace {

using vehicle_agent::Localizer;
using vehicle_agent::LocalizerOptions;

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void Track(const std::string& name, const std::vector<SensorStep>& steps, LocalizerOptions o) {
  o.initial_pose_in_map = steps[0].scan.true_base_pose * core::Pose2(0.4, -0.3, 10 * M_PI / 180);
  Localizer localizer(o);
  (void)localizer.SetMap(Addition().static_map(), 1);
  std::vector<double> error_m, error_deg, converging_m;
  double particles = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (const SensorStep& s : steps) {
    const auto r = localizer.Update(s.odom, s.scan.scan, Mount());
    particles += r.stats.particles;
    const core::Pose2 e = core::Between(s.scan.true_base_pose, r.estimate.pose_in_map);
    if (s.scan.scan.stamp_s < 10.0) {
      converging_m.push_back(std::hypot(e.x_m, e.y_m));
      continue;
    }
    error_m.push_back(std::hypot(e.x_m, e.y_m));
    error_deg.push_back(std::abs(e.theta_rad) * 180 / M_PI);
  }
  const std::chrono::duration<double, std::micro> us = std::chrono::steady_clock::now() - start;
  const double n = static_cast<double>(steps.size());
  std::printf("%-22s %8.4f %9.4f %8.4f %8.3f %8.2f %9.0f %8ld %8.1f\n", name.c_str(),
              Median(converging_m), Median(error_m),
              *std::max_element(error_m.begin(), error_m.end()), Median(error_deg),
              *std::max_element(error_deg.begin(), error_deg.end()), particles / n,
              static_cast<long>(localizer.counters().filter_updates), us.count() / n);
}

}  // namespace

int RunLocalizationStudy() {
  const std::vector<SensorStep> steps = RecordSensorSteps(Addition(), 0, 300.0);
  std::printf("%-22s %8s %9s %8s %8s %8s %9s %8s %8s\n", "variant", "0-10s_m", "median_m", "max_m",
              "med_deg", "max_deg", "particles", "updates", "us/scan");
  const LocalizerOptions d;
  auto with = [&d](auto change) {
    LocalizerOptions o = d;
    change(o);
    return o;
  };
  Track("default", steps, d);
  Track("sigma_hit_0.2_amcl", steps, with([](auto& o) { o.likelihood_field.sigma_hit_m = 0.2; }));
  Track("sigma_hit_0.05", steps, with([](auto& o) { o.likelihood_field.sigma_hit_m = 0.05; }));
  Track("no_lateral_slip", steps, with([](auto& o) { o.motion.alpha5_lateral_from_trans = 0; }));
  Track("update_every_scan", steps,
        with([](auto& o) { o.update_min_translation_m = o.update_min_rotation_rad = 0; }));
  Track("update_0.2m_30deg_amcl", steps, with([](auto& o) {
          o.update_min_translation_m = 0.2, o.update_min_rotation_rad = M_PI / 6;
        }));
  Track("max_beams_30", steps, with([](auto& o) { o.max_beams = 30; }));
  Track("max_beams_120", steps, with([](auto& o) { o.max_beams = 120; }));
  Track("min_particles_100", steps, with([](auto& o) { o.kld.min_particles = 100; }));
  Track("min_particles_500", steps, with([](auto& o) { o.kld.min_particles = 500; }));
  return 0;
}

}  // namespace fleetmap::bench
