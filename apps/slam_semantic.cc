#include "apps/slam_semantic.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "mapping/map_io.h"
#include "semantic/keyframe_selection.h"

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

double Percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto index = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1));
  return values[index];
}

nlohmann::json TimingJson(const semantic::LiveSemanticResult& result, double seconds) {
  const semantic::SemanticMapperStatistics& s = result.statistics;
  const double max_frame = s.frame_seconds.empty()
                               ? 0.0
                               : *std::max_element(s.frame_seconds.begin(), s.frame_seconds.end());
  return {{"frame_median_ms", 1e3 * Percentile(s.frame_seconds, 0.5)},
          {"frame_p99_ms", 1e3 * Percentile(s.frame_seconds, 0.99)},
          {"frame_max_ms", 1e3 * max_frame},
          {"reprojections", s.reprojections},
          {"incremental_reprojections", s.incremental_reprojections},
          {"reprojected_frames", s.reprojected_frames},
          {"reprojection_seconds", s.reprojection_seconds},
          {"max_reprojection_ms", 1e3 * s.max_reprojection_seconds},
          {"snapshot_seconds", result.snapshot_seconds},
          {"prepare_seconds", result.prepare_seconds},
          {"semantic_seconds", seconds}};
}

// MAP/semantic_growth.json: when each object was first seen and how the object count grew.
std::string GrowthJson(const semantic::LiveSemanticResult& result, const std::string& run,
                       double seconds) {
  nlohmann::json objects = nlohmann::json::array();
  for (const semantic::SemanticObject& object : result.mapping.map.objects) {
    const auto id = static_cast<std::size_t>(object.id);
    objects.push_back({{"id", object.id},
                       {"class", object.class_name},
                       {"center", {object.center.x(), object.center.y()}},
                       {"first_seen_stamp", result.first_seen_stamp[id]},
                       {"first_seen_frame", result.first_seen_frame[id]}});
  }
  nlohmann::json growth = nlohmann::json::array();
  for (const semantic::GrowthSample& sample : result.growth) {
    int seen = 0;
    for (const double stamp : result.first_seen_stamp)
      seen += stamp >= 0.0 && stamp <= sample.stamp;
    growth.push_back({{"stamp", sample.stamp},
                      {"frames", sample.frames},
                      {"live_objects", sample.objects},
                      {"final_objects_seen", seen}});
  }
  // The object count frame by frame: the final objects by their first sighting.
  std::vector<double> stamps = result.first_seen_stamp;
  std::sort(stamps.begin(), stamps.end());
  nlohmann::json sightings = nlohmann::json::array();
  int count = 0;
  for (const double stamp : stamps) {
    if (stamp >= 0.0) sightings.push_back({{"stamp", stamp}, {"objects", ++count}});
  }
  const nlohmann::json json = {{"version", 1},
                               {"run", run},
                               {"frames", result.mapping.frames},
                               {"skipped_frames", result.skipped_frames},
                               {"objects", objects},
                               {"count_by_first_sighting", sightings},
                               {"growth", growth},
                               {"timing", TimingJson(result, seconds)}};
  return json.dump(2) + "\n";
}

}  // namespace

SlamSemantic::SlamSemantic(SlamSemanticArgs args, std::unique_ptr<semantic::LiveSemanticRun> live)
    : args_(std::move(args)), live_(std::move(live)) {}

Result<std::unique_ptr<SlamSemantic>> SlamSemantic::Open(const SlamSemanticArgs& args,
                                                         double resolution) {
  std::optional<std::vector<FrameDetections>> detections;
  if (!args.detector.model.empty()) {
    Result<std::vector<FrameDetections>> detected = DetectWithModel(args.detector, args.run);
    if (!detected.ok()) return detected.status();
    detections = std::move(*detected);
  }
  // The SLAM grid's lattice: OccupancyGrid cells from the origin (0, 0).
  semantic::GridGeometry lattice;
  lattice.resolution = resolution;
  semantic::LiveSemanticOptions options;
  options.map.points.min_score = args.min_detection_score;
  Result<std::unique_ptr<semantic::LiveSemanticRun>> live = semantic::LiveSemanticRun::Open(
      args.run, detections, lattice, options,
      [](const std::string& line) { spdlog::warn("slam --semantic: {}", line); });
  if (!live.ok()) return live.status();
  return std::unique_ptr<SlamSemantic>(new SlamSemantic(args, std::move(*live)));
}

void SlamSemantic::StartPreparing() {
  semantic::LiveSemanticRun* live = live_.get();
  prepared_ = std::async(std::launch::async, [live] { return live->Prepare(); });
}

void SlamSemantic::Observe(const mapping::SlamStep& step) {
  // SLAM runs while the frames are prepared: the steps until then are left to the later ones
  // (Finish re-poses every frame on the final trajectory, so the result is the same).
  if (prepared_.valid()) {
    if (prepared_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
    status_ = prepared_.get();
  }
  if (!status_.ok()) return;
  const double stamp = (*step.scans)[step.scan].scan.timestamp;
  if (!step.processed && live_->next_stamp() > stamp) return;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<StampedPose> trajectory = step.source->Trajectory();
  status_ = live_->Advance(trajectory, step.processed, [&step] {
    return mapping::GridToMapImage(*step.slam->BestParticle().map);
  });
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Result<semantic::LiveSemanticResult> SlamSemantic::Finish(
    const std::vector<StampedPose>& trajectory, const mapping::MapImage& map) {
  if (prepared_.valid()) status_ = prepared_.get();
  if (!status_.ok()) return status_;
  const auto start = std::chrono::steady_clock::now();
  Result<semantic::LiveSemanticResult> result = live_->Finish(trajectory, map);
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

semantic::KeyframeDatabase SlamSemantic::Keyframes(
    const semantic::LiveSemanticResult& result) const {
  return {fs::absolute(args_.run).lexically_normal().string(),
          semantic::SelectCoveringKeyframes(result.mapping.keyframes)};
}

Status SlamSemantic::WriteExtras(const fs::path& out, const mapping::MapImage& map,
                                 const semantic::LiveSemanticResult& result) const {
  SEMCHAIN_RETURN_IF_ERROR(
      WriteSemanticPng(map, result.mapping.map, args_.scale, out / "semantic.png"));
  const std::string run = fs::absolute(args_.run).lexically_normal().string();
  return WriteFileAtomically(out / "semantic_growth.json", GrowthJson(result, run, seconds_));
}

}  // namespace semchain::app
