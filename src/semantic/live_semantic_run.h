#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/trajectory_io.h"
#include "mapping/map_io.h"
#include "semantic/grid_geometry.h"
#include "semantic/semantic_mapper.h"
#include "semantic/semantic_run.h"

// Semantic mapping while SLAM runs (`semchain slam --semantic RUN`, seed 000's real-time
// semantic chain list): a run's frames go to the SemanticMapper as soon as SLAM has a pose for
// their time, and the frames already mapped are re-posed whenever the best particle's
// trajectory moved beyond the mapper's tolerance. At the end every frame is re-posed exactly
// on the final trajectory, so that the result is the batch `semantic` on that trajectory.
namespace semchain::semantic {

struct LiveSemanticOptions {
  SemanticMapOptions map;
  SemanticMapperOptions mapper;
  // Seconds of log time between two snapshots of the live object count for the growth
  // report (0: none). A snapshot extracts every object (shape fits included): ~0.5 s on a
  // furnished flat, so only a few per run by default; the first sightings of the final
  // objects give the growth frame by frame at no cost.
  double snapshot_interval_seconds = 60.0;

  bool Validate(std::string* error) const;
};

// One live snapshot: what the map held at 'stamp'.
struct GrowthSample {
  double stamp = 0.0;
  int frames = 0;
  int objects = 0;
};

struct LiveSemanticResult {
  SemanticMappingResult mapping;
  // Per object (by id): the stamp and name of the first frame that saw it.
  std::vector<double> first_seen_stamp;
  std::vector<std::string> first_seen_frame;
  std::vector<GrowthSample> growth;
  SemanticMapperStatistics statistics;
  int skipped_frames = 0;
  double snapshot_seconds = 0.0;  // spent on the live snapshots
  double prepare_seconds = 0.0;   // reading the depth images and computing the evidence
};

class LiveSemanticRun {
 public:
  // Loads and checks the run (LoadRunFrames); 'lattice' is the SLAM grid's (resolution and
  // origin; the cells grow from it). 'warn' receives one line per frame that cannot be used
  // (out of time order, no pose yet) and per class that is not one of the ten.
  static Result<std::unique_ptr<LiveSemanticRun>> Open(
      const std::filesystem::path& run_dir,
      const std::optional<std::vector<FrameDetections>>& detections, const GridGeometry& lattice,
      const LiveSemanticOptions& options, std::function<void(const std::string&)> warn);

  // A run fed frame by frame (the ROS node's mapping mode: no run folder): frames come with
  // AddFrame; 'source' names where they come from in messages; 'classes' fixes the class order.
  static Result<std::unique_ptr<LiveSemanticRun>> Create(
      const MountedCamera& camera, std::vector<std::string> classes, const GridGeometry& lattice,
      const LiveSemanticOptions& options, std::function<void(const std::string&)> warn,
      const std::string& source);

  // Appends a frame seen by the camera of Create; 'depth_m' is CV_32FC1 in metres of the
  // camera's size. It is mapped once SLAM's trajectory reaches its stamp (Advance); a frame
  // out of time order or before the first scan is skipped then with a warning. Detections of a
  // class not in the classes are warned about (once per class) and ignored.
  void AddFrame(FrameDetections frame, const cv::Mat& depth_m);

  // The semantic map now: every frame mapped so far re-posed exactly on 'trajectory' (SLAM's
  // best so far), on 'occupancy'. Frames still waiting stay queued; mapping goes on after.
  SemanticMappingResult Current(const std::vector<StampedPose>& trajectory,
                                const mapping::MapImage& occupancy);

  int mapped_frames() const { return mapper_.frame_count(); }
  int skipped_frames() const { return skipped_; }

  // Reads every frame's depth image and computes its evidence in the robot frame (no pose
  // needed), so that mapping a frame later only poses it. May run on another thread while
  // SLAM prepares its scans, but not beside the calls below.
  Status Prepare();

  // SLAM now has 'trajectory' (one pose per scan so far, in time order). The frames up to
  // its last stamp are mapped; with 'corrected' (the filter updated: its best particle may have
  // changed) the frames already mapped are re-posed where they moved beyond the tolerance.
  // 'occupancy' gives the current SLAM map, called only for a growth snapshot.
  Status Advance(const std::vector<StampedPose>& trajectory, bool corrected,
                 const std::function<mapping::MapImage()>& occupancy);

  // The stamp of the next frame waiting for a pose (infinity when none waits).
  double next_stamp() const;

  // Maps the frames left, re-poses every frame exactly on the final trajectory and returns the
  // semantic map on the final occupancy map.
  Result<LiveSemanticResult> Finish(const std::vector<StampedPose>& trajectory,
                                    const mapping::MapImage& occupancy);

 private:
  LiveSemanticRun(std::filesystem::path run_dir, RunFrames run, const GridGeometry& lattice,
                  const LiveSemanticOptions& options, std::function<void(const std::string&)> warn);

  Status FeedUpTo(double stamp, const std::vector<StampedPose>& trajectory);
  std::vector<Pose2> FramePoses(const std::vector<StampedPose>& trajectory) const;

  std::filesystem::path run_dir_;
  RunFrames run_;
  LiveSemanticOptions options_;
  std::function<void(const std::string&)> warn_;
  SemanticMapper mapper_;
  std::vector<std::optional<RobotEvidence>> prepared_;  // per run frame, until mapped
  double prepare_seconds_ = 0.0;
  std::vector<int> mapped_;  // run frame index of each mapper frame
  std::size_t next_ = 0;     // next run frame to map
  double last_stamp_ = -std::numeric_limits<double>::infinity();
  double next_snapshot_ = -std::numeric_limits<double>::infinity();
  int skipped_ = 0;
  std::vector<GrowthSample> growth_;
  double snapshot_seconds_ = 0.0;
  std::vector<std::string> warned_classes_;  // unknown classes warned about (AddFrame)
};

}  // namespace semchain::semantic
