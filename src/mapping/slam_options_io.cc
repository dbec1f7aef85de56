#include "mapping/slam_options_io.h"

#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace semchain::mapping {
namespace {

using Target = std::variant<double*, int*, bool*, std::string*>;
using Fields = std::vector<std::pair<std::string, Target>>;

using Sections = std::vector<std::pair<std::string, Fields>>;

// Reads the keys 'fields' of map 'node', and the maps 'sections' nested in it (a missing or
// null node leaves everything as is).
Status ReadFields(const yaml::Node& node, const Fields& fields, const Sections& sections = {}) {
  if (node.IsNull()) return Status::Ok();
  if (!node.IsMap()) return node.Error("expected a map");
  std::vector<std::string> allowed;
  for (const auto& [key, target] : fields) allowed.push_back(key);
  for (const auto& [key, section] : sections) allowed.push_back(key);
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys(allowed));
  for (const auto& field : fields) {
    // field.first, not a structured binding: clang before 16 cannot capture those in a lambda.
    const std::string& key = field.first;
    SEMCHAIN_RETURN_IF_ERROR(std::visit(
        [&](auto* value) { return yaml::ReadOptional(node, key, value); }, field.second));
  }
  for (const auto& [key, section] : sections) {
    if (!node.Has(key)) continue;
    const Result<yaml::Node> child = node.Get(key);
    if (!child.ok()) return child.status();
    SEMCHAIN_RETURN_IF_ERROR(ReadFields(*child, section));
  }
  return Status::Ok();
}

Status ReadSection(const yaml::Node& root, const std::string& key, const Fields& fields,
                   const Sections& sections = {}) {
  if (!root.Has(key)) return Status::Ok();
  const Result<yaml::Node> node = root.Get(key);
  if (!node.ok()) return node.status();
  return ReadFields(*node, fields, sections);
}

Fields MatcherFields(HillClimbingOptions* m) {
  return {{"linear_step_meters", &m->linear_step_meters},
          {"angular_step_radians", &m->angular_step_radians},
          {"refinements", &m->refinements},
          {"max_evaluations", &m->max_evaluations}};
}

Fields MotionFields(MotionModelOptions* m) {
  return {{"translation_per_meter", &m->translation_per_meter},
          {"translation_per_radian", &m->translation_per_radian},
          {"rotation_per_meter", &m->rotation_per_meter},
          {"rotation_per_radian", &m->rotation_per_radian},
          {"min_translation_sigma_meters", &m->min_translation_sigma_meters},
          {"min_rotation_sigma_radians", &m->min_rotation_sigma_radians}};
}

Fields RefinementFields(SurfaceRefinementOptions* r) {
  return {{"enabled", &r->enabled},
          {"iterations", &r->iterations},
          {"huber_meters", &r->huber_meters},
          {"convergence_meters", &r->convergence_meters},
          {"max_correction_meters", &r->max_correction_meters},
          {"lines_only", &r->lines_only}};
}

Status ReadModelSections(const yaml::Node& root, RbpfOptions* o) {
  SEMCHAIN_RETURN_IF_ERROR(ReadSection(root, "grid",
                                       {{"resolution_meters", &o->grid.resolution_meters},
                                        {"hit_log_odds", &o->grid.hit_log_odds},
                                        {"miss_log_odds", &o->grid.miss_log_odds},
                                        {"max_abs_log_odds", &o->grid.max_abs_log_odds}}));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadSection(root, "scan",
                  {{"min_range_meters", &o->scan.min_range_meters},
                   {"max_range_meters", &o->scan.max_range_meters},
                   {"no_return_clear_meters", &o->scan.no_return_clear_meters}}));
  LikelihoodFieldOptions& f = o->field;
  SEMCHAIN_RETURN_IF_ERROR(ReadSection(root, "likelihood_field",
                                       {{"kernel_cells", &f.kernel_cells},
                                        {"obstacle_log_odds", &f.obstacle_log_odds},
                                        {"require_free_in_front", &f.require_free_in_front},
                                        {"interpolate_surface", &f.interpolate_surface},
                                        {"score_sigma_meters", &f.score_sigma_meters},
                                        {"likelihood_sigma_meters", &f.likelihood_sigma_meters},
                                        {"max_distance_meters", &f.max_distance_meters}}));
  SEMCHAIN_RETURN_IF_ERROR(ReadSection(root, "matcher", MatcherFields(&o->matcher)));
  Fields motion = MotionFields(&o->motion);
  motion.emplace_back("per_reading_noise", &o->motion.per_reading_noise);
  return ReadSection(root, "motion", motion);
}

Status ReadFilterSections(const yaml::Node& root, RbpfOptions* o) {
  ProposalOptions& p = o->proposal;
  SEMCHAIN_RETURN_IF_ERROR(
      ReadSection(root, "proposal",
                  {{"use_scan_matching", &p.use_scan_matching},
                   {"samples", &p.samples},
                   {"match_from_motion_sample", &p.match_from_motion_sample},
                   {"sample_window_meters", &p.sample_window_meters},
                   {"sample_window_radians", &p.sample_window_radians},
                   {"observation_gain", &p.observation_gain},
                   {"min_matched_points", &p.min_matched_points},
                   {"recovery_window_meters", &p.recovery_window_meters},
                   {"recovery_window_radians", &p.recovery_window_radians},
                   {"min_sigma_meters", &p.min_sigma_meters},
                   {"min_sigma_radians", &p.min_sigma_radians}},
                  {{"mode_refinement", RefinementFields(&p.mode_refinement)},
                   {"heading_search",
                    {{"window_sigmas", &p.heading_search.window_sigmas},
                     {"max_window_radians", &p.heading_search.max_window_radians},
                     {"step_radians", &p.heading_search.step_radians},
                     {"min_score_ratio", &p.heading_search.min_score_ratio}}}}));
  AnnealingOptions& a = o->annealing;
  SEMCHAIN_RETURN_IF_ERROR(
      ReadSection(root, "annealing",
                  {{"enabled", &a.enabled},
                   {"rule", &a.rule},
                   {"alpha", &a.alpha},
                   {"motion_dominant_alpha", &a.motion_dominant_alpha},
                   {"observation_dominant_alpha", &a.observation_dominant_alpha},
                   {"flat_fraction", &a.flat_fraction}}));
  GeneticResamplingOptions& g = o->genetic;
  return ReadSection(root, "genetic",
                     {{"enabled", &g.enabled},
                      {"high_weight_factor", &g.high_weight_factor},
                      {"low_weight_factor", &g.low_weight_factor},
                      {"crossover_rate_1", &g.crossover_rate_1},
                      {"crossover_rate_2", &g.crossover_rate_2},
                      {"mutation_rate_1", &g.mutation_rate_1},
                      {"mutation_rate_2", &g.mutation_rate_2},
                      {"beta", &g.beta},
                      {"crossover_max_blend", &g.crossover_max_blend},
                      {"crossover_max_distance_meters", &g.crossover_max_distance_meters},
                      {"crossover_max_angle_radians", &g.crossover_max_angle_radians},
                      {"mutation_sigma_meters", &g.mutation_sigma_meters},
                      {"mutation_sigma_radians", &g.mutation_sigma_radians}});
}

Status ReadEveryScan(const yaml::Node& root, EveryScanOptions* e) {
  if (!root.Has("every_scan")) return Status::Ok();
  const Result<yaml::Node> node = root.Get("every_scan");
  if (!node.ok()) return node.status();
  if (node->IsNull()) return Status::Ok();
  if (!node->IsMap()) return node->Error("expected a map");
  SEMCHAIN_RETURN_IF_ERROR(node->CheckKeys(
      {"method", "refinement_passes", "min_matched_points", "match_max_range_meters",
       "match_beam_step", "matcher", "refinement", "search_below_ratio", "typical_window_scans",
       "search_margin_ratio", "search", "prior_sigma_meters", "prior_sigma_radians"}));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(*node, "method", &e->method));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(*node, "refinement_passes", &e->refinement_passes));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(*node, "min_matched_points", &e->min_matched_points));
  SEMCHAIN_RETURN_IF_ERROR(
      yaml::ReadOptional(*node, "match_max_range_meters", &e->match_max_range_meters));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(*node, "match_beam_step", &e->match_beam_step));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(*node, "search_below_ratio", &e->search_below_ratio));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(*node, "prior_sigma_meters", &e->prior_sigma_meters));
  SEMCHAIN_RETURN_IF_ERROR(
      yaml::ReadOptional(*node, "prior_sigma_radians", &e->prior_sigma_radians));
  SEMCHAIN_RETURN_IF_ERROR(
      yaml::ReadOptional(*node, "typical_window_scans", &e->typical_window_scans));
  SEMCHAIN_RETURN_IF_ERROR(
      yaml::ReadOptional(*node, "search_margin_ratio", &e->search_margin_ratio));
  CorrelativeSearchOptions& w = e->search;
  SEMCHAIN_RETURN_IF_ERROR(ReadSection(*node, "search",
                                       {{"linear_window_meters", &w.linear_window_meters},
                                        {"angular_window_radians", &w.angular_window_radians},
                                        {"linear_step_meters", &w.linear_step_meters},
                                        {"angular_step_radians", &w.angular_step_radians},
                                        {"beam_step", &w.beam_step}},
                                       {{"refinement", MatcherFields(&w.refinement)}}));
  SEMCHAIN_RETURN_IF_ERROR(ReadSection(*node, "refinement", RefinementFields(&e->refinement)));
  return ReadSection(*node, "matcher", MatcherFields(&e->matcher));
}

// pose_graph.loop_loss: none, huber, cauchy or dcs (dynamic covariance scaling).
Status ReadLoopLoss(const yaml::Node& root, PoseGraphOptions* optimizer) {
  if (!root.Has("pose_graph")) return Status::Ok();
  const Result<yaml::Node> node = root.Get("pose_graph");
  if (!node.ok()) return node.status();
  if (!node->IsMap() || !node->Has("loop_loss")) return Status::Ok();
  const Result<yaml::Node> value = node->Get("loop_loss");
  if (!value.ok()) return value.status();
  std::string name;
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(*node, "loop_loss", &name));
  const std::pair<const char*, RobustLoss> losses[] = {
      {"none", RobustLoss::kNone},
      {"huber", RobustLoss::kHuber},
      {"cauchy", RobustLoss::kCauchy},
      {"dcs", RobustLoss::kDynamicCovarianceScaling}};
  for (const auto& [known, loss] : losses) {
    if (name == known) {
      optimizer->loop_loss = loss;
      return Status::Ok();
    }
  }
  return value->Error("loop_loss must be none, huber, cauchy or dcs, not '" + name + "'");
}

// pose_graph: {enabled, submap_travel_meters, ...}: the pose graph behind the filter.
Status ReadPoseGraph(const yaml::Node& root, SlamOptions* options) {
  LoopClosureOptions& l = options->loop_closure;
  SEMCHAIN_RETURN_IF_ERROR(ReadLoopLoss(root, &l.optimizer));
  std::string loop_loss;  // read above; listed so that the key is allowed
  return ReadSection(root, "pose_graph",
                     {{"enabled", &options->pose_graph},
                      {"loop_loss", &loop_loss},
                      {"loop_loss_scale", &l.optimizer.loop_loss_scale},
                      {"dcs_phi", &l.optimizer.dcs_phi},
                      {"submap_travel_meters", &l.submap_travel_meters},
                      {"min_loop_travel_meters", &l.min_loop_travel_meters},
                      {"search_every_nodes", &l.search_every_nodes},
                      {"max_built_submaps", &l.max_built_submaps},
                      {"max_built_submaps_megabytes", &l.max_built_submaps_megabytes},
                      {"window_sigmas", &l.window_sigmas},
                      {"linear_window_meters", &l.linear_window_meters},
                      {"max_linear_window_meters", &l.max_linear_window_meters},
                      {"angular_window_radians", &l.angular_window_radians},
                      {"max_angular_window_radians", &l.max_angular_window_radians},
                      {"gate_sigmas", &l.gate_sigmas},
                      {"confirm_within_meters", &l.confirm_within_meters},
                      {"confirm_every_closure", &l.confirm_every_closure},
                      {"corridor_confirmation", &l.corridor_confirmation},
                      {"confirm_min_separation_meters", &l.confirm_min_separation_meters},
                      {"min_score", &l.min_score},
                      {"consistent_min_score", &l.consistent_min_score},
                      {"min_points", &l.min_points},
                      {"match_max_range_meters", &l.match_max_range_meters},
                      {"match_beam_step", &l.match_beam_step},
                      {"query_travel_meters", &l.query_travel_meters},
                      {"query_cell_meters", &l.query_cell_meters},
                      {"unknown_is_neutral", &l.unknown_is_neutral},
                      {"min_known_fraction", &l.min_known_fraction},
                      {"match_covariance", &l.match_covariance},
                      {"covariance_window_meters", &l.covariance.window_meters},
                      {"covariance_window_radians", &l.covariance.window_radians},
                      {"covariance_score_drop", &l.covariance.score_drop},
                      {"max_residual_sigmas", &l.max_residual_sigmas},
                      {"odometry_sigma_meters", &l.odometry_sigma_meters},
                      {"odometry_sigma_per_meter", &l.odometry_sigma_per_meter},
                      {"odometry_sigma_radians", &l.odometry_sigma_radians},
                      {"odometry_sigma_radians_per_radian", &l.odometry_sigma_radians_per_radian},
                      {"loop_sigma_meters", &l.loop_sigma_meters},
                      {"loop_sigma_radians", &l.loop_sigma_radians},
                      {"snap_sigmas", &l.snap_sigmas},
                      {"adapt_motion_noise", &l.adapt_motion_noise},
                      {"min_motion_noise_scale", &l.min_motion_noise_scale},
                      {"max_motion_noise_scale", &l.max_motion_noise_scale},
                      {"online", &l.online},
                      {"online_lag_nodes", &l.online_lag_nodes},
                      {"background", &l.background},
                      {"follow_min_shift_meters", &l.follow_min_shift_meters},
                      {"follow_min_turn_radians", &l.follow_min_turn_radians}});
}

Status ReadLaserOdometry(const yaml::Node& root, LaserOdometryOptions* l) {
  return ReadSection(root, "laser_odometry",
                     {{"enabled", &l->enabled},
                      {"scans_per_submap", &l->scans_per_submap},
                      {"min_matched_points", &l->min_matched_points},
                      {"match_max_range_meters", &l->match_max_range_meters},
                      {"match_beam_step", &l->match_beam_step}},
                     {{"matcher", MatcherFields(&l->matcher)},
                      {"refinement", RefinementFields(&l->refinement)},
                      {"prior", MotionFields(&l->prior)}});
}

}  // namespace

Status ReadSlamOptions(const yaml::Node& root, SlamOptions* options) {
  if (root.IsNull()) return Status::Ok();
  if (!root.IsMap()) return root.Error("expected a map of SLAM options");
  RbpfOptions& o = options->rbpf;
  SEMCHAIN_RETURN_IF_ERROR(root.CheckKeys({"particles",
                                           "seed",
                                           "threads",
                                           "linear_update_meters",
                                           "angular_update_radians",
                                           "resample_threshold",
                                           "weight_gain",
                                           "match_max_range_meters",
                                           "match_beam_step",
                                           "grid",
                                           "scan",
                                           "likelihood_field",
                                           "matcher",
                                           "motion",
                                           "proposal",
                                           "annealing",
                                           "genetic",
                                           "every_scan",
                                           "laser_odometry",
                                           "pose_graph"}));
  int seed = static_cast<int>(o.seed);
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "particles", &o.particles));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "seed", &seed));
  if (seed < 0) return root.Error("seed must be >= 0");
  o.seed = static_cast<std::uint64_t>(seed);
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "threads", &o.threads));
  SEMCHAIN_RETURN_IF_ERROR(
      yaml::ReadOptional(root, "linear_update_meters", &o.linear_update_meters));
  SEMCHAIN_RETURN_IF_ERROR(
      yaml::ReadOptional(root, "angular_update_radians", &o.angular_update_radians));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "resample_threshold", &o.resample_threshold));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "weight_gain", &o.weight_gain));
  SEMCHAIN_RETURN_IF_ERROR(
      yaml::ReadOptional(root, "match_max_range_meters", &o.match_max_range_meters));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(root, "match_beam_step", &o.match_beam_step));
  SEMCHAIN_RETURN_IF_ERROR(ReadModelSections(root, &o));
  SEMCHAIN_RETURN_IF_ERROR(ReadFilterSections(root, &o));
  SEMCHAIN_RETURN_IF_ERROR(ReadEveryScan(root, &options->every_scan));
  SEMCHAIN_RETURN_IF_ERROR(ReadLaserOdometry(root, &options->laser_odometry));
  SEMCHAIN_RETURN_IF_ERROR(ReadPoseGraph(root, options));
  std::string error;
  if (!options->Validate(&error)) return root.Error(error);
  return Status::Ok();
}

Status LoadSlamOptions(const std::filesystem::path& path, SlamOptions* options) {
  const Result<yaml::Node> root = yaml::Node::LoadFile(path);
  if (!root.ok()) return root.status();
  return ReadSlamOptions(*root, options);
}

Status ApplyVariant(const std::string& variant, SlamOptions* options) {
  if (variant != "plain" && variant != "annealing" && variant != "genetic" && variant != "both") {
    return Status::Error("unknown variant '" + variant +
                         "' (expected plain, annealing, genetic or both)");
  }
  options->rbpf.annealing.enabled = variant == "annealing" || variant == "both";
  options->rbpf.genetic.enabled = variant == "genetic" || variant == "both";
  return Status::Ok();
}

}  // namespace semchain::mapping
