#include "eval/reloc_methods.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/angles.h"
#include "core/cpu_time.h"
#include "io/rgbd_frame_io.h"
#include "semantic/bow_occlusion.h"
#include "semantic/orb_features.h"

namespace semchain::eval {
namespace {

std::vector<localization::PoseHypothesis> ToHypotheses(
    const std::vector<semantic::PoseCandidate>& candidates) {
  std::vector<localization::PoseHypothesis> hypotheses;
  for (const semantic::PoseCandidate& c : candidates) {
    // More objects in agreement, more weight; the laser fit separates look-alikes.
    hypotheses.push_back({c.pose, c.covariance, c.agreeing * (0.1 + c.laser_score)});
  }
  return hypotheses;
}

// At most 'max_kept' of the particles, evenly strided (after resampling their order carries
// no meaning, so a stride is a fair sample).
ParticleSnapshot Subsample(const std::vector<localization::Particle>& particles, int max_kept) {
  ParticleSnapshot snapshot;
  snapshot.particles = static_cast<int>(particles.size());
  const std::size_t kept = static_cast<std::size_t>(std::max(1, max_kept));
  const std::size_t stride = std::max<std::size_t>(1, (particles.size() + kept - 1) / kept);
  for (std::size_t i = 0; i < particles.size(); i += stride) {
    snapshot.poses.push_back(particles[i].pose);
    snapshot.weights.push_back(particles[i].weight);
  }
  return snapshot;
}

// The covariance of a renewed prior, relative to the pre-localization's.
constexpr double kRenewedPriorScale = 4.0;

// Poses this far apart are different places, not a correction the filter makes by itself
// (twice the benchmark's success tolerance).
bool AnotherPlace(const Pose2& a, const Pose2& b) {
  return (a.translation() - b.translation()).norm() > 0.5 ||
         std::abs(NormalizeAngle(a.theta - b.theta)) > 0.35;
}

// Tracking covariance after a scan matcher found the robot.
const Eigen::Matrix3d kTrackingCovariance =
    Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 0.03 * 0.03).asDiagonal();

class MethodRun {
 public:
  MethodRun(const std::string& method, const RelocMap& map, const RelocRunInputs& inputs)
      : method_(method),
        map_(map),
        inputs_(inputs),
        amcl_(map.localization, map.amcl_options, MakeRng(inputs.seed, 1)) {}

  RelocTrace Run() {
    RelocTrace trace;
    std::size_t next_frame = 0;
    double cpu = 0.0;
    int iterations = 0;
    if (method_ == "amcl" || method_ == "semantic-amcl" || method_ == "semantic-amcl-bow") {
      amcl_.InitializeGlobal();
    }
    for (const StampedScan& scan : inputs_.scans) {
      const double start = ThreadCpuSeconds();
      scan_points_.reset();
      // The frame taken at this scan, if any.
      const RelocFrame* frame = nullptr;
      while (next_frame < inputs_.frames.size() &&
             inputs_.frames[next_frame].stamp <= scan.scan.timestamp + 1e-6) {
        frame = &inputs_.frames[next_frame++];
      }
      iterations += Step(scan, frame, &trace);
      if (trace.prelocalization && trace.prelocalization_scan < 0) {
        trace.prelocalization_scan = static_cast<int>(trace.estimates.size());
      }
      cpu += ThreadCpuSeconds() - start;
      trace.estimates.push_back(estimate_);
      trace.cpu_seconds.push_back(cpu);
      trace.search_cpu_seconds.push_back(search_cpu_);
      trace.iterations.push_back(iterations);
      if (inputs_.record_particles_every > 0) RecordParticles(scan, &trace);
    }
    if (unrecorded_) trace.particle_snapshots.push_back(std::move(*unrecorded_));
    return trace;
  }

 private:
  // The current scan's returns as the scan matcher uses them, made on first use: most frames
  // yield no hypothesis to rate and no search.
  const std::vector<Eigen::Vector2d>& ScanPoints(const StampedScan& scan) const {
    if (!scan_points_) scan_points_ = map_.matcher.MatchPoints(scan.scan, scan.LaserOffset());
    return *scan_points_;
  }

  // Rates a pose by how well this scan fits the map there: the mean match-grid value M of its
  // returns, as the branch-and-bound search scores a pose (sharp, σ 0.05 m: the hypotheses are
  // aligned to their objects first, and a softer fit, σ 0.15 m, ranked look-alike hypotheses a
  // few decimetres apart badly, first-hypothesis error 0.20 m instead of 0.15 m on the e2e
  // test's trials).
  std::function<double(const Pose2&)> LaserScorer(const StampedScan& scan) const {
    return [this, &scan](const Pose2& pose) {
      return mapping::CellScore(map_.matcher.grid(), ScanPoints(scan), pose);
    };
  }

  // The first best hypothesis of the trial is what the benchmark scores as the pre-localization.
  static void NoteFirstHypothesis(const std::vector<semantic::PoseCandidate>& candidates,
                                  RelocTrace* trace) {
    if (!candidates.empty() && !trace->prelocalization) {
      trace->prelocalization = candidates.front().pose;
    }
  }

  // Remembers a frame's objects; returns what pre-localization may use now: nothing when the
  // frame shows no object (what is remembered gave its hypotheses when it was seen).
  std::vector<semantic::ObservedObject> Observe(const StampedScan& scan, const RelocFrame& frame) {
    std::vector<semantic::ObservedObject> observed = semantic::ObserveObjects(
        frame.detections, inputs_.camera, map_.prelocalizer.options().min_score);
    if (!map_.method.observation_memory) return observed;
    memory_.Add(scan.odometry, observed);  // also when empty: it counts the turn
    if (observed.empty()) return observed;
    return memory_.Recall(scan.odometry);
  }

  std::vector<semantic::PoseCandidate> PreLocalize(
      const StampedScan& scan, const std::vector<semantic::ObservedObject>& observed,
      RelocTrace* trace, int min_agreeing = 0) const {
    if (observed.size() < 2) return {};
    std::vector<semantic::PoseCandidate> candidates =
        map_.prelocalizer.Localize(observed, LaserScorer(scan), nullptr, min_agreeing);
    ++trace->prelocalizations;
    NoteFirstHypothesis(candidates, trace);
    return candidates;
  }

  std::vector<semantic::PoseCandidate> PreLocalizeSingle(
      const StampedScan& scan, const std::vector<semantic::ObservedObject>& observed,
      RelocTrace* trace) const {
    // Not noted as the trial's pre-localization: its many circle hypotheses are for the scan
    // matcher to tell apart, and the benchmark's pre-localization error is the paper's (pairs).
    std::vector<semantic::PoseCandidate> candidates =
        map_.prelocalizer.LocalizeSingle(observed, LaserScorer(scan));
    ++trace->single_object_prelocalizations;
    return candidates;
  }

  // Seed 000 §3.1 steps 3–4: the most similar keyframes name the object hidden now; its two
  // chain neighbours, seen now, pre-localize the robot.
  std::vector<semantic::PoseCandidate> PreLocalizeHidden(
      const StampedScan& scan, const RelocFrame& frame,
      const std::vector<semantic::ObservedObject>& observed, RelocTrace* trace) const {
    if (!map_.recognizer || frame.image.empty() || frame.detections.empty()) return {};
    Result<cv::Mat> image = ReadColorImage(frame.image);
    if (!image.ok()) return {};
    const cv::Mat descriptors = semantic::ExtractOrbDescriptors(*image, semantic::OrbOptions());
    const semantic::OcclusionQuery query = semantic::QueryOccludedObjects(
        *map_.recognizer, map_.semantic, descriptors, frame.detections);
    const auto& occluded = query.inference.inference.occluded;
    if (occluded.empty()) return {};
    const std::vector<int> neighbours = {occluded.front().upstream, occluded.front().downstream};
    std::vector<semantic::PoseCandidate> candidates =
        map_.prelocalizer.Localize(observed, LaserScorer(scan), &neighbours);
    ++trace->hidden_object_prelocalizations;
    NoteFirstHypothesis(candidates, trace);
    return candidates;
  }

  // After a filter update, keeps the particles when RelocTrace::particle_snapshots asks for
  // them; any other update waits in unrecorded_ in case it turns out to be the last.
  void RecordParticles(const StampedScan& scan, RelocTrace* trace) {
    const int updates = amcl_.counters().updates;
    if (updates == recorded_updates_) return;
    recorded_updates_ = updates;
    const bool after_prelocalization = trace->prelocalization_scan >= 0 && !snapped_prelocalized_;
    ParticleSnapshot snapshot = Subsample(amcl_.particles(), inputs_.record_particles_max);
    snapshot.scan = static_cast<int>(trace->estimates.size()) - 1;
    snapshot.time = scan.scan.timestamp;
    unrecorded_.reset();
    if (trace->particle_snapshots.empty() || after_prelocalization ||
        updates % inputs_.record_particles_every == 0) {
      snapped_prelocalized_ = snapped_prelocalized_ || after_prelocalization;
      trace->particle_snapshots.push_back(std::move(snapshot));
    } else {
      unrecorded_ = std::move(snapshot);
    }
  }

  // Processes one scan; returns the filter updates / matcher runs it took.
  int Step(const StampedScan& scan, const RelocFrame* frame, RelocTrace* trace) {
    if (method_ == "amcl") return Track(scan);
    if (method_ == "semantic-amcl" || method_ == "semantic-amcl-bow") {
      // Every frame with two objects in view is a semantic measurement: the first seeds the
      // particles, each later one renews the prior; between frames the prior moves with the
      // odometry (the robot turns between frames, the prior's heading must follow).
      if (frame) {
        const std::vector<semantic::ObservedObject> observed = Observe(scan, *frame);
        auto candidates = PreLocalize(scan, observed, trace);
        if (candidates.empty() && method_ == "semantic-amcl-bow") {
          candidates = PreLocalizeHidden(scan, *frame, observed, trace);
        }
        if (!candidates.empty()) {
          prior_ = ToHypotheses(candidates);
          prior_odometry_ = scan.odometry;
          if (!seeded_ || amcl_.FailureDetected()) {
            amcl_.InitializeFromHypotheses(*prior_);
            filter_pose_.reset();
            seeded_ = true;
          } else {
            // Once seeded, the prior only has to keep the filter in the right place; a looser
            // one leaves the fine pose to the laser.
            for (localization::PoseHypothesis& h : *prior_) h.covariance *= kRenewedPriorScale;
          }
        }
      }
      if (prior_) {
        std::vector<localization::PoseHypothesis> moved = *prior_;
        const Pose2 motion = prior_odometry_.Between(scan.odometry);
        for (localization::PoseHypothesis& h : moved) h.pose = h.pose * motion;
        amcl_.SetPosePrior(moved);
      }
      return Track(scan);
    }
    // Scan-matcher methods: relocalize, then track (semantic-scanmatch re-checking the lock).
    if (!tracking_) {
      NoteTurn(scan);
      // Before a full turn, a scan without a frame gives the semantic method nothing to search;
      // it is not timed (the thread CPU clock is a system call, ~0.5 µs, all it would measure).
      if (method_ == "semantic-scanmatch" && !frame && !FullTurn()) return 0;
      const double search_start = ThreadCpuSeconds();
      std::optional<localization::RelocalizationResult> result = Relocalize(scan, frame, trace);
      search_cpu_ += ThreadCpuSeconds() - search_start;
      if (!result) return 0;
      if (!result->success) return 1;
      StartTracking(scan, result->pose);
      return 1;
    }
    const int updates = Track(scan);
    if (frame && method_ == "semantic-scanmatch" && map_.method.recheck_lock) {
      const double search_start = ThreadCpuSeconds();
      const bool moved = RecheckLock(scan, *frame, trace);
      search_cpu_ += ThreadCpuSeconds() - search_start;
      return updates + (moved ? 1 : 0);
    }
    return updates;
  }

  void StartTracking(const StampedScan& scan, const Pose2& pose) {
    amcl_.InitializePose(pose, kTrackingCovariance);
    tracking_ = true;
    filter_pose_ = pose;
    filter_odometry_ = scan.odometry;
    estimate_ = pose;
  }

  // A lock from a look-alike pair explains that pair; as the robot turns, the frames show
  // objects it cannot explain. When a frame's pre-localization finds poses, far from the tracked
  // one, that explain more of the objects seen, the scan matcher searches them beside the
  // tracked pose and the best match is kept. Returns whether the robot was moved.
  bool RecheckLock(const StampedScan& scan, const RelocFrame& frame, RelocTrace* trace) {
    const std::vector<semantic::ObservedObject> observed = Observe(scan, frame);
    if (observed.size() < 2) return false;
    // Only poses explaining more than the tracked one are of interest: the others are dropped
    // before the laser rates them.
    const int explained = map_.prelocalizer.Agreeing(observed, *estimate_);
    if (explained >= static_cast<int>(observed.size())) return false;  // none can explain more
    const std::vector<semantic::PoseCandidate> candidates =
        PreLocalize(scan, observed, trace, explained + 1);
    std::vector<semantic::PoseCandidate> better;
    for (const semantic::PoseCandidate& c : candidates) {
      if (AnotherPlace(c.pose, *estimate_)) better.push_back(c);
    }
    if (better.empty()) return false;
    std::vector<localization::PoseHypothesis> priors = ToHypotheses(better);
    priors.insert(priors.begin(), {*estimate_, kTrackingCovariance, 1.0});
    const localization::RelocalizationResult result =
        map_.matcher.Relocalize(ScanPoints(scan), priors);
    if (!result.success || result.hypothesis == 0) return false;
    StartTracking(scan, result.pose);
    return true;
  }

  // Adds the turn since the last scan to what the robot turned while lost.
  void NoteTurn(const StampedScan& scan) {
    if (start_odometry_) {
      turned_ += std::abs(NormalizeAngle(scan.odometry.theta - last_heading_));
    } else {
      start_odometry_ = scan.odometry;
    }
    last_heading_ = scan.odometry.theta;
  }
  bool FullTurn() const { return turned_ >= 2.0 * M_PI; }

  // One relocalization attempt of a scan-matcher method; nothing when it waits for a prior.
  std::optional<localization::RelocalizationResult> Relocalize(const StampedScan& scan,
                                                               const RelocFrame* frame,
                                                               RelocTrace* trace) {
    if (method_ == "scanmatch-global") {
      return map_.matcher.RelocalizeGlobal(ScanPoints(scan));
    }
    std::vector<semantic::PoseCandidate> candidates;
    std::vector<semantic::ObservedObject> observed;
    if (frame) {
      observed = Observe(scan, *frame);
      candidates = PreLocalize(scan, observed, trace);
    }
    const bool full_turn = FullTurn();
    if (candidates.empty() && full_turn && map_.method.single_object && !single_object_tried_) {
      // Once: the circles give many windows, and a turn's objects are all remembered (also when
      // this scan has no frame or its frame shows nothing).
      if (observed.empty() && map_.method.observation_memory) {
        observed = memory_.Recall(scan.odometry);
      }
      if (!observed.empty()) {
        single_object_tried_ = true;
        candidates = PreLocalizeSingle(scan, observed, trace);
      }
    }
    if (!candidates.empty()) {
      return map_.matcher.Relocalize(ScanPoints(scan), ToHypotheses(candidates));
    }
    // Without a semantic prior after a full turn (no two objects in view anywhere around), the
    // whole map is searched, as a robot would rather than stay lost.
    if (full_turn) return map_.matcher.RelocalizeGlobal(ScanPoints(scan));
    return std::nullopt;
  }

  // One AMCL step. The filter updates only after the robot moved update_min_d / turned
  // update_min_a; in between, as nav2 publishes map → odom, the pose is the last filter pose
  // moved on by odometry.
  int Track(const StampedScan& scan) {
    const bool updated = amcl_.ProcessScan(scan.scan, scan.odometry, scan.LaserOffset());
    if (updated || !filter_pose_) {
      filter_pose_ = amcl_.Estimate().pose;
      filter_odometry_ = scan.odometry;
    }
    estimate_ = *filter_pose_ * filter_odometry_.Between(scan.odometry);
    return updated ? 1 : 0;
  }

  const std::string& method_;
  const RelocMap& map_;
  const RelocRunInputs& inputs_;
  localization::Amcl amcl_;
  std::optional<Pose2> estimate_;
  std::optional<Pose2> filter_pose_;  // the filter's pose at its last update
  Pose2 filter_odometry_;             // odometry at that update
  bool seeded_ = false;
  std::optional<Pose2> start_odometry_;
  double last_heading_ = 0.0;
  double turned_ = 0.0;  // radians turned (odometry) before a scan matcher found the robot
  bool tracking_ = false;
  double search_cpu_ = 0.0;  // CPU seconds the scan matcher's search took so far
  // ScanPoints of the scan being processed (a cache, hence mutable).
  mutable std::optional<std::vector<Eigen::Vector2d>> scan_points_;
  semantic::ObservationMemory memory_{map_.method.memory};
  bool single_object_tried_ = false;
  // The latest pre-localization and the odometry when it was made.
  std::optional<std::vector<localization::PoseHypothesis>> prior_;
  Pose2 prior_odometry_;
  // Particle snapshots (RelocRunInputs::record_particles_every).
  int recorded_updates_ = 0;  // the filter's update count when last looked at
  bool snapped_prelocalized_ = false;
  std::optional<ParticleSnapshot> unrecorded_;
};

}  // namespace

const std::vector<std::string>& RelocMethodNames() {
  static const std::vector<std::string> kNames = {"amcl", "semantic-amcl", "semantic-amcl-bow",
                                                  "semantic-scanmatch", "scanmatch-global"};
  return kNames;
}

bool IsRelocMethod(const std::string& name) {
  const auto& names = RelocMethodNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

bool IsScanMatcherMethod(const std::string& name) {
  return name == "semantic-scanmatch" || name == "scanmatch-global";
}

RelocMap::RelocMap(const mapping::MapImage& occupancy_in, const semantic::SemanticMap& semantic_in,
                   const localization::AmclOptions& amcl,
                   const semantic::PreLocalizationOptions& prelocalization,
                   const localization::ScanMatchRelocalizerOptions& scan_match)
    : occupancy(occupancy_in),
      semantic(semantic_in),
      amcl_options(amcl),
      localization(occupancy_in, amcl.laser_likelihood_max_dist),
      prelocalizer(semantic_in, occupancy_in, prelocalization),
      matcher(occupancy_in, scan_match) {}

RelocTrace RunRelocMethod(const std::string& method, const RelocMap& map,
                          const RelocRunInputs& inputs) {
  return MethodRun(method, map, inputs).Run();
}

}  // namespace semchain::eval
