#include "vehicle_agent/divergence.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "vehicle_agent/localization/input_guard.h"
#include "vehicle_agent/option_check.h"

namespace fleetmap::vehicle_agent {

core::Status DivergenceOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(CheckOption(alpha_slow >= 0 && alpha_slow < alpha_fast,
                                       "DivergenceOptions.alpha_slow", alpha_slow,
                                       ">= 0 and < alpha_fast"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(alpha_fast > 0 && alpha_fast <= 1,
                                       "DivergenceOptions.alpha_fast", alpha_fast, "in (0, 1]"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(rotation_freeze_radps >= 0,
                                       "DivergenceOptions.rotation_freeze_radps",
                                       rotation_freeze_radps, ">= 0"));
  if (rule == DivergenceRule::kPaper) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckOption(start_above > stop_below && start_above < 1,
                                       "DivergenceOptions.start_above", start_above,
                                       "> stop_below and < 1"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(stop_below >= 0, "DivergenceOptions.stop_below", stop_below, ">= 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(min_duration_s >= 0 && std::isfinite(min_duration_s),
                                       "DivergenceOptions.min_duration_s", min_duration_s,
                                       ">= 0 and finite"));
  return CheckOption(max_duration_s > min_duration_s, "DivergenceOptions.max_duration_s",
                     max_duration_s, "> min_duration_s");
}

DivergenceDetector::DivergenceDetector(const DivergenceOptions& options) : options_(options) {
  assert(options.Validate().ok());
}

DivergenceSample DivergenceDetector::Update(double stamp_s, double w_avg, double omega_radps,
                                            bool localized) {
  if (!std::isfinite(stamp_s) || !std::isfinite(w_avg) || w_avg < 0 || std::isnan(omega_radps))
    return Dropped(stamp_s, w_avg, stats_.dropped_invalid);
  const bool clock_step = has_stamp_ && IsClockStepBack(stamp_s, last_stamp_s_);
  if (has_stamp_ && stamp_s < last_stamp_s_ && !clock_step)
    return Dropped(stamp_s, w_avg, stats_.dropped_out_of_order);
  // The clock was set back: a temporary map's duration goes on from where it was.
  if (clock_step) started_s_ += stamp_s - last_stamp_s_;
  if (building_ && has_stamp_ && !clock_step) stats_.building_s += stamp_s - last_stamp_s_;
  has_stamp_ = true;
  last_stamp_s_ = stamp_s;
  ++stats_.samples;
  const bool first = averaged_ == 0;
  if (first) {  // W_slow(0) = W_fast(0) = the first W_avg
    w_slow_ = w_fast_ = w_avg;
    averaged_ = 1;
  }
  DivergenceSample s;
  s.stamp_s = stamp_s;
  s.w_avg = w_avg;
  s.w_slow = w_slow_;
  s.w_fast = w_fast_;
  s.d = w_slow_ > 0 ? std::max(0.0, 1.0 - w_fast_ / w_slow_) : 0.0;
  s.rotating = std::abs(omega_radps) > options_.rotation_freeze_radps;
  stats_.rotating += s.rotating;
  if (!s.rotating && !first) Average(w_avg);
  Step(s, localized);
  return s;
}

// Eqs. (2) and (3): W(t+1) from W(t) and W_avg(t); during the warm-up the running mean.
void DivergenceDetector::Average(double w_avg) {
  const double warm = options_.warm_up ? 1.0 / static_cast<double>(averaged_ + 1) : 0.0;
  w_slow_ += std::max(options_.alpha_slow, warm) * (w_avg - w_slow_);
  w_fast_ += std::max(options_.alpha_fast, warm) * (w_avg - w_fast_);
  ++averaged_;
}

void DivergenceDetector::Step(DivergenceSample& s, bool localized) {
  const bool paper = options_.rule == DivergenceRule::kPaper;
  const bool start_now = start_pending_ && localized && options_.map_at_start;
  start_pending_ = start_pending_ && !localized;
  if (!building_) {
    s.started = paper ? s.d > 0.0 : s.d > options_.start_above || start_now;
    if (s.started) started_s_ = s.stamp_s;
  } else {
    const double elapsed_s = s.stamp_s - started_s_;
    s.stopped = paper ? s.d <= 0.0
                      : elapsed_s >= options_.max_duration_s ||
                            (elapsed_s >= options_.min_duration_s && s.d < options_.stop_below);
  }
  building_ = (building_ || s.started) && !s.stopped;
  stats_.starts += s.started;
  stats_.stops += s.stopped;
  s.building = building_;
}

DivergenceSample DivergenceDetector::Dropped(double stamp_s, double w_avg, int64_t& counter) {
  ++counter;
  DivergenceSample s;
  s.stamp_s = stamp_s;
  s.w_avg = w_avg;
  s.w_slow = w_slow_;
  s.w_fast = w_fast_;
  s.d = w_slow_ > 0 ? std::max(0.0, 1.0 - w_fast_ / w_slow_) : 0.0;
  s.building = building_;
  s.accepted = false;
  return s;
}

void DivergenceDetector::Reset() {
  averaged_ = 0;
  w_slow_ = w_fast_ = 0.0;
  building_ = false;
  start_pending_ = true;
}

}  // namespace fleetmap::vehicle_agent
