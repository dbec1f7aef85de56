#include "ros/camera_import.h"

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <algorithm>
#include <cmath>

#include "core/atomic_file.h"
#include "ros/bag_time.h"
#include "ros/frame_pairing.h"
#include "ros/ros_image.h"
#include "sim/rgbd_renderer.h"
#include "sim/run_directory.h"

namespace semchain::ros1 {
namespace {

constexpr double kDefaultMaxRange = 6.0;  // CameraInfo's default, for a bag without frames

// The unit of the depth PNGs written: the run's when the bag comes from `bag export`, else
// millimetres (REP 118's 16UC1).
double OutputDepthScale(const ImportContext& context) {
  return context.run_info && context.run_info->camera ? context.run_info->camera->depth_scale
                                                      : 0.001;
}

struct Calibration {
  PinholeCamera intrinsics;
  std::string frame_id;
};

// The first camera_info message (a camera's calibration does not change during a recording).
Result<Calibration> ReadCalibration(BagReader& reader, ImportContext& context) {
  std::optional<Calibration> calibration;
  bool distortion = false;
  SEMCHAIN_RETURN_IF_ERROR(reader.ForEach<sensor_msgs::CameraInfo>(
      {context.options.topics.CameraInfo()},
      [&](const sensor_msgs::CameraInfo& msg, const BagMessage& message) -> Status {
        if (calibration) return Status::Ok();
        Result<PinholeCamera> intrinsics = FromCameraInfoMsg(msg, &distortion);
        if (!intrinsics.ok()) return intrinsics.status().WithContext(message.where);
        calibration =
            Calibration{*intrinsics, TfFrameId(msg.header.frame_id, context.options.frames.camera)};
        return Status::Ok();
      }));
  if (!calibration) return Status::Error(reader.path().string() + ": no camera_info message");
  if (distortion) {
    context.warnings.push_back(context.options.topics.CameraInfo() +
                               " has distortion coefficients; semchain's camera model has none "
                               "(record rectified images)");
  }
  return *calibration;
}

// Rotation entries within this of 0 or ±1 are written as such: a rotation that went through a
// quaternion comes back with 1e-16 where the camera had exact zeros.
Eigen::Isometry3d Tidy(Eigen::Isometry3d pose) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      double& value = pose.matrix()(r, c);
      const double nearest = std::round(value);
      if (std::abs(value - nearest) < 1e-12) value = nearest;
    }
  }
  return pose;
}

// Pairs and writes the frames, remembering the deepest reading for camera.yaml's max_range.
class FrameWriter {
 public:
  FrameWriter(const std::filesystem::path& run_dir, const PinholeCamera& camera, double depth_scale,
              const ImportContext& context)
      : frames_dir_(run_dir / "frames"),
        camera_(camera),
        depth_scale_(depth_scale),
        context_(context) {}

  Status Write(StampedImage color, StampedImage depth);
  std::vector<ImportedFrame>& frames() { return frames_; }
  double deepest_m() const { return deepest_m_; }

 private:
  std::filesystem::path frames_dir_;
  PinholeCamera camera_;
  double depth_scale_;
  const ImportContext& context_;
  std::vector<ImportedFrame> frames_;
  double deepest_m_ = 0.0;
};

Status FrameWriter::Write(StampedImage color, StampedImage depth) {
  const int index = static_cast<int>(frames_.size());
  const std::string name = sim::FrameName(index);
  for (const cv::Mat* image : {&color.image, &depth.image}) {
    if (image->cols != camera_.width || image->rows != camera_.height) {
      return Status::Error(name + ": image " + std::to_string(image->cols) + "x" +
                           std::to_string(image->rows) + ", camera_info says " +
                           std::to_string(camera_.width) + "x" + std::to_string(camera_.height));
    }
  }
  if (index == 0) SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(frames_dir_));
  double deepest = 0.0;
  cv::minMaxLoc(depth.image, nullptr, &deepest);
  deepest_m_ = std::max(deepest_m_, deepest * depth_scale_);
  sim::RgbdImage rgbd;
  rgbd.rgb = std::move(color.image);
  rgbd.depth = std::move(depth.image);
  SEMCHAIN_RETURN_IF_ERROR(sim::WriteFrame(frames_dir_, index, rgbd));
  ros::Time time;
  time.fromNSec(static_cast<std::uint64_t>(color.stamp_ns));
  frames_.push_back({name, color.stamp_ns, FromRosTime(time, context_.stamp_offset_seconds)});
  return Status::Ok();
}

// Streams the colour and depth topics through a FramePairer into 'writer'.
Status PairImages(BagReader& reader, FrameWriter& writer, ImportContext& context) {
  const BagTopics& topics = context.options.topics;
  FramePairer pairer(context.max_pair_gap_ns(), [&writer](StampedImage color, StampedImage depth) {
    return writer.Write(std::move(color), std::move(depth));
  });
  const double depth_scale = OutputDepthScale(context);
  SEMCHAIN_RETURN_IF_ERROR(reader.ForEach<sensor_msgs::Image>(
      {topics.ColorImage(), topics.DepthImage()},
      [&](const sensor_msgs::Image& msg, const BagMessage& message) -> Status {
        const bool is_color = message.topic == topics.ColorImage();
        Result<cv::Mat> image =
            is_color ? ColorFromImageMsg(msg) : DepthFromImageMsg(msg, depth_scale);
        if (!image.ok()) return image.status().WithContext(message.where);
        StampedImage stamped{Nanoseconds(msg.header.stamp), std::move(*image)};
        const Status status =
            is_color ? pairer.AddColor(std::move(stamped)) : pairer.AddDepth(std::move(stamped));
        return status.WithContext(message.where);
      }));
  pairer.Finish();
  if (pairer.unpaired_color() + pairer.unpaired_depth() > 0) {
    context.warnings.push_back(std::to_string(pairer.unpaired_color()) + " colour and " +
                               std::to_string(pairer.unpaired_depth()) +
                               " depth images left out: no partner within " +
                               std::to_string(context.options.max_pair_gap_s) + " s");
  }
  return Status::Ok();
}

// camera.yaml's values that no ROS message carries: from the run info `bag export` wrote, the
// options, or the frames.
void SetExtras(const ImportContext& context, const std::vector<ImportedFrame>& frames,
               double deepest_m, CameraInfo* camera) {
  if (context.run_info && context.run_info->camera) {
    const CameraExtras& extras = *context.run_info->camera;
    camera->camera.max_range = extras.max_range;
    camera->depth_scale = extras.depth_scale;
    camera->frame_rate_hz = extras.frame_rate_hz;
  } else {
    camera->camera.max_range =
        deepest_m > 0.0 ? std::ceil(deepest_m * 10.0 - 1e-9) / 10.0 : kDefaultMaxRange;
    camera->depth_scale = OutputDepthScale(context);
    if (frames.size() >= 2 && frames.back().stamp > frames.front().stamp) {
      camera->frame_rate_hz =
          static_cast<double>(frames.size() - 1) / (frames.back().stamp - frames.front().stamp);
    }
  }
  if (context.options.camera_max_range)
    camera->camera.max_range = *context.options.camera_max_range;
}

}  // namespace

Result<ImportedCamera> ImportCamera(BagReader& reader, const BagTransforms& transforms,
                                    const std::filesystem::path& run_dir, ImportContext& context) {
  const BagTopics& topics = context.options.topics;
  ImportedCamera result;
  const bool images = reader.Has(topics.ColorImage());
  if (!images && !reader.Has(topics.CameraInfo())) return result;
  SEMCHAIN_RETURN_IF_ERROR(reader.Require<sensor_msgs::CameraInfo>(topics.CameraInfo()));
  if (images) SEMCHAIN_RETURN_IF_ERROR(reader.Require<sensor_msgs::Image>(topics.DepthImage()));
  Result<Calibration> calibration = ReadCalibration(reader, context);
  if (!calibration.ok()) return calibration.status();
  const std::string& base = context.options.frames.base;
  Result<Eigen::Isometry3d> mounting = transforms.Lookup(base, calibration->frame_id, ros::Time());
  if (!mounting.ok()) {
    return Status::Error(reader.path().string() + ": no pose of the camera: " +
                         mounting.status().message() + " (tf frames: " + transforms.Frames() + ")");
  }
  CameraInfo camera;
  camera.camera.intrinsics = calibration->intrinsics;
  camera.camera.robot_from_camera = Tidy(*mounting);
  FrameWriter writer(run_dir, calibration->intrinsics, OutputDepthScale(context), context);
  if (images) SEMCHAIN_RETURN_IF_ERROR(PairImages(reader, writer, context));
  result.frames = std::move(writer.frames());
  SetExtras(context, result.frames, writer.deepest_m(), &camera);
  result.camera = camera;
  return result;
}

}  // namespace semchain::ros1
