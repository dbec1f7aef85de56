#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/match_grid.h"
#include "mapping/precomputation_grid.h"
#include "mapping/translation_pyramid.h"

// Branch-and-bound scan matching (Hess et al., "Real-Time Loop Closure in 2D LIDAR SLAM",
// ICRA 2016, Algorithm 3; Cartographer's FastCorrelativeScanMatcher2D): the exhaustive search of
// a window of poses (x, y, θ) on a grid of steps (one map cell, one angular step), made fast by
// scoring a node that covers 2^h × 2^h translations on the precomputation grid of height h, an
// upper bound, and pruning every node whose bound is below the best score found. It finds the
// same optimum as the exhaustive search of the same discretisation. With a prior pose it searches
// a window around it (seed 001 §2.2); without one the window is the whole map (global
// relocalization, Cartographer's MatchFullSubmap).
namespace semchain::mapping {

struct BranchAndBoundOptions {
  // Height of the search tree: the coarsest node covers 2^depth × 2^depth cells (Cartographer's
  // branch_and_bound_depth, default 7).
  int branch_and_bound_depth = 7;
  // Angular step; 0 derives it from the farthest point as Cartographer does, so that the
  // farthest return moves by at most one cell between steps: acos(1 − r² / (2 d_max²)).
  double angular_step_radians = 0.0;

  bool Validate(std::string* error) const;
};

// A search window around 'center': x and y within ±linear_window_meters, θ within
// ±angular_window_radians (π or more searches every heading once).
struct SearchWindow {
  Pose2 center;
  double linear_window_meters = 7.0;     // Cartographer's linear_search_window
  double angular_window_radians = 0.52;  // 30°, Cartographer's angular_search_window
  // The headings within this of the centre's were searched before with the same translations:
  // a search widened in heading only skips them (the same angular steps, the same points).
  // 0 searches them all; ignored when the window covers every heading.
  double searched_angular_window_radians = 0.0;
};

struct BranchAndBoundResult {
  bool found = false;  // a pose scored at least the minimum score
  Pose2 pose;          // the best pose (valid when found)
  double score = 0.0;  // mean M over the points at 'pose', in [0, 1]
  // The best pose lies on the window's border, at an outermost translation or an outermost
  // heading: the optimum may be outside the window in that dimension.
  bool on_linear_edge = false;
  bool on_angular_edge = false;
  // Work counters: nodes scored (every level), the root nodes, the angles searched, CPU time.
  std::int64_t nodes_scored = 0;
  std::int64_t root_nodes = 0;
  int angles = 0;
  double cpu_seconds = 0.0;
};

class BranchAndBoundMatcher {
 public:
  // Builds the precomputation grids of 'grid' (which must outlive this object).
  BranchAndBoundMatcher(const MatchGrid& grid, const BranchAndBoundOptions& options = {});
  BranchAndBoundMatcher(const BranchAndBoundMatcher&) = delete;
  BranchAndBoundMatcher& operator=(const BranchAndBoundMatcher&) = delete;

  // The best pose of 'points' (returns in the robot frame, metres) within 'window' whose score
  // is at least 'min_score'. With 'allowed' (cells as the match grid's), only translations on
  // its allowed cells are searched, and nodes holding none are dropped unscored.
  BranchAndBoundResult Match(const std::vector<Eigen::Vector2d>& points, const SearchWindow& window,
                             double min_score, const TranslationPyramid* allowed = nullptr) const;
  // The same over the whole map and every heading (no prior).
  BranchAndBoundResult MatchFullMap(const std::vector<Eigen::Vector2d>& points, double min_score,
                                    const TranslationPyramid* allowed = nullptr) const;
  // The exhaustive search of the same discretisation as Match (for tests and comparison).
  BranchAndBoundResult MatchExhaustive(const std::vector<Eigen::Vector2d>& points,
                                       const SearchWindow& window) const;

  const MatchGrid& grid() const { return grid_; }
  // Memory held by the precomputation grids.
  std::size_t precomputation_bytes() const { return stack_.bytes(); }

 private:
  struct Discretization;
  Discretization Discretize(const std::vector<Eigen::Vector2d>& points,
                            const SearchWindow& window) const;

  const MatchGrid& grid_;
  BranchAndBoundOptions options_;
  PrecomputationGridStack stack_;
};

}  // namespace semchain::mapping
