#include "semantic/semantic_options.h"

namespace semchain::semantic {

std::map<std::string, ClassShapePrior> DefaultClassPriors() {
  using Shape = ClassShapePrior::Shape;
  std::map<std::string, ClassShapePrior> priors;
  priors["door"] = {Shape::kBox, 0.9, 0.05, 0.0, 0.05};
  priors["cabinet"] = {Shape::kBox, 0.6, 0.4, 0.0, 0.05};
  priors["bucket"] = {Shape::kCircle, 0.0, 0.0, 0.15, 0.03};
  priors["chair"] = {Shape::kBox, 0.5, 0.5, 0.0, 0.05};
  priors["stool"] = {Shape::kCircle, 0.0, 0.0, 0.17, 0.03};
  priors["table"] = {Shape::kBox, 1.2, 0.75, 0.0, 0.05};
  priors["sofa"] = {Shape::kBox, 1.8, 0.88, 0.0, 0.05};
  priors["computer"] = {Shape::kBox, 0.5, 0.22, 0.0, 0.05};
  priors["bed"] = {Shape::kBox, 1.4, 2.0, 0.0, 0.05};
  priors["clock"] = {Shape::kBox, 0.32, 0.05, 0.0, 0.03};
  return priors;
}

ClassShapePrior SemanticMapOptions::PriorOf(const std::string& class_name) const {
  const auto it = priors.find(class_name);
  return it == priors.end() ? ClassShapePrior{} : it->second;
}

bool SemanticMapOptions::Validate(std::string* error) const {
  const auto fail = [error](const std::string& message) {
    *error = message;
    return false;
  };
  if (!(grid.hit_log_odds > 0.0)) return fail("grid.hit_log_odds must be positive");
  if (!(grid.miss_log_odds < 0.0)) return fail("grid.miss_log_odds must be negative");
  if (!(grid.undetected_log_odds <= 0.0)) return fail("grid.undetected_log_odds must be <= 0");
  if (!(grid.max_abs_log_odds > 0.0)) return fail("grid.max_abs_log_odds must be positive");
  if (points.pixel_stride < 1) return fail("points.pixel_stride must be at least 1");
  if (!(points.box_trim_fraction >= 0.0 && points.box_trim_fraction < 0.5)) {
    return fail("points.box_trim_fraction must be in [0, 0.5)");
  }
  if (!(points.min_depth_gate > 0.0 && points.max_depth_gate >= points.min_depth_gate)) {
    return fail("points: need 0 < min_depth_gate <= max_depth_gate");
  }
  if (free_space.column_stride < 1) return fail("free_space.column_stride must be at least 1");
  if (!(extraction.occupied_probability > 0.5 && extraction.occupied_probability < 1.0)) {
    return fail("extraction.occupied_probability must be in (0.5, 1)");
  }
  if (extraction.min_split_frames < 1) return fail("extraction.min_split_frames must be >= 1");
  if (!(extraction.min_split_share >= 0.0 && extraction.min_split_share <= 1.0)) {
    return fail("extraction.min_split_share must be in [0, 1]");
  }
  if (extraction.merge_gap_cells < 0) return fail("extraction.merge_gap_cells must be >= 0");
  if (!(extraction.fragment_fraction >= 0.0)) {
    return fail("extraction.fragment_fraction must be >= 0");
  }
  if (!(extraction.merge_center_fraction >= 0.0)) {
    return fail("extraction.merge_center_fraction must be >= 0");
  }
  if (!(extraction.merge_overlap > 0.0)) return fail("extraction.merge_overlap must be positive");
  if (!(extraction.max_extent_factor >= 1.0)) {
    return fail("extraction.max_extent_factor must be at least 1");
  }
  if (!(extraction.merge_across_classes > 0.0)) {
    return fail("extraction.merge_across_classes must be positive");
  }
  if (!(chain.doorway_half_width > 0.0)) return fail("chain.doorway_half_width must be positive");
  if (chain.neighbours < 0) return fail("chain.neighbours must not be negative");
  for (const auto& [name, prior] : priors) {
    const bool box = prior.shape == ClassShapePrior::Shape::kBox;
    if (box ? !(prior.width > 0.0 && prior.depth > 0.0) : !(prior.radius > 0.0)) {
      return fail("priors." + name + ": sizes must be positive");
    }
    if (!(prior.size_std > 0.0)) return fail("priors." + name + ".size_std must be positive");
  }
  if (!(pose_tolerance >= 0.0 && max_pose_gap > 0.0)) return fail("pose tolerances invalid");
  return true;
}

}  // namespace semchain::semantic
