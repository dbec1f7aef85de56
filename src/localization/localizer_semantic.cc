#include <algorithm>
#include <cmath>

#include "bow/bow_occlusion.h"
#include "bow/orb_features.h"
#include "core/angles.h"
#include "io/rgbd_frame_io.h"
#include "localization/localizer.h"
#include "localization/localizer_hypotheses.h"

// What the Localizer makes of the camera's objects: observing them, pre-localizing from pairs,
// single objects and the hidden object the bag of words names, noting the hypotheses and what
// decided between look-alike places, and re-checking a scan matcher's lock against them.
namespace semchain::localization {

const std::vector<Eigen::Vector2d>& Localizer::ScanPoints(const StampedScan& scan) const {
  // Made on first use: most frames yield no hypothesis to rate and no search.
  if (!scan_points_) scan_points_ = map_.matcher.MatchPoints(scan.scan, scan.LaserOffset());
  return *scan_points_;
}

// Rates a pose by how well this scan fits the map there: the mean match-grid value M of its
// returns, as the branch-and-bound search scores a pose (sharp, σ 0.05 m: the hypotheses are
// aligned to their objects first, and a softer fit, σ 0.15 m, ranked look-alike hypotheses a
// few decimetres apart badly, first-hypothesis error 0.20 m instead of 0.15 m on the e2e test's
// trials).
std::function<double(const Pose2&)> Localizer::LaserScorer(const StampedScan& scan) const {
  return [this, &scan](const Pose2& pose) {
    return mapping::CellScore(map_.matcher.grid(), ScanPoints(scan), pose);
  };
}

// Moves a hypothesis to where this scan fits the map best nearby (the scan matcher's Ceres
// refinement): the objects place the robot to about a decimetre, the walls to centimetres.
std::function<Pose2(const Pose2&)> Localizer::LaserRefiner(const StampedScan& scan) const {
  return [this, &scan](const Pose2& pose) { return map_.matcher.Refine(ScanPoints(scan), pose); };
}

void Localizer::NoteHypotheses(const std::vector<PoseCandidate>& candidates) {
  if (candidates.empty()) return;
  hypotheses_ = ToHypotheses(candidates);
}

// The first pair hypothesis the method goes by (the benchmark's pre-localization error, the
// paper's measure): one that stands out, or the best after a full turn left look-alikes undecided.
// Hypotheses kept side by side while undecided are not a pose the method stands by.
void Localizer::NoteAccepted(const PoseCandidate& candidate) {
  if (!statistics_.first_prelocalization) statistics_.first_prelocalization = candidate.pose;
}

bool Localizer::NoteDecided(const std::vector<PoseCandidate>& candidates, const Pose2& odometry,
                            int hidden_objects) {
  undecided_ = !decision_gate_.Update(candidates, odometry, hidden_objects);
  if (undecided_) ++statistics_.undecided_prelocalizations;
  return !undecided_;
}

bool Localizer::LockedOnLookAlike(const StampedScan& scan,
                                  const std::vector<ObservedObject>& observed,
                                  const std::vector<PoseCandidate>& candidates) const {
  if (!filter_ || candidates.empty()) return false;
  // The filter's pose now (its last update moved on by odometry), as the objects were seen.
  const Pose2 now = filter_->At(scan.odometry);
  const PoseCandidate& best = candidates.front();
  if (!map_.prelocalizer.DistinctPlaces(best.pose, now)) return false;
  const int explained_now = map_.prelocalizer.Agreeing(observed, now);
  if (explained_now + options_.relocate_margin <= best.agreeing) return true;
  // Particles that gathered at a place while the look-alikes were undecided stand by nothing
  // the objects decided: they follow the decided place once it explains more of the objects.
  const bool decided_before =
      std::any_of(decided_places_.begin(), decided_places_.end(), [&](const Sighting& place) {
        return !map_.prelocalizer.DistinctPlaces(place.At(scan.odometry), now);
      });
  return !decided_before && explained_now < best.agreeing;
}

void Localizer::NoteDecidedPlace(const Pose2& pose, const Pose2& odometry) {
  // Places decided on before the robot moved past the observation memory's horizon were decided
  // on objects it no longer remembers.
  std::erase_if(decided_places_, [&](const Sighting& place) {
    return (place.odometry.translation() - odometry.translation()).norm() >
           options_.memory.max_travel;
  });
  const auto same =
      std::find_if(decided_places_.begin(), decided_places_.end(), [&](const Sighting& place) {
        return !map_.prelocalizer.DistinctPlaces(place.At(odometry), pose);
      });
  if (same != decided_places_.end()) {
    *same = {pose, odometry};
  } else {
    decided_places_.push_back({pose, odometry});
  }
}

// Remembers a frame's objects; returns what pre-localization may use now: nothing when the
// frame shows no object (what is remembered gave its hypotheses when it was seen).
std::vector<ObservedObject> Localizer::Observe(const StampedScan& scan,
                                               const LocalizerFrame& frame) {
  std::vector<ObservedObject> observed =
      ObserveObjects(frame.detections, frame.camera, map_.prelocalizer.options());
  if (!options_.observation_memory) return observed;
  memory_.Add(scan.odometry, observed);  // also when empty: it counts the turn
  if (observed.empty()) return observed;
  return memory_.Recall(scan.odometry);
}

std::vector<PoseCandidate> Localizer::PreLocalize(const StampedScan& scan,
                                                  const std::vector<ObservedObject>& observed,
                                                  int min_agreeing, bool note) {
  if (observed.size() < 2) return {};
  std::vector<PoseCandidate> candidates = map_.prelocalizer.Localize(
      observed, LaserScorer(scan), nullptr, min_agreeing, LaserRefiner(scan));
  ++statistics_.prelocalizations;
  if (note) NoteHypotheses(candidates);
  return candidates;
}

std::vector<PoseCandidate> Localizer::PreLocalizeSingle(
    const StampedScan& scan, const std::vector<ObservedObject>& observed) {
  // Not noted as the first pre-localization: its many circle hypotheses are for the scan matcher
  // to tell apart, and the benchmark's pre-localization error is the paper's (pairs).
  std::vector<PoseCandidate> candidates =
      map_.prelocalizer.LocalizeSingle(observed, LaserScorer(scan), LaserRefiner(scan));
  ++statistics_.single_object_prelocalizations;
  NoteHypotheses(candidates);
  return candidates;
}

// Seed 000 §3.1 steps 3–4: the most similar keyframes name the object hidden now; its two chain
// neighbours, seen now, pre-localize the robot.
std::vector<PoseCandidate> Localizer::PreLocalizeHidden(
    const StampedScan& scan, const LocalizerFrame& frame,
    const std::vector<ObservedObject>& observed) {
  // The hidden object's two chain neighbours must both be in view: a frame with fewer than two
  // detections cannot name one, so its image is not described.
  if (!map_.recognizer || frame.detections.size() < 2) return {};
  cv::Mat image = frame.color;
  if (image.empty()) {
    if (frame.color_path.empty()) return {};
    Result<cv::Mat> read = ReadColorImage(frame.color_path);
    if (!read.ok()) return {};
    image = *read;
  }
  const cv::Mat descriptors = bow::ExtractOrbDescriptors(image, bow::OrbOptions());
  const bow::OcclusionQuery query =
      bow::QueryOccludedObjects(*map_.recognizer, map_.semantic, descriptors, frame.detections);
  const auto& occluded = query.inference.inference.occluded;
  if (occluded.empty()) return {};
  const std::vector<int> neighbours = {occluded.front().upstream, occluded.front().downstream};
  std::vector<PoseCandidate> candidates =
      map_.prelocalizer.Localize(observed, LaserScorer(scan), &neighbours, 0, LaserRefiner(scan));
  ++statistics_.hidden_object_prelocalizations;
  return candidates;
}

// A lock from a look-alike pair explains that pair; as the robot turns, the frames show objects
// it cannot explain. When a frame's pre-localization finds poses, far from the tracked one, that
// explain more of the objects seen, the lock may move there: on the objects' word alone when the
// new place explains relocate_margin more of them (the laser fits look-alike places alike, the
// tracked one, refined by tracking, often a little better), and when it explains fewer more only
// if the scan matcher, searching it beside the tracked pose, also fits it better. Returns whether
// the robot was moved.
bool Localizer::RecheckLock(const StampedScan& scan, const LocalizerFrame& frame) {
  const std::vector<ObservedObject> observed = Observe(scan, frame);
  if (observed.size() < 2) return false;
  // Only poses explaining more than the tracked one are of interest: the others are dropped
  // before the laser rates them.
  const int explained = map_.prelocalizer.Agreeing(observed, *estimate_);
  if (explained >= static_cast<int>(observed.size())) return false;  // none can explain more
  if (options_.recheck_on_new_evidence_only && RecheckedAlready(scan, observed, explained)) {
    return false;
  }
  ++statistics_.lock_rechecks;
  const auto found_nothing = [&] {
    // Assigned, not emplace()d: clang 14 takes a nested struct with default member initialisers
    // for not default-constructible inside its enclosing class's std::optional.
    fruitless_recheck_ = FruitlessRecheck{};
    FruitlessRecheck& memo = *fruitless_recheck_;
    const Eigen::Isometry2d odometry_from_robot = scan.odometry.ToIsometry();
    memo.objects = observed;
    for (ObservedObject& o : memo.objects) o.surface = odometry_from_robot * o.surface;
    memo.map_from_odometry = *estimate_ * scan.odometry.Inverse();
    memo.explained = explained;
    return false;
  };
  const std::vector<PoseCandidate> candidates = PreLocalize(scan, observed, explained + 1);
  std::vector<PoseCandidate> better;
  for (const PoseCandidate& c : candidates) {
    if (map_.prelocalizer.DistinctPlaces(c.pose, *estimate_)) better.push_back(c);
  }
  if (better.empty()) return found_nothing();
  RelocalizationResult result;
  if (better.front().agreeing >= explained + options_.relocate_margin) {
    // Look-alikes among the places that explain more: the objects that tell them apart are
    // still to come.
    if (!map_.prelocalizer.Decided(better)) return found_nothing();
    result = map_.matcher.Relocalize(ScanPoints(scan), ToHypotheses(better));
    if (!result.success) return found_nothing();
  } else {
    std::vector<PoseHypothesis> priors = ToHypotheses(better);
    priors.insert(priors.begin(), {*estimate_, TrackingCovariance(), 1.0});
    result = map_.matcher.Relocalize(ScanPoints(scan), priors);
    if (!result.success || result.hypothesis == 0) return found_nothing();
  }
  StartTracking(scan.odometry, result.pose);
  ++statistics_.lock_corrections;
  return true;
}

bool Localizer::RecheckedAlready(const StampedScan& scan,
                                 const std::vector<ObservedObject>& observed, int explained) const {
  if (!fruitless_recheck_ || fruitless_recheck_->explained != explained) return false;
  const Pose2 shift =
      fruitless_recheck_->map_from_odometry.Inverse() * (*estimate_ * scan.odometry.Inverse());
  if (shift.translation().norm() > options_.recheck_pose_shift ||
      std::abs(NormalizeAngle(shift.theta)) > options_.recheck_pose_turn) {
    return false;
  }
  const Eigen::Isometry2d odometry_from_robot = scan.odometry.ToIsometry();
  return std::all_of(observed.begin(), observed.end(), [&](const ObservedObject& o) {
    ObservedObject at = o;
    at.surface = odometry_from_robot * o.surface;
    return std::any_of(fruitless_recheck_->objects.begin(), fruitless_recheck_->objects.end(),
                       [&](const ObservedObject& seen) {
                         return SameObject(seen, at, options_.memory.same_object_distance);
                       });
  });
}

}  // namespace semchain::localization
