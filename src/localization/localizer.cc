#include "localization/localizer.h"

#include <cmath>
#include <utility>

#include "core/angles.h"
#include "core/check.h"
#include "core/cpu_time.h"
#include "core/rng.h"
#include "localization/localizer_hypotheses.h"

namespace semchain::localization {
namespace {

// The covariance of a renewed prior, relative to the pre-localization's.
constexpr double kRenewedPriorScale = 4.0;

}  // namespace

const char* LocalizerStateName(LocalizerState state) {
  switch (state) {
    case LocalizerState::kLost:
      return "lost";
    case LocalizerState::kHypothesesPending:
      return "hypotheses_pending";
    case LocalizerState::kTracking:
      return "tracking";
  }
  return "lost";
}

Localizer::Localizer(const LocalizerMap& map, LocalizationMethod method,
                     const LocalizerOptions& options)
    : map_(map),
      method_(method),
      options_(options),
      amcl_(map.localization, map.amcl_options, MakeRng(options.seed, 1)),
      memory_(options.memory),
      decision_gate_(map.prelocalizer,
                     {options.decision_confirmations, options.decide_on_new_evidence,
                      options.memory.max_travel, options.decision_min_laser_score}) {
  std::string error;
  SEMCHAIN_CHECK(options_.scan_tracking.Validate(&error));
  if (!IsScanMatcherMethod(method_)) amcl_.InitializeGlobal();
}

void Localizer::AddFrame(LocalizerFrame frame) { pending_frames_.push_back(std::move(frame)); }

int Localizer::AddScan(const StampedScan& scan) {
  scan_points_.reset();
  if (pending_initial_pose_) {
    last_odometry_ = scan.odometry;
    const auto [pose, covariance] = *std::exchange(pending_initial_pose_, std::nullopt);
    SetInitialPose(pose, covariance);
  }
  // The frame taken at this scan, if any.
  std::optional<LocalizerFrame> frame;
  while (!pending_frames_.empty() && pending_frames_.front().stamp <= scan.scan.timestamp + 1e-6) {
    frame = std::move(pending_frames_.front());
    pending_frames_.pop_front();
  }
  const int iterations = Step(scan, frame ? &*frame : nullptr);
  last_odometry_ = scan.odometry;
  ++statistics_.scans;
  statistics_.iterations += iterations;
  return iterations;
}

void Localizer::SetInitialPose(const Pose2& pose, const Eigen::Matrix3d& covariance) {
  if (!last_odometry_) {
    pending_initial_pose_.emplace(pose, covariance);
    return;
  }
  const Pose2 odometry = *last_odometry_;
  memory_.Clear();
  decision_gate_.Reset();
  prior_.reset();
  amcl_.ClearPosePrior();
  if (IsScanMatcherMethod(method_)) {
    StartTracking(odometry, pose, /*pose_given=*/true);
    return;
  }
  amcl_.InitializePose(pose, SampleableCovariance(covariance));
  seeded_ = true;
  pose_given_ = true;
  StopScanTracking();
  filter_ = Sighting{pose, odometry};
  estimate_ = pose;
}

void Localizer::RelocalizeGlobally() {
  pending_initial_pose_.reset();
  // Objects remembered by odometry sit where they were seen relative to the old pose; after a
  // kidnap they would place the robot wrongly.
  memory_.Clear();
  prior_.reset();
  hypotheses_.clear();
  amcl_.ClearPosePrior();
  estimate_.reset();
  filter_.reset();
  seeded_ = false;
  pose_given_ = false;
  StopScanTracking();
  undecided_ = false;
  decision_gate_.Reset();
  decided_places_.clear();
  if (IsScanMatcherMethod(method_)) {
    ResetSearch();
  } else {
    amcl_.InitializeGlobal();
  }
}

void Localizer::ResetSearch() {
  tracking_ = false;
  start_odometry_.reset();
  last_heading_ = 0.0;
  turned_ = 0.0;
  single_object_tried_ = false;
  undecided_ = false;
  decision_gate_.Reset();
}

Eigen::Matrix3d Localizer::covariance() const {
  if (IsScanMatcherMethod(method_) && !tracking_) return Eigen::Matrix3d::Zero();
  return amcl_.Estimate().covariance;
}

const std::vector<Particle>& Localizer::particles() const {
  static const std::vector<Particle> kNone;
  if (IsScanMatcherMethod(method_) && !tracking_) return kNone;
  return amcl_.particles();
}

LocalizerState Localizer::state() const {
  if (IsScanMatcherMethod(method_)) {
    if (tracking_) return LocalizerState::kTracking;
    return undecided_ ? LocalizerState::kHypothesesPending : LocalizerState::kLost;
  }
  if (!estimate_) return LocalizerState::kLost;
  // Localized as the failure detector sees it: the heaviest cluster holds 90 % of the weight
  // within convergence_distance (nav2's "every particle within it" is rarely met by 2000
  // particles under nav2's odometry noise), and it has not collapsed since; and the objects
  // seen do not leave a look-alike place as likely.
  if (amcl_.failure_detector().armed() && !amcl_.FailureDetected() && !undecided_) {
    return LocalizerState::kTracking;
  }
  return seeded_ ? LocalizerState::kHypothesesPending : LocalizerState::kLost;
}

int Localizer::Step(const StampedScan& scan, const LocalizerFrame* frame) {
  switch (method_) {
    case LocalizationMethod::kAmcl:
      return Track(scan);
    case LocalizationMethod::kSemanticAmcl:
    case LocalizationMethod::kSemanticAmclBow:
      return StepSemanticAmcl(scan, frame);
    case LocalizationMethod::kSemanticScanMatch:
    case LocalizationMethod::kScanMatchGlobal:
      return StepScanMatcher(scan, frame);
  }
  return 0;
}

int Localizer::StepSemanticAmcl(const StampedScan& scan, const LocalizerFrame* frame) {
  // Every frame with two objects in view is a semantic measurement: the first seeds the
  // particles, each later one renews the prior; between frames the prior moves with the
  // odometry (the robot turns between frames, the prior's heading must follow).
  if (frame) {
    const std::vector<ObservedObject> observed = Observe(scan, *frame);
    const bool bow = method_ == LocalizationMethod::kSemanticAmclBow;
    std::vector<PoseCandidate> candidates = PreLocalize(scan, observed, 0, !bow);
    int hidden_objects = 0;
    if (bow) {
      // Seed 000 §3.1 step 3: where the objects in view do not place the robot — no mapped pair
      // among them, or look-alike places that explain them alike (an object that would tell
      // the places apart hidden) — the object the bag of words names hidden decides. Its
      // neighbours' pair is taken whenever it explains as many of the objects seen: it explains
      // the hidden one too, which the laser's preference between look-alike places does not.
      std::vector<PoseCandidate> hidden = PreLocalizeHidden(scan, *frame, observed);
      if (!hidden.empty() &&
          (candidates.empty() || hidden.front().agreeing >= candidates.front().agreeing)) {
        candidates = std::move(hidden);
        hidden_objects = 1;
      }
      NoteHypotheses(candidates);
    }
    if (!candidates.empty()) {
      const bool decided = NoteDecided(candidates, scan.odometry, hidden_objects);
      if (decided) NoteAccepted(candidates.front());
      // A filter that converged on a look-alike place while the objects did not tell the
      // places apart is moved once they do.
      const bool relocate = seeded_ && decided && LockedOnLookAlike(scan, observed, candidates);
      if (relocate) ++statistics_.lock_corrections;
      if (decided) {
        NoteDecidedPlace(candidates.front().pose, scan.odometry);
        // The objects decided: the filter is held to the places explaining as many of them as
        // the best (the laser fits look-alike places alike, and where the mapping run left the
        // robot's corner unseen, a look-alike's walls better).
        KeepMostExplaining(&candidates);
      }
      prior_ = ToHypotheses(candidates);
      prior_odometry_ = scan.odometry;
      if (!seeded_ || amcl_.FailureDetected() || relocate) {
        amcl_.InitializeFromHypotheses(*prior_);
        filter_.reset();
        seeded_ = true;
        pose_given_ = false;
        StopScanTracking();
      } else {
        // Once seeded, the prior only has to keep the filter in the right place; a looser one
        // leaves the fine pose to the laser.
        for (PoseHypothesis& h : *prior_) h.covariance *= kRenewedPriorScale;
      }
    }
  }
  if (prior_) {
    std::vector<PoseHypothesis> moved = *prior_;
    const Pose2 motion = prior_odometry_.Between(scan.odometry);
    for (PoseHypothesis& h : moved) h.pose = h.pose * motion;
    amcl_.SetPosePrior(moved);
  }
  return Track(scan);
}

// Scan-matcher methods: relocalize, then track (semantic-scanmatch re-checking the lock).
int Localizer::StepScanMatcher(const StampedScan& scan, const LocalizerFrame* frame) {
  const bool semantic = method_ == LocalizationMethod::kSemanticScanMatch;
  if (!tracking_) {
    NoteTurn(scan);
    // Before a full turn, a scan without a frame gives the semantic method nothing to search;
    // it is not timed (the thread CPU clock is a system call, ~0.5 µs, all it would measure).
    if (semantic && !frame && !FullTurn()) return 0;
    const double search_start = ThreadCpuSeconds();
    std::optional<RelocalizationResult> result = Relocalize(scan, frame);
    statistics_.search_cpu_seconds += ThreadCpuSeconds() - search_start;
    if (!result) return 0;
    if (!result->success) return 1;
    StartTracking(scan.odometry, result->pose);
    return 1;
  }
  const int updates = Track(scan);
  if (frame && semantic && options_.recheck_lock) {
    const double search_start = ThreadCpuSeconds();
    const bool moved = RecheckLock(scan, *frame);
    statistics_.search_cpu_seconds += ThreadCpuSeconds() - search_start;
    return updates + (moved ? 1 : 0);
  }
  return updates;
}

void Localizer::StartTracking(const Pose2& odometry, const Pose2& pose, bool pose_given) {
  amcl_.InitializePose(pose, TrackingCovariance());
  tracking_ = true;
  pose_given_ = pose_given;
  StopScanTracking();  // it starts afresh from this pose
  fruitless_recheck_.reset();
  filter_ = Sighting{pose, odometry};
  estimate_ = pose;
}

// Adds the turn since the last scan to what the robot turned while lost.
void Localizer::NoteTurn(const StampedScan& scan) {
  if (start_odometry_) {
    turned_ += std::abs(NormalizeAngle(scan.odometry.theta - last_heading_));
  } else {
    start_odometry_ = scan.odometry;
  }
  last_heading_ = scan.odometry.theta;
}

bool Localizer::FullTurn() const { return turned_ >= 2.0 * M_PI; }

// One relocalization attempt of a scan-matcher method; nothing when it waits for a prior.
std::optional<RelocalizationResult> Localizer::Relocalize(const StampedScan& scan,
                                                          const LocalizerFrame* frame) {
  if (method_ == LocalizationMethod::kScanMatchGlobal) {
    return map_.matcher.RelocalizeGlobal(ScanPoints(scan));
  }
  std::vector<PoseCandidate> candidates;
  std::vector<ObservedObject> observed;
  if (frame) {
    observed = Observe(scan, *frame);
    candidates = PreLocalize(scan, observed);
  }
  const bool full_turn = FullTurn();
  if (!candidates.empty()) {
    const bool decided = NoteDecided(candidates, scan.odometry);
    if (!decided && !full_turn) {
      // Not sure yet: a look-alike place explains the objects seen as well; the turn goes on
      // and shows more of them. After a full turn everything around has been seen, and the best
      // match that fits the laser is taken (the lock re-check corrects it should later objects
      // rule it out).
      return std::nullopt;
    }
    if (!decided) {
      // Taken undecided, a place still needs the laser fit a decision needs (DecisionGate): the
      // one frame's best may be a look-alike the objects fit by chance and the walls do not
      // (lab_loop seed 3, a development seed, trial 32: 0.38 after the turn, where the right place
      // stood out with 0.99 but had no confirmation yet). None fits: wait for the next frame.
      std::erase_if(candidates, [&](const PoseCandidate& c) {
        return c.laser_score < options_.decision_min_laser_score;
      });
      if (candidates.empty()) return std::nullopt;
    }
    NoteAccepted(candidates.front());
  }
  if (candidates.empty() && full_turn && options_.single_object && !single_object_tried_) {
    // Once: the circles give many windows, and a turn's objects are all remembered (also when
    // this scan has no frame or its frame shows nothing).
    if (observed.empty() && options_.observation_memory) observed = memory_.Recall(scan.odometry);
    if (!observed.empty()) {
      single_object_tried_ = true;
      candidates = PreLocalizeSingle(scan, observed);
    }
  }
  if (!candidates.empty()) {
    // The laser fits look-alike places alike: it only chooses among the hypotheses that explain
    // the most objects.
    KeepMostExplaining(&candidates);
    return map_.matcher.Relocalize(ScanPoints(scan), ToHypotheses(candidates));
  }
  // Without a semantic prior after a full turn (no two objects in view anywhere around), the
  // whole map is searched, as a robot would rather than stay lost.
  if (full_turn) return map_.matcher.RelocalizeGlobal(ScanPoints(scan));
  return std::nullopt;
}

// One AMCL step. The filter updates only after the robot moved update_min_d / turned
// update_min_a; in between, as nav2 publishes map → odom, the pose is the last filter pose moved
// on by odometry. With scan tracking active the scan is matched against the map from the last
// scan's pose moved on by odometry; a match is the pose, and the filter, when it updated, is
// moved onto it.
int Localizer::Track(const StampedScan& scan) {
  const std::optional<Pose2> predicted =
      filter_ ? std::optional<Pose2>(filter_->At(scan.odometry)) : std::nullopt;
  const bool updated = amcl_.ProcessScan(scan.scan, scan.odometry, scan.LaserOffset());
  if (updated || !filter_) filter_ = Sighting{amcl_.Estimate().pose, scan.odometry};
  if (!scan_tracking_ && ScanTrackingMayStart()) {
    StopScanTracking();  // a fresh start
    scan_tracking_ = true;
  }
  if (scan_tracking_) {
    const ScanTrackingResult match =
        TrackScan(map_.matcher,
                  map_.matcher.MatchPoints(scan.scan, scan.LaserOffset(),
                                           options_.scan_tracking.point_spacing_meters),
                  ScanTrackingPredictions(scan, predicted),
                  ScanTrackingThresholds(options_.scan_tracking, typical_score_));
    ++statistics_.scan_match_tries;
    if (match.searched) ++statistics_.scan_match_searches;
    if (match.matched) {
      ++statistics_.scan_matches;
      scan_misses_ = 0;
      typical_score_ += options_.scan_tracking.typical_score_gain * (match.score - typical_score_);
      if (updated) amcl_.Recenter(match.pose);
      filter_ = Sighting{match.pose, scan.odometry};
      if (recent_matches_.size() == 2) recent_matches_.erase(recent_matches_.begin());
      recent_matches_.emplace_back(scan.scan.timestamp, match.pose);
    } else if (++scan_misses_ >= options_.scan_tracking.max_missed_scans) {
      StopScanTracking();
    }
  }
  estimate_ = filter_->At(scan.odometry);
  return updated ? 1 : 0;
}

bool Localizer::ScanTrackingMayStart() const {
  if (!options_.scan_tracking.enabled) return false;
  if (!pose_given_ && !options_.scan_tracking.after_global_localization) return false;
  if (IsScanMatcherMethod(method_)) return tracking_;
  // The filter stands by a pose: it was started at one, or it converged (and its cloud is tight),
  // and it has not collapsed since; and no look-alike place is left as likely.
  if (amcl_.FailureDetected() || undecided_) return false;
  if (pose_given_) return true;
  const Eigen::Matrix3d& c = amcl_.Estimate().covariance;
  const ScanTrackingOptions& o = options_.scan_tracking;
  return amcl_.failure_detector().armed() &&
         std::max(c(0, 0), c(1, 1)) <= o.start_max_sigma_meters * o.start_max_sigma_meters &&
         c(2, 2) <= o.start_max_sigma_radians * o.start_max_sigma_radians;
}

// The odometry's prediction (the last scan's pose moved on by odometry; the filter's pose before
// any), and, when the last two scans were matched, their motion carried on to this scan's stamp:
// MIT CSAIL's odometry jumps by up to 0.7 m and 24° in one scan where the laser shows none.
std::vector<Pose2> Localizer::ScanTrackingPredictions(
    const StampedScan& scan, const std::optional<Pose2>& odometry_prediction) const {
  std::vector<Pose2> predictions = {odometry_prediction.value_or(filter_->pose)};
  if (recent_matches_.size() < 2 || scan_misses_ > 0) return predictions;
  const auto& [t0, p0] = recent_matches_[0];
  const auto& [t1, p1] = recent_matches_[1];
  const double ratio = (scan.scan.timestamp - t1) / (t1 - t0);
  // Logs whose clock stands still or runs back (Intel's) give no speed.
  if (!(t1 > t0 && ratio > 0.0 && ratio <= 3.0)) return predictions;
  predictions.push_back(p1 * Interpolate(Pose2(), p0.Between(p1), ratio));
  return predictions;
}

void Localizer::StopScanTracking() {
  scan_tracking_ = false;
  scan_misses_ = 0;
  typical_score_ = options_.scan_tracking.initial_typical_score;
  recent_matches_.clear();
}

}  // namespace semchain::localization
