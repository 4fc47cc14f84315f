#include "vehicle_agent/node/pipeline_config.h"

#include "vehicle_agent/node/config_reading.h"

namespace fleetmap::vehicle_agent::node {

using core::YamlReader;

core::Status ReadLocalization(const YamlReader& r, const YAML::Node& n, LocalizerOptions& l) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(
      r, n, "localization",
      {"max_beams", "min_particles", "max_particles", "update_min_translation_m",
       "update_min_rotation_rad", "w_avg_model", "external_sigma_xy_m", "external_sigma_theta_rad",
       "lost_after_s", "lost_explained_share", "lost_max_search_period_s", "relocalize_margin",
       "odometry_scale_sigma", "odometry_scale_walk_sigma_per_sqrt_m",
       "odometry_scale_pull_distance_m", "seed"}));
  FLEETMAP_READ_AS(r, int, n, "max_beams", "localization.", l.max_beams);
  FLEETMAP_READ_AS(r, int, n, "min_particles", "localization.", l.kld.min_particles);
  FLEETMAP_READ_AS(r, int, n, "max_particles", "localization.", l.kld.max_particles);
  FLEETMAP_READ_NUMBER(r, n, "update_min_translation_m", "localization.",
                       l.update_min_translation_m);
  FLEETMAP_READ_NUMBER(r, n, "update_min_rotation_rad", "localization.", l.update_min_rotation_rad);
  FLEETMAP_RETURN_IF_ERROR(ReadChoice<WAvgModel>(
      r, n, "w_avg_model", "localization.w_avg_model",
      {{"beam", WAvgModel::kBeamModel}, {"likelihood_field", WAvgModel::kLikelihoodField}},
      l.w_avg_model));
  FLEETMAP_READ_NUMBER(r, n, "external_sigma_xy_m", "localization.", l.external_sigma_xy_m);
  FLEETMAP_READ_NUMBER(r, n, "external_sigma_theta_rad", "localization.",
                       l.external_sigma_theta_rad);
  FLEETMAP_READ_NUMBER(r, n, "lost_after_s", "localization.", l.lost_after_s);
  FLEETMAP_READ_NUMBER(r, n, "lost_explained_share", "localization.", l.lost_explained_share);
  FLEETMAP_READ_NUMBER(r, n, "lost_max_search_period_s", "localization.",
                       l.lost_max_search_period_s);
  FLEETMAP_READ_NUMBER(r, n, "relocalize_margin", "localization.", l.relocalize_margin);
  FLEETMAP_READ_NUMBER(r, n, "odometry_scale_sigma", "localization.",
                       l.odometry_scale.initial_sigma);
  FLEETMAP_READ_NUMBER(r, n, "odometry_scale_walk_sigma_per_sqrt_m", "localization.",
                       l.odometry_scale.walk_sigma_per_sqrt_m);
  FLEETMAP_READ_NUMBER(r, n, "odometry_scale_pull_distance_m", "localization.",
                       l.odometry_scale.pull_distance_m);
  FLEETMAP_READ_AS(r, uint32_t, n, "seed", "localization.", l.seed);
  return core::OkStatus();
}

core::Status ReadDivergence(const YamlReader& r, const YAML::Node& n, DivergenceOptions& d) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, n, "divergence",
                {"rule", "alpha_slow", "alpha_fast", "start_above", "stop_below", "min_duration_s",
                 "max_duration_s", "rotation_freeze_radps", "map_at_start"}));
  FLEETMAP_RETURN_IF_ERROR(ReadChoice<DivergenceRule>(
      r, n, "rule", "divergence.rule",
      {{"hysteresis", DivergenceRule::kHysteresis}, {"paper", DivergenceRule::kPaper}}, d.rule));
  FLEETMAP_READ_NUMBER(r, n, "alpha_slow", "divergence.", d.alpha_slow);
  FLEETMAP_READ_NUMBER(r, n, "alpha_fast", "divergence.", d.alpha_fast);
  FLEETMAP_READ_NUMBER(r, n, "start_above", "divergence.", d.start_above);
  FLEETMAP_READ_NUMBER(r, n, "stop_below", "divergence.", d.stop_below);
  FLEETMAP_READ_NUMBER(r, n, "min_duration_s", "divergence.", d.min_duration_s);
  FLEETMAP_READ_NUMBER(r, n, "max_duration_s", "divergence.", d.max_duration_s);
  FLEETMAP_READ_NUMBER(r, n, "rotation_freeze_radps", "divergence.", d.rotation_freeze_radps);
  FLEETMAP_READ_AS(r, bool, n, "map_at_start", "divergence.", d.map_at_start);
  return core::OkStatus();
}

core::Status ReadBuilder(const YamlReader& r, const YAML::Node& n, TempMapBuilderOptions& b) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(CheckKeys(r, n, "builder",
                                     {"size_m", "max_duration_s", "edge_margin_m", "levels",
                                      "odometry_sigma_m", "odometry_sigma_per_m"}));
  FLEETMAP_READ_NUMBER(r, n, "size_m", "builder.", b.mapper.map.size_m);
  FLEETMAP_READ_NUMBER(r, n, "max_duration_s", "builder.", b.max_duration_s);
  FLEETMAP_READ_NUMBER(r, n, "edge_margin_m", "builder.", b.edge_margin_m);
  FLEETMAP_READ_AS(r, int, n, "levels", "builder.", b.mapper.map.levels);
  FLEETMAP_READ_NUMBER(r, n, "odometry_sigma_m", "builder.", b.mapper.matcher.prior_sigma_xy_m);
  FLEETMAP_READ_NUMBER(r, n, "odometry_sigma_per_m", "builder.",
                       b.mapper.matcher.prior_sigma_xy_per_m);
  return core::OkStatus();
}

core::Status ReadCandidateWatch(const YamlReader& r, const YAML::Node& n, AgentPipelineOptions& p) {
  if (!n) return core::OkStatus();
  FLEETMAP_RETURN_IF_ERROR(
      CheckKeys(r, n, "candidate_watch",
                {"pass_margin_m", "hit_margin_m", "min_free_scans", "max_range_m", "max_sigma_m",
                 "hold_gap_s", "report_held_s"}));
  CandidateWatchOptions& w = p.candidate_watch;
  FLEETMAP_READ_NUMBER(r, n, "pass_margin_m", "candidate_watch.", w.pass_margin_m);
  FLEETMAP_READ_NUMBER(r, n, "hit_margin_m", "candidate_watch.", w.hit_margin_m);
  FLEETMAP_READ_AS(r, int, n, "min_free_scans", "candidate_watch.", w.min_free_scans);
  FLEETMAP_READ_NUMBER(r, n, "max_range_m", "candidate_watch.", w.max_range_m);
  FLEETMAP_READ_NUMBER(r, n, "max_sigma_m", "candidate_watch.", p.candidate_watch_max_sigma_m);
  FLEETMAP_READ_NUMBER(r, n, "hold_gap_s", "candidate_watch.", w.hold_gap_s);
  FLEETMAP_READ_NUMBER(r, n, "report_held_s", "candidate_watch.", w.report_held_s);
  return core::OkStatus();
}

}  // namespace fleetmap::vehicle_agent::node
