#include "ros/bag_export.h"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <system_error>
#include <vector>

#include "core/progress_bar.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"
#include "ros/bag_time.h"
#include "ros/ros_geometry.h"
#include "ros/ros_image.h"
#include "ros/ros_scan.h"
#include "ros/run_contents.h"
#include "ros/run_info.h"

namespace semchain::ros1 {
namespace fs = std::filesystem;
namespace {

// What happens at one stamp; at equal stamps scans go first, then truth, then frames.
struct Event {
  enum class Kind { kScan, kTruth, kFrame };
  ros::Time time;
  Kind kind;
  std::size_t index;  // into RunContents' lasers, truth or frames
};

// The least gap between consecutive scans' stamps in the bag.
constexpr double kMinScanGapSeconds = 1e-3;

// The scans' stamps, each at least kMinScanGapSeconds after the one before ('restamped' counts
// those moved).
std::vector<double> MonotonicScanStamps(const RunContents& run, std::size_t* restamped) {
  std::vector<double> stamps;
  for (const carmen::Laser& laser : run.lasers) {
    double stamp = laser.stamp.timestamp;
    if (!stamps.empty() && stamp < stamps.back() + kMinScanGapSeconds) {
      stamp = stamps.back() + kMinScanGapSeconds;
      ++*restamped;
    }
    stamps.push_back(stamp);
  }
  return stamps;
}

Result<std::vector<Event>> MakeEvents(const RunContents& run, std::int64_t offset,
                                      std::size_t* restamped) {
  std::vector<Event> events;
  const auto add = [&](double stamp, Event::Kind kind, std::size_t index) -> Status {
    Result<ros::Time> time = ToRosTime(stamp, offset);
    if (!time.ok()) return time.status();
    events.push_back({*time, kind, index});
    return Status::Ok();
  };
  const std::vector<double> scan_stamps = MonotonicScanStamps(run, restamped);
  for (std::size_t i = 0; i < run.lasers.size(); ++i) {
    SEMCHAIN_RETURN_IF_ERROR(add(scan_stamps[i], Event::Kind::kScan, i));
  }
  for (std::size_t i = 0; i < run.truth.size(); ++i) {
    SEMCHAIN_RETURN_IF_ERROR(add(run.truth[i].timestamp, Event::Kind::kTruth, i));
  }
  for (std::size_t i = 0; i < run.frames.size(); ++i) {
    SEMCHAIN_RETURN_IF_ERROR(add(run.frames[i].stamp, Event::Kind::kFrame, i));
  }
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
    // By the stamps' nanoseconds: ros::Time's operator!= is ambiguous in C++20 under clang (its
    // == may also be used reversed), which the fuzz build compiles this with.
    const std::uint64_t ta = a.time.toNSec(), tb = b.time.toNSec();
    return ta != tb ? ta < tb : a.kind < b.kind;
  });
  return events;
}

// Writes the messages of a loaded run into a bag.
class Exporter {
 public:
  Exporter(const fs::path& run_dir, const RunContents& run, const BagExportOptions& options,
           BagWriter& bag)
      : run_dir_(run_dir), run_(run), options_(options), bag_(bag) {}

  Status WriteStart(const ros::Time& time, const RunInfo& info);
  Status Write(const Event& event);
  const BagExportSummary& summary() const { return summary_; }

 private:
  template <typename Message>
  Status Put(const std::string& topic, const ros::Time& time, const Message& msg,
             bool latched = false) {
    ++summary_.messages;
    return bag_.Write(topic, time, msg, latched);
  }
  std_msgs::Header Header(const ros::Time& time, const std::string& frame_id) const {
    std_msgs::Header header;
    header.stamp = time;
    header.frame_id = frame_id;
    return header;
  }
  geometry_msgs::TransformStamped Transform(const ros::Time& time, const std::string& parent,
                                            const std::string& child,
                                            const geometry_msgs::Transform& pose) const {
    geometry_msgs::TransformStamped transform;
    transform.header = Header(time, parent);
    transform.child_frame_id = child;
    transform.transform = pose;
    return transform;
  }
  Status WriteScan(const carmen::Laser& laser, const ros::Time& time);
  Status WriteFrame(const CameraFrame& frame, const ros::Time& time);
  Status WriteImages(const CameraFrame& frame, const std_msgs::Header& header);

  const fs::path& run_dir_;
  const RunContents& run_;
  const BagExportOptions& options_;
  BagWriter& bag_;
  BagExportSummary summary_;
};

Status Exporter::WriteStart(const ros::Time& time, const RunInfo& info) {
  std_msgs::String run_info;
  run_info.data = FormatRunInfo(info);
  SEMCHAIN_RETURN_IF_ERROR(Put(options_.topics.run_info, time, run_info, true));
  // The laser sits where the first scan's log line puts it relative to the odometry pose.
  const BagFrames& frames = options_.frames;
  tf2_msgs::TFMessage statics;
  const Pose2 laser = run_.lasers.front().scan.LaserOffset();
  statics.transforms.push_back(Transform(time, frames.base, frames.laser, ToTransformMsg(laser)));
  if (run_.camera) {
    statics.transforms.push_back(Transform(time, frames.base, frames.camera,
                                           ToTransformMsg(run_.camera->camera.robot_from_camera)));
  }
  return Put(options_.topics.tf_static, time, statics, true);
}

Status Exporter::Write(const Event& event) {
  switch (event.kind) {
    case Event::Kind::kScan:
      return WriteScan(run_.lasers[event.index], event.time);
    case Event::Kind::kTruth: {
      geometry_msgs::PoseStamped truth;
      truth.header = Header(event.time, options_.frames.map);
      truth.pose = ToPoseMsg(run_.truth[event.index].pose);
      return Put(options_.topics.truth, event.time, truth);
    }
    case Event::Kind::kFrame:
      return WriteFrame(run_.frames[event.index], event.time);
  }
  return Status::Ok();
}

Status Exporter::WriteScan(const carmen::Laser& laser, const ros::Time& time) {
  const BagFrames& frames = options_.frames;
  ++summary_.scans;
  SEMCHAIN_RETURN_IF_ERROR(
      Put(options_.topics.scan, time, ToLaserScanMsg(laser, Header(time, frames.laser))));
  tf2_msgs::TFMessage tf;
  tf.transforms.push_back(
      Transform(time, frames.odom, frames.base, ToTransformMsg(laser.scan.odometry)));
  SEMCHAIN_RETURN_IF_ERROR(Put(options_.topics.tf, time, tf));
  nav_msgs::Odometry odometry;
  odometry.header = Header(time, frames.odom);
  odometry.child_frame_id = frames.base;
  odometry.pose.pose = ToPoseMsg(laser.scan.odometry);
  odometry.twist.twist.linear.x = laser.tv;
  odometry.twist.twist.angular.z = laser.rv;
  return Put(options_.topics.odom, time, odometry);
}

Status Exporter::WriteFrame(const CameraFrame& frame, const ros::Time& time) {
  ++summary_.frames;
  const std_msgs::Header header = Header(time, options_.frames.camera);
  if (run_.camera) {
    SEMCHAIN_RETURN_IF_ERROR(Put(options_.topics.CameraInfo(), time,
                                 ToCameraInfoMsg(run_.camera->camera.intrinsics, header)));
  }
  if (options_.images && frame.has_images) SEMCHAIN_RETURN_IF_ERROR(WriteImages(frame, header));
  if (!frame.detections) return Status::Ok();
  // The record travels on the bag's clock, like every other stamp in it.
  FrameDetections record = *frame.detections;
  record.stamp = FromRosTime(time, 0);
  Result<std::string> line = FormatDetectionsRecord(record);
  if (!line.ok()) return line.status().WithContext(frame.name);
  std_msgs::String detections;
  detections.data = *line;
  return Put(options_.topics.detections, time, detections);
}

Status Exporter::WriteImages(const CameraFrame& frame, const std_msgs::Header& header) {
  Result<cv::Mat> rgb = ReadColorImage(ColorImagePath(run_dir_, frame.name));
  if (!rgb.ok()) return rgb.status();
  const fs::path depth_path = DepthImagePath(run_dir_, frame.name);
  const cv::Mat raw = cv::imread(depth_path.string(), cv::IMREAD_UNCHANGED);
  if (raw.type() != CV_16UC1 || raw.size() != rgb->size()) {
    return Status::Error(depth_path.string() +
                         ": expected a 16-bit depth image the size of the colour image");
  }
  SEMCHAIN_RETURN_IF_ERROR(
      Put(options_.topics.ColorImage(), header.stamp, ToColorImageMsg(*rgb, header)));
  SEMCHAIN_RETURN_IF_ERROR(Put(options_.topics.DepthImage(), header.stamp,
                               ToDepthImageMsg(raw, run_.camera->depth_scale, header)));
  summary_.images += 2;
  return Status::Ok();
}

RunInfo MakeRunInfo(const RunContents& run, std::int64_t offset) {
  RunInfo info;
  info.stamp_offset_seconds = offset;
  if (run.camera) {
    info.camera = CameraExtras{run.camera->camera.max_range, run.camera->depth_scale,
                               run.camera->frame_rate_hz};
  }
  info.world_yaml = run.world_yaml;
  return info;
}

// A CARMEN log alone as a run: its scans with their odometry.
Result<RunContents> LoadLogAsRun(const fs::path& log_path) {
  Result<carmen::Log> log = carmen::ReadLog(log_path);
  if (!log.ok()) return log.status();
  RunContents run;
  for (const carmen::Laser* laser : log->Lasers()) run.lasers.push_back(*laser);
  if (run.lasers.empty()) {
    return Status::Error(log_path.string() + ": no laser scans (FLASER or ROBOTLASER1 lines)");
  }
  return run;
}

}  // namespace

Result<BagExportSummary> ExportRunToBag(const fs::path& run_dir, const fs::path& bag_path,
                                        const BagExportOptions& options) {
  std::error_code error;
  Result<RunContents> run =
      fs::is_regular_file(run_dir, error) ? LoadLogAsRun(run_dir) : LoadRunContents(run_dir);
  if (!run.ok()) return run.status();
  const std::int64_t offset = ExportStampOffset(run->EarliestStamp());
  std::size_t restamped = 0;
  Result<std::vector<Event>> events = MakeEvents(*run, offset, &restamped);
  if (!events.ok()) return events.status().WithContext(run_dir.string());
  Result<std::unique_ptr<BagWriter>> bag = BagWriter::Create(bag_path, options.compression);
  if (!bag.ok()) return bag.status();
  Exporter exporter(run_dir, *run, options, **bag);
  SEMCHAIN_RETURN_IF_ERROR(exporter.WriteStart(events->front().time, MakeRunInfo(*run, offset)));
  std::optional<ProgressBar> progress;
  if (options.show_progress) progress.emplace("bag export", events->size());
  for (std::size_t i = 0; i < events->size(); ++i) {
    SEMCHAIN_RETURN_IF_ERROR(exporter.Write((*events)[i]));
    if (progress) progress->Update(i + 1);
  }
  if (progress) progress->Finish();
  SEMCHAIN_RETURN_IF_ERROR((*bag)->Finish());
  BagExportSummary summary = exporter.summary();
  summary.stamp_offset_seconds = offset;
  summary.restamped_scans = restamped;
  return summary;
}

}  // namespace semchain::ros1
