// The divergence detector (the paper's Sec. 3.2, after Abrate et al. and Augmented MCL,
// Probabilistic Robotics table 8.3): a slow and a fast recency average of the scan
// likelihood W_avg, eqs. (1)-(4):
//   W_slow(t+1) = W_slow(t) + alpha_slow (W_avg(t) - W_slow(t))
//   W_fast(t+1) = W_fast(t) + alpha_fast (W_avg(t) - W_fast(t))
//   d(t)        = max(0, 1 - W_fast(t) / W_slow(t))
// d rises when the last few scans fit the map worse than the long-term average: something
// changed. The averages are not updated while the vehicle rotates (|omega| above a threshold).
// When d says so, a temporary map is started or stopped.
#pragma once

#include <cstdint>

#include "core/result.h"

namespace fleetmap::vehicle_agent {

enum class DivergenceRule {
  kPaper,       // start at d > 0, stop at d <= 0 (the paper's rule)
  kHysteresis,  // start at d > start_above, stop at d < stop_below, with min/max durations
};

// Defaults chosen by measurement on the simulator (`localization_bench --divergence_study`
// and the whole system's evaluation, docs/localization.md): the paper's rule opens a
// temporary map at every flicker of d in an unchanged hall; hysteresis opens few or none there
// and still catches most changes coming into view.
struct DivergenceOptions {
  // Per-sample decay rates, 0 <= alpha_slow < alpha_fast <= 1 (the paper: alpha_slow <<
  // alpha_fast). At 25 scans/s the time constants are 1 / (25 alpha): 40 s and 0.4 s. The
  // values AMCL suggests for recovery_alpha_slow / recovery_alpha_fast.
  double alpha_slow = 0.001;
  double alpha_fast = 0.1;
  // How the averages start; the paper does not say. true: each starts as the running mean of
  // the W_avg seen so far, i.e. the rate is max(alpha, 1 / n) for the n-th sample, until
  // 1 / alpha samples have been seen; then eqs. (2) and (3) as written. false: both start at
  // the first W_avg, and W_slow needs minutes to reach its level (a first scan taken before
  // the localizer converged is far below it): changes in the first minutes go unseen
  // (measured in docs/localization.md).
  bool warm_up = true;
  // While |omega| exceeds this the averages are frozen (the paper), rad/s, >= 0. The
  // simulator's scans have no motion skew, so turning costs no W_avg there (measured: no
  // difference); on a real scanner a scan taken while turning is smeared.
  double rotation_freeze_radps = 0.1;
  DivergenceRule rule = DivergenceRule::kHysteresis;
  // kHysteresis only: start above, stop below, 0 <= stop_below < start_above < 1. d = 0.1
  // is about 1.6% of the beams contradicting the map (a pallet's face 10 m away). Lower
  // thresholds start more maps in an unchanged hall; higher ones miss small changes next to a
  // wall (a parked robot), which the map then never holds: 0.05 / 0.025 is what the map needs
  // (docs/localization.md, "Choosing the rule"). A false start costs bandwidth, not map
  // quality: the merge adds nothing a temporary map of an unchanged place holds
  // (docs/aggregator.md, "Figures").
  double start_above = 0.05;
  double stop_below = 0.025;
  // kHysteresis only: building lasts at least / at most this long, s, 0 <= min < max. A
  // change longer than max_duration_s is split into several temporary maps. 20 s: the
  // aggregator adds an obstacle once temporary maps of two times (2 s apart) saw it, and the
  // builder closes a map every 3 s (TempMapBuilderOptions), so a change seen once keeps the
  // vehicle mapping through several maps of its pass, until it has passed the object and
  // seen its far faces; shorter loses the faces seen only looking back, longer maps more
  // people (docs/aggregator.md, "Change detection of the real system").
  double min_duration_s = 20.0;
  double max_duration_s = 60.0;
  // kHysteresis only: the first sample after start-up (or Reset) taken while the vehicle is
  // localized opens a temporary map. d compares the scans with their own past, so whatever
  // is in view from the first scan on (a pallet next to where the vehicle was switched on) is
  // part of that past and never raises d; the vehicle maps its first min_duration_s instead.
  // In an unchanged place that costs a few maps' bandwidth and adds nothing. Off by default:
  // about even across the world suite, more removals found but a worse tail
  // (docs/experiments/2026-12-05-map-at-start-and-held-walls.md).
  bool map_at_start = false;

  core::Status Validate() const;
};

// One detector step: the values of eqs. (1)-(4) at this sample and the state they led to.
struct DivergenceSample {
  double stamp_s = 0.0;
  double w_avg = 0.0;     // eq. (1), as given
  double w_slow = 0.0;    // W_slow(t), before this sample's W_avg enters it
  double w_fast = 0.0;    // W_fast(t)
  double d = 0.0;         // eq. (4)
  bool building = false;  // a temporary map is being built after this sample
  bool rotating = false;  // |omega| above the threshold: the averages were not updated
  bool started = false;   // this sample opened a temporary map
  bool stopped = false;   // this sample closed one
  bool accepted = true;   // false: the input was dropped (see DivergenceStats)
};

struct DivergenceStats {
  int64_t samples = 0;               // accepted
  int64_t dropped_invalid = 0;       // non-finite stamp, NaN/inf/negative W_avg or NaN omega
  int64_t dropped_out_of_order = 0;  // stamp before the last accepted one
  int64_t rotating = 0;              // accepted while rotating
  int64_t starts = 0;
  int64_t stops = 0;
  double building_s = 0.0;  // time spent building
};

class DivergenceDetector {
 public:
  // `options` must pass Validate() (an assert).
  explicit DivergenceDetector(const DivergenceOptions& options);

  // One scan's W_avg at `stamp_s` with the vehicle turning at `omega_radps`. `localized`:
  // the pose is good enough to anchor a map (the map at start-up waits for it).
  DivergenceSample Update(double stamp_s, double w_avg, double omega_radps, bool localized = true);
  // Forgets the averages (e.g. after a global re-localization); a map being built is closed.
  void Reset();

  bool building() const { return building_; }
  const DivergenceStats& stats() const { return stats_; }
  const DivergenceOptions& options() const { return options_; }

 private:
  DivergenceSample Dropped(double stamp_s, double w_avg, int64_t& counter);
  void Step(DivergenceSample& s, bool localized);
  void Average(double w_avg);

  const DivergenceOptions options_;
  int64_t averaged_ = 0;  // samples that entered the averages
  double w_slow_ = 0.0, w_fast_ = 0.0;
  bool has_stamp_ = false;
  double last_stamp_s_ = 0.0;
  bool building_ = false;
  bool start_pending_ = true;  // map_at_start: no localized sample since start-up or Reset
  double started_s_ = 0.0;
  DivergenceStats stats_;
};

}  // namespace fleetmap::vehicle_agent
