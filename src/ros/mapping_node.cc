#include "ros/mapping_node.h"

#include <nav_msgs/OccupancyGrid.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/cpu_time.h"
#include "io/detections_io.h"
#include "mapping/map_io.h"
#include "ros/log_throttle.h"
#include "ros/object_markers.h"
#include "ros/ros_geometry.h"
#include "ros/ros_image.h"
#include "ros/ros_map.h"
#include "semantic/box_depth.h"
#include "semantic/keyframe_selection.h"
#include "semantic/map_folder_writer.h"

namespace semchain::ros1 {
namespace {

// Scans wait while the map is published or saved (a second or so): a queue as deep as a few
// seconds of scans keeps every scan, as `semchain slam` uses every scan of a log.
constexpr std::uint32_t kScanQueue = 200;
// The detections topic's messages are small and quick to handle.
constexpr std::uint32_t kDetectionsQueue = 50;

void Warn(const std::string& line) { ROS_WARN("semchain_ros: %s", line.c_str()); }

}  // namespace

Result<std::unique_ptr<MappingNode>> MappingNode::Create(::ros::NodeHandle nh,
                                                         ::ros::NodeHandle private_nh,
                                                         const NodeMode& mode) {
  Result<MappingNodeParameters> parameters = ReadMappingNodeParameters(private_nh);
  if (!parameters.ok()) return parameters.status();
  Result<std::unique_ptr<detection::YoloDetector>> detector =
      LoadNodeDetector(parameters->detector, parameters->class_map);
  if (!detector.ok()) return detector.status();
  std::unique_ptr<MappingNode> node(
      new MappingNode(nh, std::move(*parameters), std::move(*detector)));
  node->Start(mode);
  return node;
}

MappingNode::MappingNode(::ros::NodeHandle nh, MappingNodeParameters parameters,
                         std::unique_ptr<detection::YoloDetector> detector)
    : nh_(nh),
      parameters_(std::move(parameters)),
      detector_(std::move(detector)),
      slam_(parameters_.slam),
      tf_buffer_(::ros::Duration(30.0)),
      tf_listener_(tf_buffer_),
      camera_(parameters_.camera_max_range),
      rgbd_(detector_.get(), [this] { return camera_.Camera(tf_buffer_, parameters_.frames); }) {}

MappingNode::~MappingNode() { Shutdown(); }

namespace {

// The largest share of the frames' thread that the objects' snapshots for /semchain/objects take.
constexpr double kObjectsSnapshotShare = 0.1;

// How long the save service waits for the frames the detector is still working on.
constexpr double kDetectorDrainSeconds = 30.0;

}  // namespace

void MappingNode::Start(const NodeMode& mode) {
  map_publisher_ = nh_.advertise<nav_msgs::OccupancyGrid>("map", 1, true);
  objects_publisher_ = nh_.advertise<visualization_msgs::MarkerArray>("semchain/objects", 1, true);
  scan_input_ = std::make_unique<ScanInput>(
      nh_, "scan", kScanQueue, tf_buffer_, parameters_.frames.odom_frame_id,
      [this](const sensor_msgs::LaserScanConstPtr& scan, const ScanArrival&) { OnScan(scan); });
  const auto frame_queue = static_cast<std::uint32_t>(parameters_.frame_queue_size);
  if (detector_) {
    // camera_info on the detector's thread too: the camera is used there only.
    detector_thread_ = std::make_unique<DetectorThread>(nh_);
    ::ros::NodeHandle& camera_nh = detector_thread_->nh();
    camera_info_subscriber_ =
        camera_nh.subscribe("camera/color/camera_info", 2, &MappingNode::OnCameraInfo, this);
    color_subscriber_ = camera_nh.subscribe("camera/color/image_raw", frame_queue,
                                            &MappingNode::OnColorImage, this);
    depth_subscriber_ = camera_nh.subscribe("camera/depth/image_raw", frame_queue,
                                            &MappingNode::OnDepthImage, this);
    detector_thread_->Start();
  } else {
    camera_info_subscriber_ =
        nh_.subscribe("camera/color/camera_info", 2, &MappingNode::OnCameraInfo, this);
    detections_subscriber_ =
        nh_.subscribe("semchain/detections", kDetectionsQueue, &MappingNode::OnDetections, this);
    if (parameters_.keyframe_images) {
      color_subscriber_ =
          nh_.subscribe("camera/color/image_raw", frame_queue, &MappingNode::OnKeyframeImage, this);
    }
  }
  save_service_ = nh_.advertiseService("semchain/save_map", &MappingNode::OnSaveMap, this);
  // An unwritable ~out is said now, not after an hour of mapping; the node maps anyway (the
  // folder may become writable, or the map be saved elsewhere by a restart).
  const Status writable = EnsureWritableDirectory(
      std::filesystem::absolute(parameters_.out).lexically_normal().parent_path());
  if (!writable.ok()) {
    ROS_ERROR("semchain_ros: ~out %s: %s; mapping anyway, saving will fail",
              parameters_.out.c_str(), writable.message().c_str());
  }
  const std::string objects =
      detector_ ? "detector " +
                      DescribeNodeDetector(parameters_.detector, parameters_.class_map, *detector_)
                : std::string("/semchain/detections");
  ROS_INFO("semchain_ros: %s, out %s, objects: %s, %s%s", mode.Describe().c_str(),
           parameters_.out.c_str(), objects.c_str(), DescribeMappingParameters(parameters_).c_str(),
           ::ros::Time::isSimTime() ? ", use_sim_time" : "");
}

bool MappingNode::Acceptable(const StampedScan& scan) const {
  if (slam_.size() == 0) return true;
  const StampedScan& last = slam_.scans().back();
  // A scan stamped as the last one is the same scan again: the tf filter releases an old scan
  // sent again at once (tf knows its stamp) while the newer one before it still waits for tf.
  if (scan.scan.timestamp <= last.scan.timestamp) {
    SEMCHAIN_WARN_THROTTLE(5.0,
                           "semchain_ros: scan at %.3f s is not newer than the last one (%.3f s): "
                           "out of time order, skipped",
                           scan.scan.timestamp, last.scan.timestamp);
    return false;
  }
  return true;
}

void MappingNode::OnScan(const sensor_msgs::LaserScanConstPtr& message) {
  const std::optional<StampedScan> scan =
      ScanWithOdometry(tf_buffer_, *message, parameters_.frames);
  if (!scan) {
    ++timings_.dropped_scans;
    return;
  }
  if (!Acceptable(*scan)) {
    ++timings_.rejected_scans;
    return;
  }
  const double cpu_start = ThreadCpuSeconds();
  Feed(*scan);
  timings_.cpu_ms.push_back(1000.0 * (ThreadCpuSeconds() - cpu_start));
  PublishTransform(message->header.stamp, trajectory_.back().pose, scan->odometry);
  const double stamp = scan->scan.timestamp;
  if (!last_map_stamp_ || stamp - *last_map_stamp_ >= parameters_.map_update_interval) {
    PublishMap(message->header.stamp);
    last_map_stamp_ = stamp;
  }
  const ::ros::WallTime now = ::ros::WallTime::now();
  if (!first_scan_wall_) {
    first_scan_wall_ = now;
    timings_.first_stamp = stamp;
  }
  timings_.last_stamp = stamp;
  timings_.wall_seconds = (now - *first_scan_wall_).toSec();
}

void MappingNode::Feed(const StampedScan& scan) {
  const mapping::SlamStep step = slam_.AddScan(scan);
  {
    const std::lock_guard<std::mutex> lock(trajectory_mutex_);
    trajectory_ = slam_.Trajectory();
  }
  // The semantic mapper is the detector thread's when there is one: the scans never wait for
  // it (a snapshot of hundreds of frames takes hundreds of milliseconds).
  const auto advance = [this, corrected = step.processed] {
    const std::lock_guard<std::mutex> lock(mutex_);
    AdvanceSemantic(corrected);
  };
  if (detector_thread_) {
    detector_thread_->Post(advance);
  } else {
    advance();
  }
}

void MappingNode::AdvanceSemantic(bool corrected) {
  if (!semantic_) return;
  std::optional<double> latest;
  {
    const std::lock_guard<std::mutex> lock(trajectory_mutex_);
    if (!trajectory_.empty()) latest = trajectory_.back().timestamp;
  }
  // As `slam --semantic` does: frames wait for a pose; a filter update may move mapped ones.
  // Most scans pose no new frame: the trajectory is copied only when one is.
  if (!latest || (!corrected && semantic_->next_stamp() > *latest)) return;
  const double cpu_start = ThreadCpuSeconds();
  const Status advanced = semantic_->Advance(Trajectory(), corrected, {});
  timings_.semantic_seconds += ThreadCpuSeconds() - cpu_start;
  if (!advanced.ok()) ROS_ERROR("semchain_ros: %s", advanced.message().c_str());
}

std::vector<StampedPose> MappingNode::Trajectory() const {
  const std::lock_guard<std::mutex> lock(trajectory_mutex_);
  return trajectory_;
}

void MappingNode::PublishTransform(const ::ros::Time& stamp, const Pose2& pose,
                                   const Pose2& odometry) {
  geometry_msgs::TransformStamped map_from_odom;
  // Future-dated as slam_gmapping and amcl do, so that consumers can use it until the next scan.
  map_from_odom.header.stamp = stamp + ::ros::Duration(parameters_.transform_tolerance);
  map_from_odom.header.frame_id = parameters_.frames.global_frame_id;
  map_from_odom.child_frame_id = parameters_.frames.odom_frame_id;
  map_from_odom.transform = ToTransformMsg(pose * odometry.Inverse());
  tf_broadcaster_.sendTransform(map_from_odom);
}

void MappingNode::PublishMap(const ::ros::Time& stamp) {
  auto image = std::make_shared<const mapping::MapImage>(
      mapping::GridToMapImage(*slam_.filter().BestParticle().map));
  nav_msgs::OccupancyGrid grid = ToOccupancyGridMsg(*image, parameters_.frames.global_frame_id);
  grid.header.stamp = stamp;
  grid.info.map_load_time = stamp;
  map_publisher_.publish(grid);
  // The objects on this map take a snapshot of the semantic map (hundreds of milliseconds with
  // hundreds of frames): on the detector's thread, so that the scans do not wait for it.
  if (detector_thread_) {
    detector_thread_->Post([this, image, stamp] { PublishObjects(*image, stamp); });
  } else {
    PublishObjects(*image, stamp);
  }
}

void MappingNode::PublishObjects(const mapping::MapImage& image, const ::ros::Time& stamp) {
  if (!::ros::ok()) return;  // posted before the node began to shut down: nobody listens now
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!semantic_ || semantic_->mapped_frames() == 0) return;
  const ::ros::WallTime start = ::ros::WallTime::now();
  // A snapshot's cost grows with the frames; when the map updates come faster than that allows
  // (a bag played fast), some are left out rather than take the frames' time.
  if (next_objects_wall_ && start < *next_objects_wall_) return;
  const double cpu_start = ThreadCpuSeconds();
  const semantic::SemanticMappingResult current = semantic_->Current(Trajectory(), image);
  timings_.snapshot_seconds += ThreadCpuSeconds() - cpu_start;
  const double took = (::ros::WallTime::now() - start).toSec();
  next_objects_wall_ = start + ::ros::WallDuration(took / kObjectsSnapshotShare);
  visualization_msgs::MarkerArray markers =
      ObjectMarkers(current.map, {}, parameters_.frames.global_frame_id);
  for (visualization_msgs::Marker& marker : markers.markers) marker.header.stamp = stamp;
  objects_publisher_.publish(markers);
  if (current.map.objects.size() != published_objects_) {
    published_objects_ = current.map.objects.size();
    ROS_INFO("semchain_ros: %zu objects, %zu chains after %d frames", current.map.objects.size(),
             current.map.chains.size(), semantic_->mapped_frames());
  }
}

void MappingNode::AddFrame(FrameDetections frame, const cv::Mat& depth_m) {
  const std::optional<MountedCamera> camera = camera_.Camera(tf_buffer_, parameters_.frames);
  const std::lock_guard<std::mutex> lock(mutex_);
  // camera_info comes on a connection of its own and may reach the node after the first images:
  // their frames wait for it instead of being lost.
  frames_awaiting_camera_.push_back({std::move(frame), depth_m});
  if (frames_awaiting_camera_.size() > static_cast<std::size_t>(parameters_.frame_queue_size)) {
    frames_awaiting_camera_.pop_front();
    ++frames_lost_;
    SEMCHAIN_WARN_THROTTLE(5.0,
                           "semchain_ros: no camera yet (camera_info and its frame in tf): the "
                           "oldest waiting frame is dropped");
  }
  if (camera) MapAwaitingFrames(*camera);
}

void MappingNode::MapAwaitingFrames(const MountedCamera& camera) {
  if (!semantic_) {
    // The semantic grid numbers its cells on the SLAM grid's lattice (cells from the origin).
    semantic::GridGeometry lattice;
    lattice.resolution = parameters_.slam.rbpf.grid.resolution_meters;
    semantic::LiveSemanticOptions options;
    options.map.points.min_score = parameters_.min_detection_score;
    Result<std::unique_ptr<semantic::LiveSemanticRun>> created =
        semantic::LiveSemanticRun::Create(camera, DefaultClassNames(), lattice, options, Warn,
                                          detector_ ? "camera" : "/semchain/detections");
    if (!created.ok()) {
      SEMCHAIN_ERROR_THROTTLE(5.0, "semchain_ros: %s", created.status().message().c_str());
      return;
    }
    semantic_ = std::move(*created);
  }
  for (AwaitingFrame& waiting : frames_awaiting_camera_) {
    const cv::Mat depth = waiting.depth_m.empty() ? semantic::DepthFromBoxes(
                                                        waiting.frame.detections, camera.intrinsics)
                                                  : waiting.depth_m;
    semantic_->AddFrame(std::move(waiting.frame), depth);
  }
  frames_awaiting_camera_.clear();
  // A frame the detector hands over after the scans of its time were fed (the detector is
  // slower than the scans, or the bag has ended) is mapped now: no later scan may come to map it.
  AdvanceSemantic(false);
}

void MappingNode::OnDetections(const std_msgs::StringConstPtr& message) {
  Result<FrameDetections> frame = ParseDetectionsRecord(message->data, "/semchain/detections");
  if (!frame.ok()) {
    SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: %s", frame.status().message().c_str());
    return;
  }
  if (parameters_.keyframe_images && !frame->detections.empty()) {
    const std::lock_guard<std::mutex> lock(mutex_);
    keyframe_images_.AddFrame(frame->frame, frame->stamp);
  }
  AddFrame(std::move(*frame), cv::Mat());
}

void MappingNode::OnKeyframeImage(const sensor_msgs::ImageConstPtr& message) {
  Result<cv::Mat> rgb = ColorFromImageMsg(*message);
  if (!rgb.ok()) {
    SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: %s", rgb.status().message().c_str());
    return;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  keyframe_images_.AddImage(message->header.stamp.toSec(), *rgb);
}

void MappingNode::OnCameraInfo(const sensor_msgs::CameraInfoConstPtr& message) {
  camera_.OnCameraInfo(*message);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (frames_awaiting_camera_.empty()) return;
  }
  // Outside the lock: the lookup may wait for tf, and the scans must not wait with it.
  const std::optional<MountedCamera> camera = camera_.Camera(tf_buffer_, parameters_.frames);
  if (!camera) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  MapAwaitingFrames(*camera);
}

void MappingNode::OnDepthImage(const sensor_msgs::ImageConstPtr& message) {
  AddDetectedFrame(rgbd_.OnDepthImage(message));
}

void MappingNode::OnColorImage(const sensor_msgs::ImageConstPtr& message) {
  AddDetectedFrame(rgbd_.OnColorImage(message));
}

void MappingNode::AddDetectedFrame(std::optional<RgbdDetections> detected) {
  if (!detected) return;
  FrameDetections frame;
  frame.frame = detected->frame;
  frame.stamp = detected->stamp;
  frame.detections = std::move(detected->detections);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    timings_.detect_ms.push_back(detected->detect_ms);
    if (parameters_.keyframe_images && !frame.detections.empty()) {
      keyframe_images_.AddFrameImage(frame.frame, detected->color);
    }
  }
  AddFrame(std::move(frame), detected->depth_m);
}

Status MappingNode::Save() {
  if (slam_.size() == 0) return Status::Error("no scan yet: nothing to save");
  const mapping::SlamResult result = slam_.Finish();
  semantic::MapFolderContents contents;
  contents.occupancy = mapping::GridToMapImage(result.map);
  contents.trajectory = result.trajectory;
  semantic::SemanticMappingResult mapped;
  mapped.map.classes = DefaultClassNames();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (semantic_) {
    // Frames the detector handed over after the last scan's step wait for a pose still: those
    // within the trajectory are mapped now.
    const Status advanced = semantic_->Advance(result.trajectory, false, {});
    if (!advanced.ok()) return advanced;
    mapped = semantic_->Current(result.trajectory, contents.occupancy);
  }
  // No run folder holds the frames: the keyframes' images are saved in the map folder itself
  // ("run": "."), those of keyframes without an image left out, and keyframes.json is written
  // after them (which keyframes it lists is known only then); with no image at all the folder
  // writer writes the keyframes naming no folder (semantic-amcl-bow then says it needs images).
  const bool with_images = keyframe_images_.size() > 0;
  // The covering subset (seed 000 §3.1 step 2) of the frames the bag of words can describe.
  std::vector<semantic::Keyframe> candidates = mapped.keyframes;
  if (with_images) {
    std::erase_if(candidates,
                  [this](const semantic::Keyframe& k) { return !keyframe_images_.Has(k.frame); });
  }
  const std::vector<semantic::Keyframe> selected = semantic::SelectCoveringKeyframes(candidates);
  semantic::KeyframeDatabase keyframes{"", selected};
  const auto write_images = [&](const std::filesystem::path& staging) -> Status {
    if (!with_images) return Status::Ok();
    Result<std::vector<semantic::Keyframe>> written = keyframe_images_.Write(staging, selected);
    if (!written.ok()) return written.status();
    keyframes = {".", std::move(*written)};
    return semantic::WriteKeyframes(staging / "keyframes.json", keyframes);
  };
  contents.semantic = &mapped.map;
  contents.keyframes = with_images ? nullptr : &keyframes;
  SEMCHAIN_RETURN_IF_ERROR(semantic::WriteMapFolder(parameters_.out, contents, write_images));
  saved_at_ = {slam_.size(), MappedFrames()};
  ROS_INFO("semchain_ros: saved %s: %zu scans, %zu objects, %zu chains, %zu keyframes (%s)",
           parameters_.out.c_str(), result.trajectory.size(), mapped.map.objects.size(),
           mapped.map.chains.size(), keyframes.keyframes.size(),
           keyframes.run.empty() ? "no images" : "with images");
  return Status::Ok();
}

bool MappingNode::OnSaveMap(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  // The frames queued for the detector before the call go into the map.
  if (detector_thread_ && !detector_thread_->Drain(kDetectorDrainSeconds)) {
    ROS_WARN(
        "semchain_ros: save_map: the detector still works on frames after %.0f s; saving "
        "without them",
        kDetectorDrainSeconds);
  }
  const Status saved = Save();
  response.success = saved.ok();
  response.message = saved.ok() ? parameters_.out : saved.message();
  if (!saved.ok()) ROS_ERROR("semchain_ros: save_map: %s", saved.message().c_str());
  return true;
}

void MappingNode::Shutdown() {
  if (shut_down_) return;
  shut_down_ = true;
  // Nothing runs beside what follows (roscpp has dropped the callbacks still queued on the main
  // queue); the images already on the detector's queue are still mapped.
  if (detector_thread_) {
    detector_thread_->Stop();
    if (!detector_thread_->RunQueued(kDetectorDrainSeconds)) {
      ROS_WARN("semchain_ros: shutting down with frames not yet detected after %.0f s",
               kDetectorDrainSeconds);
    }
  }
  if (!frames_awaiting_camera_.empty()) {
    ROS_WARN(
        "semchain_ros: %zu frames not mapped: no camera for them (camera_info, or tf from %s to "
        "its frame)",
        frames_awaiting_camera_.size(), parameters_.frames.base_frame_id.c_str());
  }
  // A map saved since the last scan and frame is what a save now would write (the final passes
  // take seconds).
  const bool saved_already = saved_at_ == std::pair(slam_.size(), MappedFrames());
  if (parameters_.save_on_shutdown && slam_.size() > 0 && !saved_already) {
    const Status saved = Save();
    if (!saved.ok()) ROS_ERROR("semchain_ros: saving on shutdown: %s", saved.message().c_str());
  }
  const Status written = WriteStats();
  if (!written.ok()) ROS_ERROR("semchain_ros: %s", written.message().c_str());
}

int MappingNode::MappedFrames() const { return semantic_ ? semantic_->mapped_frames() : 0; }

Status MappingNode::WriteStats() const {
  if (parameters_.stats_file.empty()) return Status::Ok();
  const double span = timings_.last_stamp - timings_.first_stamp;
  nlohmann::json stats = {
      {"mode", "mapping"},
      {"scans", slam_.size()},
      {"processed", slam_.filter().statistics().processed},
      {"dropped_scans", timings_.dropped_scans + (scan_input_ ? scan_input_->dropped() : 0)},
      {"rescued_scans", scan_input_ ? scan_input_->rescued() : 0},
      {"rejected_scans", timings_.rejected_scans},
      {"frames_detected", detector_ ? static_cast<int>(timings_.detect_ms.size()) : 0},
      {"frames_mapped", MappedFrames()},
      {"frames_skipped", semantic_ ? semantic_->skipped_frames() : 0},
      {"frames_without_camera", frames_lost_ + static_cast<int>(frames_awaiting_camera_.size())},
      {"cpu_ms_per_scan", Spread(timings_.cpu_ms)},
      {"detector_ms_per_frame", Spread(timings_.detect_ms)},
      {"semantic_cpu_seconds", timings_.semantic_seconds},
      {"objects_snapshot_cpu_seconds", timings_.snapshot_seconds},
      {"scan_seconds", span},
      {"wall_seconds", timings_.wall_seconds},
      {"real_time_factor", timings_.wall_seconds > 0.0 ? span / timings_.wall_seconds : 0.0}};
  return WriteFileAtomically(parameters_.stats_file, stats.dump(2) + "\n");
}

}  // namespace semchain::ros1
