#include "io/camera_io.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <initializer_list>

#include "core/atomic_file.h"
#include "io/yaml_reader.h"

namespace semchain {
namespace {

std::string Number(double value) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.9g", value);
  return text;
}

std::string List(std::initializer_list<double> values) {
  std::string text = "[";
  for (double v : values) text += (text.size() > 1 ? ", " : "") + Number(v);
  return text + "]";
}

Result<double> PositiveNumber(const yaml::Node& map, const std::string& key) {
  Result<yaml::Node> node = map.Get(key);
  if (!node.ok()) return node.status();
  Result<double> value = node->AsDouble();
  if (!value.ok()) return value.status();
  if (*value <= 0.0) return node->Error("must be positive");
  return *value;
}

Result<int> PositiveInt(const yaml::Node& map, const std::string& key) {
  Result<yaml::Node> node = map.Get(key);
  if (!node.ok()) return node.status();
  Result<int> value = node->AsInt();
  if (!value.ok()) return value.status();
  if (*value <= 0) return node->Error("must be positive");
  return *value;
}

Result<Eigen::Isometry3d> ReadExtrinsics(const yaml::Node& node) {
  SEMCHAIN_RETURN_IF_ERROR(node.CheckKeys({"translation", "rotation", "quaternion_xyzw"}));
  Result<yaml::Node> translation_node = node.Get("translation");
  if (!translation_node.ok()) return translation_node.status();
  Result<std::vector<double>> translation = translation_node->AsDoubleList(3);
  if (!translation.ok()) return translation.status();

  Result<yaml::Node> rotation_node = node.Get("rotation");
  if (!rotation_node.ok()) return rotation_node.status();
  if (!rotation_node->IsSequence() || rotation_node->size() != 3) {
    return rotation_node->Error("expected 3 rows of 3 numbers");
  }
  Eigen::Matrix3d rotation;
  for (int row = 0; row < 3; ++row) {
    Result<std::vector<double>> values = rotation_node->At(row).AsDoubleList(3);
    if (!values.ok()) return values.status();
    for (int col = 0; col < 3; ++col) rotation(row, col) = (*values)[col];
  }
  const double orthogonality =
      (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm();
  if (orthogonality > 1e-6 || std::abs(rotation.determinant() - 1.0) > 1e-6) {
    return rotation_node->Error("is not a rotation matrix");
  }
  if (node.Has("quaternion_xyzw")) {
    Result<yaml::Node> q_node = node.Get("quaternion_xyzw");
    if (!q_node.ok()) return q_node.status();
    Result<std::vector<double>> q = q_node->AsDoubleList(4);
    if (!q.ok()) return q.status();
    Eigen::Quaterniond quaternion((*q)[3], (*q)[0], (*q)[1], (*q)[2]);
    if (std::abs(quaternion.norm() - 1.0) > 1e-6 ||
        quaternion.angularDistance(Eigen::Quaterniond(rotation)) > 1e-6) {
      return q_node->Error("disagrees with the rotation matrix");
    }
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = Eigen::Vector3d((*translation)[0], (*translation)[1], (*translation)[2]);
  return pose;
}

}  // namespace

std::string FormatCameraYaml(const CameraInfo& info) {
  const PinholeCamera& k = info.camera.intrinsics;
  const Eigen::Matrix3d r = info.camera.robot_from_camera.rotation();
  const Eigen::Vector3d t = info.camera.robot_from_camera.translation();
  const Eigen::Quaterniond q(r);
  std::string text =
      "# An RGB-D camera. Pinhole model without distortion; pixel centres at integer\n"
      "# coordinates. The optical frame has z forward, x right, y down; the robot frame x "
      "forward,\n"
      "# y left, z up (z = 0 on the floor). Depth PNGs hold distances along the optical axis\n"
      "# (depth_scale metres per unit); 0 = no measurement.\n";
  text += "width: " + std::to_string(k.width) + "\n";
  text += "height: " + std::to_string(k.height) + "\n";
  text += "fx: " + Number(k.fx) + "\nfy: " + Number(k.fy) + "\n";
  text += "cx: " + Number(k.cx) + "\ncy: " + Number(k.cy) + "\n";
  text += "max_range: " + Number(info.camera.max_range) + "\n";
  text += "depth_scale: " + Number(info.depth_scale) + "\n";
  text += "frame_rate_hz: " + Number(info.frame_rate_hz) + "\n";
  text += "robot_from_camera:\n";
  text += "  translation: " + List({t.x(), t.y(), t.z()}) + "\n";
  text += "  rotation: [" + List({r(0, 0), r(0, 1), r(0, 2)}) + ", " +
          List({r(1, 0), r(1, 1), r(1, 2)}) + ", " + List({r(2, 0), r(2, 1), r(2, 2)}) + "]\n";
  text += "  quaternion_xyzw: " + List({q.x(), q.y(), q.z(), q.w()}) + "\n";
  return text;
}

Status WriteCameraYaml(const std::filesystem::path& path, const CameraInfo& info) {
  return WriteFileAtomically(path, FormatCameraYaml(info));
}

Result<CameraInfo> ReadCameraYaml(const std::filesystem::path& path) {
  Result<yaml::Node> root = yaml::Node::LoadFile(path);
  if (!root.ok()) return root.status();
  if (!root->IsMap()) return root->Error("expected a map of camera parameters");
  SEMCHAIN_RETURN_IF_ERROR(root->CheckKeys({"width", "height", "fx", "fy", "cx", "cy", "max_range",
                                            "depth_scale", "frame_rate_hz", "robot_from_camera"}));
  CameraInfo info;
  PinholeCamera& k = info.camera.intrinsics;
  Result<int> width = PositiveInt(*root, "width");
  if (!width.ok()) return width.status();
  Result<int> height = PositiveInt(*root, "height");
  if (!height.ok()) return height.status();
  k.width = *width;
  k.height = *height;
  for (auto [key, field] : {std::pair{"fx", &k.fx}, std::pair{"fy", &k.fy}}) {
    Result<double> value = PositiveNumber(*root, key);
    if (!value.ok()) return value.status();
    *field = *value;
  }
  for (auto [key, field] : {std::pair{"cx", &k.cx}, std::pair{"cy", &k.cy}}) {
    Result<yaml::Node> node = root->Get(key);
    if (!node.ok()) return node.status();
    Result<double> value = node->AsDouble();
    if (!value.ok()) return value.status();
    *field = *value;
  }
  Result<double> max_range = PositiveNumber(*root, "max_range");
  if (!max_range.ok()) return max_range.status();
  info.camera.max_range = *max_range;
  Result<double> depth_scale = PositiveNumber(*root, "depth_scale");
  if (!depth_scale.ok()) return depth_scale.status();
  info.depth_scale = *depth_scale;
  if (root->Has("frame_rate_hz")) {
    Result<double> rate = PositiveNumber(*root, "frame_rate_hz");
    if (!rate.ok()) return rate.status();
    info.frame_rate_hz = *rate;
  }
  Result<yaml::Node> extrinsics = root->Get("robot_from_camera");
  if (!extrinsics.ok()) return extrinsics.status();
  if (!extrinsics->IsMap()) return extrinsics->Error("expected a map");
  Result<Eigen::Isometry3d> pose = ReadExtrinsics(*extrinsics);
  if (!pose.ok()) return pose.status();
  info.camera.robot_from_camera = *pose;
  return info;
}

}  // namespace semchain
