#include "ros/camera_import.h"

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "core/atomic_file.h"
#include "ros/bag_time.h"
#include "ros/frame_pairing.h"
#include "ros/ros_compressed_image.h"
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

constexpr const char* kCalibrationHint = "; give the camera's calibration with --camera-yaml FILE";

// The first camera_info message of 'topic' (a camera's calibration does not change during a
// recording).
Result<Calibration> ReadCalibration(BagReader& reader, const std::string& topic,
                                    ImportContext& context) {
  const Status present = reader.Require<sensor_msgs::CameraInfo>(topic);
  if (!present.ok()) return Status::Error(present.message() + kCalibrationHint);
  std::optional<Calibration> calibration;
  bool distortion = false;
  SEMCHAIN_RETURN_IF_ERROR(reader.ForEach<sensor_msgs::CameraInfo>(
      {topic}, [&](const sensor_msgs::CameraInfo& msg, const BagMessage& message) -> Status {
        if (calibration) return Status::Ok();
        Result<PinholeCamera> intrinsics = FromCameraInfoMsg(msg, &distortion);
        if (!intrinsics.ok()) {
          return Status::Error(message.where + ": " + intrinsics.status().message() +
                               kCalibrationHint);
        }
        calibration =
            Calibration{*intrinsics, TfFrameId(msg.header.frame_id, context.options.frames.camera)};
        return Status::Ok();
      }));
  if (!calibration) return Status::Error(reader.path().string() + ": no camera_info message");
  if (distortion) {
    context.warnings.push_back(topic +
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

// An image of the camera, decoded: colour in RGB, depth in the run's depth units.
using ImageSink = std::function<Status(bool is_color, std::int64_t stamp_ns, cv::Mat image)>;

// Calls 'sink' with every image of the colour and depth topics of 'topics' (those not empty),
// raw or compressed, in bag order.
Status ReadImages(BagReader& reader, const CameraTopics& topics, double depth_scale,
                  const ImageSink& sink) {
  std::vector<std::string> raw;
  std::vector<std::string> compressed;
  if (!topics.color.empty()) (topics.color_compressed ? compressed : raw).push_back(topics.color);
  if (!topics.depth.empty()) (topics.depth_compressed ? compressed : raw).push_back(topics.depth);
  const auto pass = [&](Result<cv::Mat> image, const std_msgs::Header& header,
                        const BagMessage& message) -> Status {
    if (!image.ok()) return image.status().WithContext(message.where);
    return sink(message.topic == topics.color, Nanoseconds(header.stamp), std::move(*image))
        .WithContext(message.where);
  };
  return reader.ForEach<sensor_msgs::Image, sensor_msgs::CompressedImage>(
      raw,
      [&](const sensor_msgs::Image& msg, const BagMessage& message) -> Status {
        const bool is_color = message.topic == topics.color;
        return pass(is_color ? ColorFromImageMsg(msg) : DepthFromImageMsg(msg, depth_scale),
                    msg.header, message);
      },
      compressed,
      [&](const sensor_msgs::CompressedImage& msg, const BagMessage& message) -> Status {
        const bool is_color = message.topic == topics.color;
        return pass(
            is_color ? ColorFromCompressedMsg(msg) : DepthFromCompressedMsg(msg, depth_scale),
            msg.header, message);
      });
}

// Streams the colour and depth images through a FramePairer into 'writer'.
Status PairImages(BagReader& reader, const CameraTopics& topics, FrameWriter& writer,
                  ImportContext& context) {
  FramePairer pairer(context.max_pair_gap_ns(), [&writer](StampedImage color, StampedImage depth) {
    return writer.Write(std::move(color), std::move(depth));
  });
  SEMCHAIN_RETURN_IF_ERROR(ReadImages(
      reader, topics, OutputDepthScale(context),
      [&pairer](bool is_color, std::int64_t stamp_ns, cv::Mat image) {
        StampedImage stamped{stamp_ns, std::move(image)};
        return is_color ? pairer.AddColor(std::move(stamped)) : pairer.AddDepth(std::move(stamped));
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

// A camera without depth: each colour image is a frame whose depth image holds no reading.
Status WriteColorOnly(BagReader& reader, const CameraTopics& topics, const PinholeCamera& camera,
                      FrameWriter& writer, ImportContext& context) {
  context.warnings.push_back(
      topics.color +
      ": colour images without depth (the bag has no depth topic; --depth-topic "
      "names one): the frames' depth images hold no reading");
  const cv::Mat no_depth = cv::Mat::zeros(camera.height, camera.width, CV_16UC1);
  return ReadImages(reader, topics, OutputDepthScale(context),
                    [&](bool, std::int64_t stamp_ns, cv::Mat image) {
                      return writer.Write({stamp_ns, std::move(image)}, {stamp_ns, no_depth});
                    });
}

// camera.yaml's values that no ROS message carries: from the run info `bag export` wrote, the
// options, or the frames.
void SetExtras(const ImportContext& context, const std::vector<ImportedFrame>& frames,
               double deepest_m, std::optional<double> file_max_range, CameraInfo* camera) {
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
  if (file_max_range) camera->camera.max_range = *file_max_range;
  if (context.options.camera_max_range)
    camera->camera.max_range = *context.options.camera_max_range;
}

// The camera's intrinsics and mounting (and max_range, from a file): --camera-yaml's, or from
// camera_info and tf.
struct CameraSetup {
  MountedCamera camera;
  std::optional<double> max_range;  // the file's
};

Result<CameraSetup> SetUpCamera(BagReader& reader, const BagTransforms& transforms,
                                const CameraTopics& topics, ImportContext& context) {
  const std::filesystem::path& file = context.options.camera_yaml;
  if (!file.empty()) {
    Result<CameraInfo> info = ReadCameraYaml(file);
    if (!info.ok()) return Status::Error("--camera-yaml: " + info.status().message());
    return CameraSetup{info->camera, info->camera.max_range};
  }
  Result<Calibration> calibration = ReadCalibration(reader, topics.camera_info, context);
  if (!calibration.ok()) return calibration.status();
  const std::string& base = context.options.frames.base;
  Result<Eigen::Isometry3d> mounting = transforms.Lookup(base, calibration->frame_id, ros::Time());
  if (!mounting.ok()) {
    return Status::Error(
        reader.path().string() + ": no pose of the camera: " + mounting.status().message() +
        " (tf frames: " + transforms.Frames() + "); give it with --camera-yaml FILE");
  }
  CameraSetup setup;
  setup.camera.intrinsics = calibration->intrinsics;
  setup.camera.robot_from_camera = Tidy(*mounting);
  return setup;
}

}  // namespace

Result<ImportedCamera> ImportCamera(BagReader& reader, const BagTransforms& transforms,
                                    const CameraTopics& topics,
                                    const std::filesystem::path& run_dir, ImportContext& context) {
  ImportedCamera result;
  const bool images = !topics.color.empty();
  if (!images && !reader.Has(topics.camera_info) && context.options.camera_yaml.empty()) {
    return result;
  }
  Result<CameraSetup> setup = SetUpCamera(reader, transforms, topics, context);
  if (!setup.ok()) return setup.status();
  const PinholeCamera& intrinsics = setup->camera.intrinsics;
  FrameWriter writer(run_dir, intrinsics, OutputDepthScale(context), context);
  if (images && !topics.depth.empty()) {
    SEMCHAIN_RETURN_IF_ERROR(PairImages(reader, topics, writer, context));
  } else if (images) {
    SEMCHAIN_RETURN_IF_ERROR(WriteColorOnly(reader, topics, intrinsics, writer, context));
  }
  result.frames = std::move(writer.frames());
  CameraInfo camera;
  camera.camera = setup->camera;
  SetExtras(context, result.frames, writer.deepest_m(), setup->max_range, &camera);
  result.camera = camera;
  return result;
}

}  // namespace semchain::ros1
