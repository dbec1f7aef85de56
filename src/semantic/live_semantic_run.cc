#include "semantic/live_semantic_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "io/trajectory_lookup.h"

namespace semchain::semantic {
namespace {

std::string Seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f s", t);
  return text;
}

// One line per class that is not one of the ten, with how often it was detected.
void WarnUnknownClasses(const RunFrames& run, const std::function<void(const std::string&)>& warn) {
  const std::vector<std::string> known = DefaultClassNames();
  std::map<std::string, int> unknown;
  for (const FrameDetections& frame : run.frames) {
    for (const Detection& detection : frame.detections) {
      if (std::find(known.begin(), known.end(), detection.class_name) == known.end()) {
        ++unknown[detection.class_name];
      }
    }
  }
  for (const auto& [name, count] : unknown) {
    const bool mapped =
        std::find(run.classes.begin(), run.classes.end(), name) != run.classes.end();
    warn(run.source + ": " + std::to_string(count) + " detections of unknown class '" + name +
         "' (not one of the ten classes): " + (mapped ? "mapped as an extra class" : "ignored"));
  }
}

}  // namespace

bool LiveSemanticOptions::Validate(std::string* error) const {
  if (!map.Validate(error)) return false;
  if (!mapper.Validate(error)) return false;
  if (!(snapshot_interval_seconds >= 0.0)) {
    *error = "snapshot_interval_seconds must be >= 0";
    return false;
  }
  return true;
}

LiveSemanticRun::LiveSemanticRun(std::filesystem::path run_dir, RunFrames run,
                                 const GridGeometry& lattice, const LiveSemanticOptions& options,
                                 std::function<void(const std::string&)> warn)
    : run_dir_(std::move(run_dir)),
      run_(std::move(run)),
      options_(options),
      warn_(std::move(warn)),
      mapper_(lattice, run_.classes, run_.camera.camera, options.map, options.mapper) {}

Result<std::unique_ptr<LiveSemanticRun>> LiveSemanticRun::Open(
    const std::filesystem::path& run_dir,
    const std::optional<std::vector<FrameDetections>>& detections, const GridGeometry& lattice,
    const LiveSemanticOptions& options, std::function<void(const std::string&)> warn) {
  std::string invalid;
  if (!options.Validate(&invalid)) return Status::Error("invalid semantic options: " + invalid);
  Result<RunFrames> run = LoadRunFrames(run_dir, detections, {});
  if (!run.ok()) return run.status();
  if (!warn) warn = [](const std::string&) {};
  WarnUnknownClasses(*run, warn);
  return std::unique_ptr<LiveSemanticRun>(
      new LiveSemanticRun(run_dir, std::move(*run), lattice, options, std::move(warn)));
}

Result<std::unique_ptr<LiveSemanticRun>> LiveSemanticRun::Create(
    const MountedCamera& camera, std::vector<std::string> classes, const GridGeometry& lattice,
    const LiveSemanticOptions& options, std::function<void(const std::string&)> warn,
    const std::string& source) {
  std::string invalid;
  if (!options.Validate(&invalid)) return Status::Error("invalid semantic options: " + invalid);
  RunFrames run;
  run.camera.camera = camera;
  run.classes = std::move(classes);
  run.source = source;
  if (!warn) warn = [](const std::string&) {};
  return std::unique_ptr<LiveSemanticRun>(
      new LiveSemanticRun({}, std::move(run), lattice, options, std::move(warn)));
}

void LiveSemanticRun::AddFrame(FrameDetections frame, const cv::Mat& depth_m) {
  for (const Detection& detection : frame.detections) {
    const std::string& name = detection.class_name;
    if (std::find(run_.classes.begin(), run_.classes.end(), name) != run_.classes.end() ||
        std::find(warned_classes_.begin(), warned_classes_.end(), name) != warned_classes_.end()) {
      continue;
    }
    warned_classes_.push_back(name);
    warn_(run_.source + ": frame " + frame.frame + ": detection of unknown class '" + name +
          "' (not one of the " + std::to_string(run_.classes.size()) + " classes): ignored");
  }
  prepared_.resize(run_.frames.size());
  prepared_.push_back(mapper_.ComputeEvidence(frame, depth_m));
  run_.frames.push_back(std::move(frame));
}

SemanticMappingResult LiveSemanticRun::Current(const std::vector<StampedPose>& trajectory,
                                               const mapping::MapImage& occupancy) {
  if (!trajectory.empty() && mapper_.frame_count() > 0) {
    mapper_.Repose(FramePoses(trajectory), /*exact=*/true);
  }
  return mapper_.Snapshot(occupancy);
}

double LiveSemanticRun::next_stamp() const {
  return next_ < run_.frames.size() ? run_.frames[next_].stamp
                                    : std::numeric_limits<double>::infinity();
}

Status LiveSemanticRun::FeedUpTo(double stamp, const std::vector<StampedPose>& trajectory) {
  std::optional<TrajectoryLookup> lookup;
  while (next_ < run_.frames.size() && run_.frames[next_].stamp <= stamp) {
    const std::size_t index = next_++;
    const FrameDetections& frame = run_.frames[index];
    if (frame.stamp < last_stamp_) {
      warn_(run_.source + ": frame " + frame.frame + " at " + Seconds(frame.stamp) +
            " is older than the frame before it (" + Seconds(last_stamp_) +
            "): out of time order, skipped");
      ++skipped_;
      continue;
    }
    if (!lookup) lookup.emplace(trajectory);
    const std::optional<Pose2> pose =
        trajectory.empty()
            ? std::nullopt
            : lookup->At(frame.stamp, options_.map.pose_tolerance, options_.map.max_pose_gap);
    if (!pose) {
      std::string where = " falls in a gap of the scans";
      if (trajectory.empty() || frame.stamp < trajectory.front().timestamp) {
        where = " comes before the first scan";
      } else if (frame.stamp > trajectory.back().timestamp) {
        where = " comes after the last scan (" + Seconds(trajectory.back().timestamp) + ")";
      }
      warn_(run_.source + ": frame " + frame.frame + " at " + Seconds(frame.stamp) + where +
            ": no pose, skipped");
      ++skipped_;
      continue;
    }
    if (index >= prepared_.size() || !prepared_[index]) {
      Result<cv::Mat> depth = ReadFrameDepth(run_dir_, run_, frame);
      if (!depth.ok()) return depth.status();
      mapper_.AddFrame(frame, *pose, *depth);
    } else {
      mapper_.AddEvidence(frame, std::move(*prepared_[index]), *pose);
      prepared_[index].reset();
    }
    mapped_.push_back(static_cast<int>(index));
    last_stamp_ = frame.stamp;
  }
  return Status::Ok();
}

Status LiveSemanticRun::Prepare() {
  const auto start = std::chrono::steady_clock::now();
  prepared_.resize(run_.frames.size());
  for (std::size_t i = next_; i < run_.frames.size(); ++i) {
    Result<cv::Mat> depth = ReadFrameDepth(run_dir_, run_, run_.frames[i]);
    if (!depth.ok()) return depth.status();
    prepared_[i] = mapper_.ComputeEvidence(run_.frames[i], *depth);
  }
  prepare_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return Status::Ok();
}

std::vector<Pose2> LiveSemanticRun::FramePoses(const std::vector<StampedPose>& trajectory) const {
  const TrajectoryLookup lookup(trajectory);
  std::vector<Pose2> poses;
  poses.reserve(mapped_.size());
  for (int i = 0; i < mapper_.frame_count(); ++i) {
    const std::optional<Pose2> pose =
        lookup.At(mapper_.frame_stamp(i), options_.map.pose_tolerance, options_.map.max_pose_gap);
    poses.push_back(pose ? *pose : mapper_.frame_pose(i));
  }
  return poses;
}

Status LiveSemanticRun::Advance(const std::vector<StampedPose>& trajectory, bool corrected,
                                const std::function<mapping::MapImage()>& occupancy) {
  if (trajectory.empty()) return Status::Ok();
  if (corrected && mapper_.frame_count() > 0) mapper_.Repose(FramePoses(trajectory));
  const double now = trajectory.back().timestamp;
  SEMCHAIN_RETURN_IF_ERROR(FeedUpTo(now, trajectory));
  if (options_.snapshot_interval_seconds > 0.0 && now >= next_snapshot_ &&
      mapper_.frame_count() > 0 && occupancy) {
    const auto start = std::chrono::steady_clock::now();
    const SemanticMappingResult snapshot = mapper_.Snapshot(occupancy());
    growth_.push_back({now, mapper_.frame_count(), static_cast<int>(snapshot.map.objects.size())});
    next_snapshot_ = now + options_.snapshot_interval_seconds;
    snapshot_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return Status::Ok();
}

Result<LiveSemanticResult> LiveSemanticRun::Finish(const std::vector<StampedPose>& trajectory,
                                                   const mapping::MapImage& occupancy) {
  SEMCHAIN_RETURN_IF_ERROR(FeedUpTo(std::numeric_limits<double>::infinity(), trajectory));
  if (mapper_.frame_count() == 0) {
    return Status::Error(run_.source + ": none of the " + std::to_string(run_.frames.size()) +
                         " frames has a pose on the SLAM trajectory: nothing to map");
  }
  // The final trajectory poses every frame, as the batch path would: equal results.
  mapper_.Repose(FramePoses(trajectory), /*exact=*/true);
  LiveSemanticResult result;
  result.mapping = mapper_.Snapshot(occupancy);
  for (const int frame : result.mapping.first_frame) {
    const bool seen = frame >= 0;
    result.first_seen_stamp.push_back(seen ? mapper_.frame_stamp(frame) : -1.0);
    result.first_seen_frame.push_back(
        seen ? run_.frames[static_cast<std::size_t>(mapped_[static_cast<std::size_t>(frame)])].frame
             : std::string());
  }
  result.growth = growth_;
  result.growth.push_back({trajectory.empty() ? last_stamp_ : trajectory.back().timestamp,
                           mapper_.frame_count(),
                           static_cast<int>(result.mapping.map.objects.size())});
  result.statistics = mapper_.statistics();
  result.skipped_frames = skipped_;
  result.snapshot_seconds = snapshot_seconds_;
  result.prepare_seconds = prepare_seconds_;
  return result;
}

}  // namespace semchain::semantic
