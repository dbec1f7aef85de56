#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "localization/pose_hypothesis.h"
#include "mapping/branch_and_bound_matcher.h"
#include "mapping/ceres_scan_matcher.h"
#include "mapping/map_io.h"
#include "mapping/match_grid.h"
#include "mapping/translation_pyramid.h"
#include "sensors/laser_scan.h"

// Scan-matcher relocalization (seed 001 §2.2, Cartographer style): branch-and-bound over the
// map's precomputation grids inside a window around a prior pose (the semantic
// pre-localization), then Ceres refinement of Σ (1 − M(S_i(T)))² on the bicubic grid. Without a
// prior the same matcher searches the whole map: the `scanmatch-global` baseline
// (Cartographer's global relocalization).
namespace semchain::localization {

struct ScanMatchRelocalizerOptions {
  mapping::MatchGridOptions grid;
  mapping::BranchAndBoundOptions branch_and_bound;
  mapping::CeresScanMatcherOptions ceres;
  // A match is accepted when its branch-and-bound score (mean M over the points) reaches this
  // (Cartographer's global_localization_min_score is 0.6 on its probability grids).
  double min_score = 0.6;
  // Returns farther than this are dropped: far returns are sparse and would make the angular
  // step (set by the farthest point) tiny. Cartographer's default max_range is 30 m.
  double max_range_meters = 30.0;
  // Returns closer than this to the previously kept one are dropped (a cheap voxel filter).
  double min_point_spacing_meters = 0.1;
  // With a prior the search first covers a narrow window around each hypothesis, a little more
  // than the pre-localization's typical error (development trials, two_similar_rooms seed 1,
  // its changed world seed 3, long_corridor seed 3, lab_loop seed 5: 117 of 122 first
  // hypotheses within 0.3 m in x and y, 107 within 4°). When it finds no match,
  // the windows are widened in both dimensions to the wide windows below; when its best match
  // lies on the border of the translations or of the headings (the optimum may be outside),
  // only in that dimension, again until the best match is inside or the window is wide in
  // both: the translations to the wide window, the headings to twice the last ones (at most the
  // wide window), searching only the headings not searched yet. A linear window of 0 skips the
  // narrow search.
  double narrow_linear_window_meters = 0.3;
  double narrow_angular_window_radians = 0.07;
  // The wide window is 3σ of the hypothesis' covariance, clamped to these.
  double min_linear_window_meters = 0.5;
  double max_linear_window_meters = 7.0;
  double min_angular_window_radians = 0.2;
  // The global search (no prior) places the robot only on the map's free cells and those
  // within this distance of one (the robot stands where its laser saw free space; the margin
  // covers a laser mounted off the robot's centre), and drops search nodes holding none of
  // them: on a large map most translations lie in walls or unknown space. < 0: the whole map.
  double global_free_space_margin_meters = 0.25;

  bool Validate(std::string* error) const;
};

struct RelocalizationResult {
  bool success = false;  // the branch-and-bound score reached min_score
  Pose2 pose;            // refined pose (valid when success)
  Pose2 coarse_pose;     // branch-and-bound pose
  double score = 0.0;    // branch-and-bound score of the best match (also when it failed)
  int hypothesis = -1;   // which prior hypothesis won (-1: global search)
  // The narrow windows did not settle it: wider ones were searched in translation, in heading
  // or in both.
  bool widened_linear = false;
  bool widened_angular = false;
  // Work: nodes scored in the search trees, headings searched, CPU seconds (search + refinement).
  std::int64_t nodes_scored = 0;
  std::int64_t root_nodes = 0;  // of the last search
  int angles = 0;
  int points = 0;
  double cpu_seconds = 0.0;
};

class ScanMatchRelocalizer {
 public:
  // Builds the match grid and the precomputation grids of 'map' (once per map).
  ScanMatchRelocalizer(const mapping::MapImage& map, const ScanMatchRelocalizerOptions& options);
  ScanMatchRelocalizer(const ScanMatchRelocalizer&) = delete;
  ScanMatchRelocalizer& operator=(const ScanMatchRelocalizer&) = delete;

  // The returns of 'scan' in the robot frame (laser at 'laser_offset'), range-limited and thinned.
  std::vector<Eigen::Vector2d> MatchPoints(const LaserScan& scan, const Pose2& laser_offset) const;
  // The same thinned to 'min_spacing_meters' instead of the options' min_point_spacing_meters.
  std::vector<Eigen::Vector2d> MatchPoints(const LaserScan& scan, const Pose2& laser_offset,
                                           double min_spacing_meters) const;

  // Searches a narrow window around each hypothesis, then, unless that settled it, wider ones
  // (up to 3σ of its covariance, clamped), and returns the best match over all of them, refined.
  RelocalizationResult Relocalize(const LaserScan& scan, const Pose2& laser_offset,
                                  const std::vector<PoseHypothesis>& priors) const;
  // The same for the scan's MatchPoints, made once by a caller that also rates poses with them.
  RelocalizationResult Relocalize(const std::vector<Eigen::Vector2d>& points,
                                  const std::vector<PoseHypothesis>& priors) const;
  // Searches the given window.
  RelocalizationResult RelocalizeInWindow(const LaserScan& scan, const Pose2& laser_offset,
                                          const mapping::SearchWindow& window) const;
  RelocalizationResult RelocalizeInWindow(const std::vector<Eigen::Vector2d>& points,
                                          const mapping::SearchWindow& window) const;
  // The same with the least score a pose needs given by the caller instead of min_score: a
  // tracker whose scans typically score less in a place (clutter, far returns) searches with
  // its own threshold.
  RelocalizationResult RelocalizeInWindow(const std::vector<Eigen::Vector2d>& points,
                                          const mapping::SearchWindow& window,
                                          double min_score) const;
  // Searches the whole map and every heading (no prior).
  RelocalizationResult RelocalizeGlobal(const LaserScan& scan, const Pose2& laser_offset) const;
  RelocalizationResult RelocalizeGlobal(const std::vector<Eigen::Vector2d>& points) const;

  // 'initial' refined for 'points' on the match grid (the Ceres step alone, no search).
  Pose2 Refine(const std::vector<Eigen::Vector2d>& points, const Pose2& initial) const;

  const mapping::MatchGrid& grid() const { return grid_; }

 private:
  // The best match so far over the windows searched around the priors, and the work done.
  struct PriorSearch {
    mapping::BranchAndBoundResult best;
    int hypothesis = -1;
    std::int64_t nodes_scored = 0;
    int angles = 0;
    double cpu_seconds = 0.0;
  };
  // The windows around the priors: translations narrow or wide (3σ); headings the narrow ones
  // × angular_scale, at most the wide ones (infinity: wide).
  struct WindowWidth {
    bool wide_linear = false;
    double angular_scale = 1.0;
  };
  // Searches a window of the given width around each prior, continuing 'search': a window must
  // beat its best so far (it prunes with it), so a wider search after a narrow one only
  // replaces what the narrow one found by something better.
  // 'searched' (may be null): the width searched before with the same translations, whose
  // headings are skipped. Returns whether a better match was found.
  bool SearchPriors(const std::vector<Eigen::Vector2d>& points,
                    const std::vector<PoseHypothesis>& priors, WindowWidth width,
                    const WindowWidth* searched, PriorSearch* search) const;
  mapping::SearchWindow WindowOf(const PoseHypothesis& prior, WindowWidth width) const;
  double WideAngularWindow(const PoseHypothesis& prior) const;
  RelocalizationResult Finish(const std::vector<Eigen::Vector2d>& points,
                              const mapping::BranchAndBoundResult& match) const;

  ScanMatchRelocalizerOptions options_;
  mapping::MatchGrid grid_;
  mapping::BranchAndBoundMatcher matcher_;
  std::optional<mapping::TranslationPyramid> free_space_;  // the global search's translations
};

}  // namespace semchain::localization
