#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/pose2.h"
#include "localization/amcl.h"
#include "localization/decision_gate.h"
#include "localization/localization_map.h"
#include "localization/localization_method.h"
#include "localization/localizer_map.h"
#include "localization/localizer_options.h"
#include "localization/observation_memory.h"
#include "localization/prelocalization.h"
#include "localization/scan_match_relocalizer.h"
#include "localization/scan_tracking.h"
#include "localization/sighting.h"
#include "mapping/map_io.h"
#include "semantic/semantic_map.h"
#include "sensors/camera.h"
#include "sensors/detection.h"
#include "sensors/laser_scan.h"

// The relocalization methods of DESIGN.md §4 as one online object: fed odometry with scans and
// camera frames in time order, asked at any moment for the pose, its covariance, the particles
// and its state.
//   amcl                AMCL initialised globally (laser only, nav2 defaults)
//   semantic-amcl       chain pre-localization (seed 000 §3.1) seeds AMCL with Gaussians around
//                       the hypotheses and weights its particles by the prior (seed 000 §3.2);
//                       laser-only AMCL until a frame shows two objects; every later such frame
//                       renews the prior (moved on by odometry in between), and re-seeds the
//                       particles when the filter reports a collapse
//   semantic-amcl-bow   semantic-amcl; when a frame's objects give no hypothesis, the bag of words
//                       finds the most similar keyframe, names the object hidden now and
//                       pre-localizes from its two chain neighbours (seed 000 §3.1 steps 3–4)
//   semantic-scanmatch  the hypotheses bound the window of branch-and-bound + Ceres (seed 001);
//                       after a full turn without two objects in view, windows around
//                       single-object hypotheses, then the whole map
//   scanmatch-global    the same matcher over the whole map (Cartographer-style baseline)
// The semantic methods pre-localize from every object seen during the last turn (see
// ObservationMemory). After a scan matcher has found the robot, AMCL tracks it.
// Whichever the method, once it tracks from an initial pose given (and, with
// ScanTrackingOptions::after_global_localization, once global localization found the robot)
// every scan is also matched against the map from the pose odometry predicts for it
// (scan_tracking.h); a matched scan gives the pose, and the filter's particles are moved onto it
// at its updates (LocalizerOptions::scan_tracking; off: AMCL alone tracks, as nav2 does).
//
//   LocalizerMap map(occupancy, semantic, AmclOptions(), PreLocalizationOptions(),
//                    ScanMatchRelocalizerOptions());
//   Localizer localizer(map, LocalizationMethod::kSemanticScanMatch, LocalizerOptions());
//   localizer.AddFrame(frame);          // whenever the camera gives one
//   localizer.AddScan(scan);            // every scan, with its odometry
//   if (localizer.pose()) use(*localizer.pose(), localizer.covariance());
namespace semchain::localization {

// One camera frame: its detections, and for semantic-amcl-bow its colour image (given, or read
// from 'color_path' when a frame needs it).
struct LocalizerFrame {
  double stamp = 0.0;
  std::vector<Detection> detections;
  MountedCamera camera;  // the camera that saw them, on the robot
  cv::Mat color;
  std::filesystem::path color_path;
};

enum class LocalizerState {
  kLost,               // no pose the method stands by
  kHypothesesPending,  // hypotheses kept, none locked: AMCL seeded by pre-localization whose
                       // particles are not yet on one pose, or look-alike places not told apart
  kTracking,           // the robot found: a scan matcher's match or a converged filter
};
const char* LocalizerStateName(LocalizerState state);

// What the localizer did so far (for benchmarks and diagnostics).
struct LocalizerStatistics {
  int scans = 0;
  int iterations = 0;                          // filter updates and matcher runs
  double search_cpu_seconds = 0.0;             // scan matchers: searching before tracking began
  std::optional<Pose2> first_prelocalization;  // the first pair hypothesis accepted
  int prelocalizations = 0;                    // pre-localizations with ≥ 2 objects
  int single_object_prelocalizations = 0;      // ... with single-object hypotheses
  int hidden_object_prelocalizations = 0;      // ... from a hidden object's neighbours (BoW)
  // ... whose best hypothesis had a look-alike at another place (PreLocalizer::Decided): the
  // method kept the hypotheses and locked onto none.
  int undecided_prelocalizations = 0;
  int lock_corrections = 0;  // tracked poses moved to a place that explains more objects
  int lock_rechecks = 0;     // lock re-checks searched (semantic-scanmatch)
  // Scan-to-map tracking: scans matched (the pose taken from the match), and of those tried,
  // how many needed the window search.
  int scan_matches = 0;
  int scan_match_tries = 0;
  int scan_match_searches = 0;
};

class Localizer {
 public:
  Localizer(const LocalizerMap& map, LocalizationMethod method, const LocalizerOptions& options);
  Localizer(const Localizer&) = delete;
  Localizer& operator=(const Localizer&) = delete;

  // Queues a camera frame; the first scan at or after its stamp uses it (of several frames
  // before one scan, the latest).
  void AddFrame(LocalizerFrame frame);
  // Processes one scan with the odometry at its time; returns the filter updates and matcher
  // runs it took.
  int AddScan(const StampedScan& scan);

  // The robot is at 'pose' (map frame) at the last scan's odometry (before any scan: at the
  // first one's), as /initialpose says.
  void SetInitialPose(const Pose2& pose, const Eigen::Matrix3d& covariance);
  // Forgets where the robot is and searches for it again from the next scan on (a kidnapped
  // robot, /global_localization).
  void RelocalizeGlobally();

  // The pose after the last scan (nothing while the method has no estimate); between filter
  // updates, the filter's last pose moved on by odometry.
  const std::optional<Pose2>& pose() const { return estimate_; }
  // The filter's covariance (x, y, θ) at its last update.
  Eigen::Matrix3d covariance() const;
  // The particles of the method's AMCL (none for a scan matcher still searching).
  const std::vector<Particle>& particles() const;
  LocalizerState state() const;
  // The hypotheses of the latest pre-localization (map frame, at the time they were made).
  const std::vector<PoseHypothesis>& hypotheses() const { return hypotheses_; }
  const LocalizerStatistics& statistics() const { return statistics_; }
  LocalizationMethod method() const { return method_; }
  // The filter, for those who want its counters (read only).
  const Amcl& filter() const { return amcl_; }

 private:
  const std::vector<Eigen::Vector2d>& ScanPoints(const StampedScan& scan) const;
  std::function<double(const Pose2&)> LaserScorer(const StampedScan& scan) const;
  std::function<Pose2(const Pose2&)> LaserRefiner(const StampedScan& scan) const;
  void NoteHypotheses(const std::vector<PoseCandidate>& candidates);
  void NoteAccepted(const PoseCandidate& candidate);
  std::vector<ObservedObject> Observe(const StampedScan& scan, const LocalizerFrame& frame);
  // 'note': the hypotheses count as the method's (hypotheses()); false
  // when the caller may still replace them.
  std::vector<PoseCandidate> PreLocalize(const StampedScan& scan,
                                         const std::vector<ObservedObject>& observed,
                                         int min_agreeing = 0, bool note = true);
  std::vector<PoseCandidate> PreLocalizeSingle(const StampedScan& scan,
                                               const std::vector<ObservedObject>& observed);
  // Hypotheses from the neighbours of the object the bag of words names hidden; not noted (the
  // caller decides whether they replace the pair hypotheses).
  std::vector<PoseCandidate> PreLocalizeHidden(const StampedScan& scan, const LocalizerFrame& frame,
                                               const std::vector<ObservedObject>& observed);
  int Step(const StampedScan& scan, const LocalizerFrame* frame);
  int StepSemanticAmcl(const StampedScan& scan, const LocalizerFrame* frame);
  int StepScanMatcher(const StampedScan& scan, const LocalizerFrame* frame);
  // A scan matcher's lock, or an initial pose given ('pose_given': scan tracking may start).
  void StartTracking(const Pose2& odometry, const Pose2& pose, bool pose_given = false);
  bool RecheckLock(const StampedScan& scan, const LocalizerFrame& frame);
  // Whether the last re-check that found nothing saw what 'observed' shows, at the same tracked
  // pose and count (recheck_on_new_evidence_only).
  bool RecheckedAlready(const StampedScan& scan, const std::vector<ObservedObject>& observed,
                        int explained) const;
  // Notes whether 'candidates' decide between look-alike places; returns it.
  bool NoteDecided(const std::vector<PoseCandidate>& candidates, const Pose2& odometry,
                   int hidden_objects = 0);
  // semantic-amcl: whether the filter sits on a look-alike place that 'candidates' (decided)
  // rule out: they put the robot elsewhere and explain relocate_margin more of the objects
  // seen, or more of them where no pre-localization decided on the filter's place.
  bool LockedOnLookAlike(const StampedScan& scan, const std::vector<ObservedObject>& observed,
                         const std::vector<PoseCandidate>& candidates) const;
  void NoteDecidedPlace(const Pose2& pose, const Pose2& odometry);
  void NoteTurn(const StampedScan& scan);
  bool FullTurn() const;
  std::optional<RelocalizationResult> Relocalize(const StampedScan& scan,
                                                 const LocalizerFrame* frame);
  int Track(const StampedScan& scan);
  // Scan tracking (scan_tracking.h): whether it may start now (the robot found), its
  // predictions for 'scan', and its end.
  bool ScanTrackingMayStart() const;
  std::vector<Pose2> ScanTrackingPredictions(const StampedScan& scan,
                                             const std::optional<Pose2>& odometry_prediction) const;
  void StopScanTracking();
  void ResetSearch();

  const LocalizerMap& map_;
  const LocalizationMethod method_;
  const LocalizerOptions options_;
  Amcl amcl_;
  std::deque<LocalizerFrame> pending_frames_;
  std::optional<Pose2> last_odometry_;  // of the last scan
  // An initial pose given before the first scan, applied at its odometry.
  std::optional<std::pair<Pose2, Eigen::Matrix3d>> pending_initial_pose_;
  std::optional<Pose2> estimate_;
  std::optional<Sighting> filter_;  // the filter's pose at its last update, and the odometry then
  bool seeded_ = false;             // semantic-amcl: the particles came from hypotheses
  bool pose_given_ = false;         // the filter was started at an initial pose (SetInitialPose)
  // Scan tracking: on (scans are matched against the map), scans missed in a row, and the last
  // two matched poses with their scans' stamps (for the prediction carrying on their motion).
  bool scan_tracking_ = false;
  int scan_misses_ = 0;
  double typical_score_ = 0.0;  // the running mean of the matches' scores
  std::vector<std::pair<double, Pose2>> recent_matches_;
  std::optional<Pose2> start_odometry_;
  double last_heading_ = 0.0;
  double turned_ = 0.0;  // radians turned (odometry) before a scan matcher found the robot
  bool tracking_ = false;
  // ScanPoints of the scan being processed (a cache, hence mutable).
  mutable std::optional<std::vector<Eigen::Vector2d>> scan_points_;
  ObservationMemory memory_;
  // The last lock re-check that found nothing: the objects it saw (surfaces in the odometry
  // frame), the tracked pose in the odometry frame (map_from_odometry) and the count that pose
  // explained.
  struct FruitlessRecheck {
    std::vector<ObservedObject> objects;
    Pose2 map_from_odometry;
    int explained = 0;
  };
  std::optional<FruitlessRecheck> fruitless_recheck_;
  bool single_object_tried_ = false;
  // The latest pre-localization did not decide between look-alike places (DecisionGate).
  bool undecided_ = false;
  DecisionGate decision_gate_;
  // semantic-amcl: the places pre-localizations decided on within the observation memory's
  // horizon (NoteDecidedPlace), each as last decided.
  std::vector<Sighting> decided_places_;
  // The latest pre-localization and the odometry when it was made.
  std::optional<std::vector<PoseHypothesis>> prior_;
  Pose2 prior_odometry_;
  std::vector<PoseHypothesis> hypotheses_;
  LocalizerStatistics statistics_;
};

}  // namespace semchain::localization
