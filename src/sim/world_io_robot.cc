// The robot and detection-model sections of a world file.
#include <cmath>
#include <string>
#include <vector>

#include "core/angles.h"
#include "sim/world_io_internal.h"

namespace semchain::sim::internal {
namespace {

using yaml::Node;

Status ReadPositiveInt(const Node& map, const std::string& key, int* value) {
  if (!map.Has(key)) return Status::Ok();
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(map, key, value));
  if (*value <= 0) return map.Get(key)->Error("must be positive");
  return Status::Ok();
}

constexpr int kMaxCameraSide = 8192;
constexpr int kMaxLidarBeams = 100'000;

Status ParseLidar(const Node& node, LidarSpec* lidar) {
  SEMCHAIN_RETURN_IF_ERROR(
      node.CheckKeys({"height", "beams", "fov_deg", "max_range", "noise_std", "forward_offset"}));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "height", &lidar->height, false));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositiveInt(node, "beams", &lidar->beams));
  if (lidar->beams > kMaxLidarBeams) {
    return node.Get("beams")->Error("must be at most " + std::to_string(kMaxLidarBeams));
  }
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "fov_deg", &lidar->fov_deg, false));
  if (lidar->fov_deg > 360.0) return node.Get("fov_deg")->Error("must be at most 360");
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "max_range", &lidar->max_range, false));
  SEMCHAIN_RETURN_IF_ERROR(ReadNonNegative(node, "noise_std", &lidar->noise_std));
  return yaml::ReadOptional(node, "forward_offset", &lidar->forward_offset);
}

Status ParseCamera(const Node& node, CameraSpec* camera) {
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys(
      {"height", "fov_deg", "width", "height_px", "max_range", "pitch_deg", "roll_deg",
       "forward_offset", "depth_noise_std", "exposure", "rgb_noise_std", "blur_sigma_px"}));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "height", &camera->height, false));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "fov_deg", &camera->fov_deg, false));
  if (camera->fov_deg >= 180.0) return node.Get("fov_deg")->Error("must be below 180");
  SEMCHAIN_RETURN_IF_ERROR(ReadPositiveInt(node, "width", &camera->width));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositiveInt(node, "height_px", &camera->height_px));
  // A frame is rendered, kept and encoded whole: refuse sizes no camera has.
  for (const auto& [key, value] :
       {std::pair{"width", camera->width}, {"height_px", camera->height_px}}) {
    if (value > kMaxCameraSide) {
      return node.Get(key)->Error("must be at most " + std::to_string(kMaxCameraSide) + " pixels");
    }
  }
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "max_range", &camera->max_range, false));
  SEMCHAIN_RETURN_IF_ERROR(ReadInRange(node, "pitch_deg", -89.0, 89.0, &camera->pitch_deg));
  SEMCHAIN_RETURN_IF_ERROR(ReadInRange(node, "roll_deg", -45.0, 45.0, &camera->roll_deg));
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(node, "forward_offset", &camera->forward_offset));
  SEMCHAIN_RETURN_IF_ERROR(ReadInRange(node, "exposure", 0.05, 20.0, &camera->exposure));
  SEMCHAIN_RETURN_IF_ERROR(ReadInRange(node, "rgb_noise_std", 0.0, 128.0, &camera->rgb_noise_std));
  SEMCHAIN_RETURN_IF_ERROR(ReadInRange(node, "blur_sigma_px", 0.0, 50.0, &camera->blur_sigma_px));
  return ReadNonNegative(node, "depth_noise_std", &camera->depth_noise_std);
}

Status ParseStart(const Node& robot, Pose2* start) {
  Result<Node> node = robot.Get("start");
  if (!node.ok()) return node.status();
  Result<std::vector<double>> pose = node->AsDoubleList(3);
  if (!pose.ok()) return node->Error("expected [x, y, theta_radians]");
  *start = Pose2((*pose)[0], (*pose)[1], NormalizeAngle((*pose)[2]));
  return Status::Ok();
}

Status ParseOdometryNoise(const Node& robot, std::array<double, 4>* alphas) {
  if (!robot.Has("odometry_noise")) return Status::Ok();
  Result<Node> node = robot.Get("odometry_noise");
  Result<std::vector<double>> values = node->AsDoubleList(4);
  if (!values.ok()) return values.status();
  for (int i = 0; i < 4; ++i) {
    if ((*values)[i] < 0.0) return node->Error("alpha1..alpha4 must not be negative");
    (*alphas)[i] = (*values)[i];
  }
  return Status::Ok();
}

Status ParseOdometryScaleError(const Node& robot, OdometryScaleError* error) {
  if (!robot.Has("odometry_scale_error")) return Status::Ok();
  Result<Node> node = robot.Get("odometry_scale_error");
  Result<std::vector<double>> values = node->AsDoubleList(2);
  if (!values.ok()) return values.status();
  for (const double value : *values) {
    // A factor 1 + e of zero or less would reverse or freeze the odometry.
    if (!(std::abs(value) < 0.5)) {
      return node->Error("expected [distance, turn] fractions, each within ±0.5");
    }
  }
  *error = {(*values)[0], (*values)[1]};
  return Status::Ok();
}

}  // namespace

Status ParseRobot(const Node& node, RobotSpec* robot) {
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys({"start", "radius", "lidar", "camera", "odometry_noise",
                                           "odometry_scale_error", "max_speed", "max_turn_rate",
                                           "scan_rate_hz", "frame_rate_hz"}));
  SEMCHAIN_RETURN_IF_ERROR(ParseStart(node, &robot->start));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "radius", &robot->radius, false));
  if (node.Has("lidar")) SEMCHAIN_RETURN_IF_ERROR(ParseLidar(*node.Get("lidar"), &robot->lidar));
  if (node.Has("camera")) {
    SEMCHAIN_RETURN_IF_ERROR(ParseCamera(*node.Get("camera"), &robot->camera));
  }
  SEMCHAIN_RETURN_IF_ERROR(ParseOdometryNoise(node, &robot->odometry_noise));
  SEMCHAIN_RETURN_IF_ERROR(ParseOdometryScaleError(node, &robot->odometry_scale_error));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "max_speed", &robot->max_speed, false));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "max_turn_rate", &robot->max_turn_rate, false));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "scan_rate_hz", &robot->scan_rate_hz, false));
  SEMCHAIN_RETURN_IF_ERROR(ReadPositive(node, "frame_rate_hz", &robot->frame_rate_hz, false));
  if (robot->frame_rate_hz > robot->scan_rate_hz) {
    // Frames are taken at scan instants, so that every frame has a logged pose.
    const std::string key = node.Has("frame_rate_hz") ? "frame_rate_hz" : "scan_rate_hz";
    return node.Get(key)->Error("frame_rate_hz must not exceed scan_rate_hz");
  }
  return Status::Ok();
}

Status ParseDetectionModel(const Node& node, DetectionModelSpec* model) {
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys({"miss_probability", "confusion_probability",
                                           "false_positives_per_frame", "min_visible_fraction",
                                           "min_box_pixels", "box_noise_px", "depth_noise_std"}));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadInRange(node, "miss_probability", 0.0, 1.0, &model->miss_probability));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadInRange(node, "confusion_probability", 0.0, 1.0, &model->confusion_probability));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadNonNegative(node, "false_positives_per_frame", &model->false_positives_per_frame));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadInRange(node, "min_visible_fraction", 0.0, 1.0, &model->min_visible_fraction));
  SEMCHAIN_RETURN_IF_ERROR(ReadNonNegativeInt(node, "min_box_pixels", &model->min_box_pixels));
  SEMCHAIN_RETURN_IF_ERROR(ReadNonNegative(node, "box_noise_px", &model->box_noise_px));
  return ReadNonNegative(node, "depth_noise_std", &model->depth_noise_std);
}

}  // namespace semchain::sim::internal
