#include "ros/localization_node.h"

#include <geometry_msgs/PoseArray.h>
#include <nav_msgs/OccupancyGrid.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "bow/bow_occlusion.h"
#include "core/atomic_file.h"
#include "core/cpu_time.h"
#include "io/detections_io.h"
#include "ros/log_throttle.h"
#include "ros/node_inputs.h"
#include "ros/object_markers.h"
#include "ros/ros_geometry.h"
#include "ros/ros_map.h"
#include "semantic/map_folder.h"

namespace semchain::ros1 {
namespace {

constexpr std::uint32_t kQueue = 10;
// Scans waiting in the subscriber, and for tf in the filter (amcl's 100).
constexpr std::uint32_t kAmclScanQueue = 100;

}  // namespace

Result<std::unique_ptr<LocalizationNode>> LocalizationNode::Create(::ros::NodeHandle nh,
                                                                   ::ros::NodeHandle private_nh,
                                                                   const NodeMode& mode) {
  Result<LocalizationNodeParameters> parameters = ReadLocalizationNodeParameters(private_nh);
  if (!parameters.ok()) return parameters.status();
  Result<semantic::MapFolder> folder = semantic::ReadMapFolder(parameters->map);
  if (!folder.ok()) return folder.status();
  auto map = std::make_unique<localization::LocalizerMap>(
      folder->occupancy, folder->semantic, parameters->amcl, localization::PreLocalizationOptions(),
      localization::ScanMatchRelocalizerOptions());
  const localization::LocalizationMethod method =
      *localization::ParseLocalizationMethod(parameters->method);
  if (method == localization::LocalizationMethod::kSemanticAmclBow) {
    if (parameters->vocabulary.empty()) {
      return Status::Error("~method semantic-amcl-bow needs ~vocabulary (semchain vocab train)");
    }
    Result<bow::KeyframeRecognizer> recognizer =
        bow::LoadKeyframeRecognizer(parameters->vocabulary, folder->keyframes);
    if (!recognizer.ok()) return recognizer.status();
    map->recognizer = std::make_shared<const bow::KeyframeRecognizer>(std::move(*recognizer));
  }
  Result<std::unique_ptr<detection::YoloDetector>> detector =
      LoadNodeDetector(parameters->detector, parameters->class_map);
  if (!detector.ok()) return detector.status();
  std::unique_ptr<LocalizationNode> node(new LocalizationNode(
      nh, private_nh, std::move(*parameters), std::move(map), std::move(*detector)));
  node->Start(mode);
  return node;
}

LocalizationNode::LocalizationNode(::ros::NodeHandle nh, ::ros::NodeHandle private_nh,
                                   LocalizationNodeParameters parameters,
                                   std::unique_ptr<localization::LocalizerMap> map,
                                   std::unique_ptr<detection::YoloDetector> detector)
    : nh_(nh),
      private_nh_(private_nh),
      parameters_(std::move(parameters)),
      map_(std::move(map)),
      detector_(std::move(detector)),
      localizer_(*map_, *localization::ParseLocalizationMethod(parameters_.method),
                 parameters_.localizer),
      tf_listener_(tf_buffer_),
      camera_(parameters_.camera_max_range),
      rgbd_(detector_.get(), [this] { return camera_.Camera(tf_buffer_, parameters_.frames); }) {}

LocalizationNode::~LocalizationNode() {
  if (detector_thread_) detector_thread_->Stop();
  const Status written = WriteStats();
  if (!written.ok()) ROS_ERROR("%s", written.message().c_str());
}

void LocalizationNode::Start(const NodeMode& mode) {
  pose_publisher_ = nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("amcl_pose", 2, true);
  particles_publisher_ = nh_.advertise<geometry_msgs::PoseArray>("particlecloud", 2, true);
  map_publisher_ = nh_.advertise<nav_msgs::OccupancyGrid>("map", 1, true);
  objects_publisher_ = nh_.advertise<visualization_msgs::MarkerArray>("semchain/objects", 1, true);
  nav_msgs::OccupancyGrid grid =
      ToOccupancyGridMsg(map_->occupancy, parameters_.frames.global_frame_id);
  grid.header.stamp = ::ros::Time::now();
  grid.info.map_load_time = grid.header.stamp;
  map_publisher_.publish(grid);
  PublishObjects();

  scan_input_ = std::make_unique<ScanInput>(
      nh_, "scan", kAmclScanQueue, tf_buffer_, parameters_.frames.odom_frame_id,
      [this](const sensor_msgs::LaserScanConstPtr& scan, const ScanArrival& arrival) {
        OnScan(scan, arrival);
      });
  initial_pose_subscriber_ =
      nh_.subscribe("initialpose", 2, &LocalizationNode::OnInitialPose, this);
  if (localization::IsSemanticMethod(localizer_.method())) {
    if (detector_) {
      // camera_info on the detector's thread too: the camera is used there only.
      detector_thread_ = std::make_unique<DetectorThread>(nh_);
      ::ros::NodeHandle& camera_nh = detector_thread_->nh();
      camera_info_subscriber_ =
          camera_nh.subscribe("camera/color/camera_info", 2, &LocalizationNode::OnCameraInfo, this);
      color_subscriber_ =
          camera_nh.subscribe("camera/color/image_raw", 2, &LocalizationNode::OnColorImage, this);
      depth_subscriber_ =
          camera_nh.subscribe("camera/depth/image_raw", 2, &LocalizationNode::OnDepthImage, this);
      detector_thread_->Start();
    } else {
      camera_info_subscriber_ =
          nh_.subscribe("camera/color/camera_info", 2, &LocalizationNode::OnCameraInfo, this);
      detections_subscriber_ =
          nh_.subscribe("semchain/detections", kQueue, &LocalizationNode::OnDetections, this);
    }
  }
  if (parameters_.has_initial_pose) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const Eigen::Vector3d cov(parameters_.initial_cov[0], parameters_.initial_cov[1],
                              parameters_.initial_cov[2]);
    localizer_.SetInitialPose(Pose2(parameters_.initial_pose[0], parameters_.initial_pose[1],
                                    parameters_.initial_pose[2]),
                              cov.asDiagonal());
  }
  // Advertised last: whoever waits for the service finds the node ready and every subscription
  // registered with the master.
  global_localization_service_ =
      nh_.advertiseService("global_localization", &LocalizationNode::OnGlobalLocalization, this);
  const std::string objects =
      !localization::IsSemanticMethod(localizer_.method()) ? "none (laser only)"
      : detector_ ? "detector " + DescribeNodeDetector(parameters_.detector, parameters_.class_map,
                                                       *detector_)
                  : std::string("/semchain/detections");
  ROS_INFO("semchain_ros: %s, method %s, map %s (%zu objects, %zu chains), objects: %s, %s%s",
           mode.Describe().c_str(), parameters_.method.c_str(), parameters_.map.c_str(),
           map_->semantic.objects.size(), map_->semantic.chains.size(), objects.c_str(),
           DescribeLocalizationParameters(parameters_).c_str(),
           ::ros::Time::isSimTime() ? ", use_sim_time" : "");
}

void LocalizationNode::OnScan(const sensor_msgs::LaserScanConstPtr& message,
                              const ScanArrival& arrival) {
  const std::optional<StampedScan> scan =
      ScanWithOdometry(tf_buffer_, *message, parameters_.frames);
  if (!scan) {
    ++timings_.dropped_scans;
    return;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  const double cpu_start = ThreadCpuSeconds();
  const int iterations = localizer_.AddScan(*scan);
  timings_.cpu_ms.push_back(1000.0 * (ThreadCpuSeconds() - cpu_start));
  NoteState();
  const bool pose_published = Publish(message->header.stamp, scan->odometry, iterations > 0);
  const ::ros::WallTime published = ::ros::WallTime::now();
  const double latency_ms = 1000.0 * (published - arrival.arrived).toSec();
  timings_.latency_ms.push_back(latency_ms);
  if (pose_published) timings_.pose_latency_ms.push_back(latency_ms);
  timings_.tf_wait_ms.push_back(1000.0 * (arrival.released - arrival.arrived).toSec());
  timings_.processing_ms.push_back(1000.0 * (published - arrival.released).toSec());
}

bool LocalizationNode::Publish(const ::ros::Time& stamp, const Pose2& odometry,
                               bool filter_updated) {
  const std::optional<Pose2>& pose = localizer_.pose();
  bool pose_published = false;
  if (pose) ++timings_.scans_with_pose;
  // As amcl: the pose goes out when the filter updated (or is forced), the last map → odom is
  // sent again after every scan.
  if (pose && (filter_updated || force_pose_ || parameters_.publish_pose_every_scan)) {
    force_pose_ = false;
    geometry_msgs::PoseWithCovarianceStamped message;
    message.header.stamp = stamp;
    message.header.frame_id = parameters_.frames.global_frame_id;
    message.pose.pose = ToPoseMsg(*pose);
    const Eigen::Matrix3d covariance = localizer_.covariance();
    // ROS's 6×6 (x, y, z, roll, pitch, yaw) row-major; the planar entries only.
    const int index[3] = {0, 1, 5};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c)
        message.pose.covariance[6 * index[r] + index[c]] = covariance(r, c);
    }
    pose_publisher_.publish(message);
    pose_published = true;
    ++timings_.poses_published;

    // map → odom such that map → odom → base_link is the pose, future-dated as amcl does so
    // that consumers can use it until the next scan.
    geometry_msgs::TransformStamped map_from_odom;
    map_from_odom.header.stamp = stamp + ::ros::Duration(parameters_.transform_tolerance);
    map_from_odom.header.frame_id = parameters_.frames.global_frame_id;
    map_from_odom.child_frame_id = parameters_.frames.odom_frame_id;
    map_from_odom.transform = ToTransformMsg(*pose * odometry.Inverse());
    map_from_odom_ = map_from_odom;
  }
  if (map_from_odom_ && parameters_.tf_broadcast) {
    map_from_odom_->header.stamp = stamp + ::ros::Duration(parameters_.transform_tolerance);
    tf_broadcaster_.sendTransform(*map_from_odom_);
  }
  if (filter_updated && !localizer_.particles().empty()) {
    geometry_msgs::PoseArray cloud;
    cloud.header.stamp = stamp;
    cloud.header.frame_id = parameters_.frames.global_frame_id;
    for (const localization::Particle& p : localizer_.particles()) {
      cloud.poses.push_back(ToPoseMsg(p.pose));
    }
    particles_publisher_.publish(cloud);
  }
  if (localizer_.hypotheses().size() != published_hypotheses_) PublishObjects();
  return pose_published;
}

void LocalizationNode::PublishObjects() {
  published_hypotheses_ = localizer_.hypotheses().size();
  visualization_msgs::MarkerArray markers =
      ObjectMarkers(map_->semantic, localizer_.hypotheses(), parameters_.frames.global_frame_id);
  const ::ros::Time now = ::ros::Time::now();
  for (visualization_msgs::Marker& marker : markers.markers) marker.header.stamp = now;
  objects_publisher_.publish(markers);
}

void LocalizationNode::NoteState() {
  const localization::LocalizerState state = localizer_.state();
  if (state == last_state_) return;
  last_state_ = state;
  force_pose_ = true;
  if (localizer_.pose()) {
    const Pose2& p = *localizer_.pose();
    ROS_INFO("semchain_ros: %s at (%.2f, %.2f, %.1f deg)", localization::LocalizerStateName(state),
             p.x, p.y, p.theta * 180.0 / M_PI);
  } else {
    ROS_INFO("semchain_ros: %s", localization::LocalizerStateName(state));
  }
}

void LocalizationNode::OnCameraInfo(const sensor_msgs::CameraInfoConstPtr& message) {
  camera_.OnCameraInfo(*message);
}

void LocalizationNode::AddFrame(double stamp, std::vector<Detection> detections,
                                const cv::Mat& color) {
  const std::optional<MountedCamera> camera = camera_.Camera(tf_buffer_, parameters_.frames);
  if (!camera) {
    if (!camera_.has_info()) {
      SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: detections before any camera_info; skipped");
    }
    return;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  localizer_.AddFrame({stamp, std::move(detections), *camera, color, {}});
}

void LocalizationNode::OnDetections(const std_msgs::StringConstPtr& message) {
  Result<FrameDetections> frame = ParseDetectionsRecord(message->data, "/semchain/detections");
  if (!frame.ok()) {
    SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: %s", frame.status().message().c_str());
    return;
  }
  AddFrame(frame->stamp, std::move(frame->detections), cv::Mat());
}

void LocalizationNode::OnDepthImage(const sensor_msgs::ImageConstPtr& message) {
  std::optional<RgbdDetections> frame = rgbd_.OnDepthImage(message);
  if (frame) AddFrame(frame->stamp, std::move(frame->detections), frame->color);
}

void LocalizationNode::OnColorImage(const sensor_msgs::ImageConstPtr& message) {
  std::optional<RgbdDetections> frame = rgbd_.OnColorImage(message);
  if (frame) AddFrame(frame->stamp, std::move(frame->detections), frame->color);
}

void LocalizationNode::OnInitialPose(
    const geometry_msgs::PoseWithCovarianceStampedConstPtr& message) {
  if (!message->header.frame_id.empty() &&
      message->header.frame_id != parameters_.frames.global_frame_id) {
    ROS_WARN("semchain_ros: /initialpose in frame '%s', expected '%s'; ignored",
             message->header.frame_id.c_str(), parameters_.frames.global_frame_id.c_str());
    return;
  }
  const auto& c = message->pose.covariance;  // 6 × 6 row-major (x, y, z, roll, pitch, yaw)
  Eigen::Matrix3d covariance;
  covariance << c[0], c[1], c[5], c[6], c[7], c[11], c[30], c[31], c[35];
  const Pose2 pose = PlanarPose(ToIsometry(message->pose.pose));
  const std::lock_guard<std::mutex> lock(mutex_);
  localizer_.SetInitialPose(pose, covariance);
  force_pose_ = true;
  ROS_INFO("semchain_ros: initial pose (%.2f, %.2f, %.1f deg)", pose.x, pose.y,
           pose.theta * 180.0 / M_PI);
}

bool LocalizationNode::OnGlobalLocalization(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  const std::lock_guard<std::mutex> lock(mutex_);
  localizer_.RelocalizeGlobally();
  map_from_odom_.reset();
  ROS_INFO("semchain_ros: global localization requested");
  NoteState();
  return true;
}

Status LocalizationNode::WriteStats() const {
  if (parameters_.stats_file.empty()) return Status::Ok();
  const localization::LocalizerStatistics& statistics = localizer_.statistics();
  nlohmann::json stats = {
      {"method", parameters_.method},
      {"scans", statistics.scans},
      {"dropped_scans", timings_.dropped_scans + (scan_input_ ? scan_input_->dropped() : 0)},
      {"rescued_scans", scan_input_ ? scan_input_->rescued() : 0},
      {"scans_with_pose", timings_.scans_with_pose},
      {"poses_published", timings_.poses_published},
      {"publish_pose_every_scan", parameters_.publish_pose_every_scan},
      {"iterations", statistics.iterations},
      {"prelocalizations", statistics.prelocalizations},
      {"cpu_ms_per_scan", Spread(timings_.cpu_ms)},
      {"latency_ms", Spread(timings_.latency_ms)},
      {"pose_latency_ms", Spread(timings_.pose_latency_ms)},
      {"tf_wait_ms", Spread(timings_.tf_wait_ms)},
      {"processing_ms", Spread(timings_.processing_ms)},
      {"state", localization::LocalizerStateName(localizer_.state())}};
  if (localizer_.pose()) {
    stats["pose"] = {localizer_.pose()->x, localizer_.pose()->y, localizer_.pose()->theta};
  }
  return WriteFileAtomically(parameters_.stats_file, stats.dump(2) + "\n");
}

}  // namespace semchain::ros1
