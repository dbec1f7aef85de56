#pragma once

#include <filesystem>
#include <string>

#include "core/status.h"
#include "sensors/camera.h"

// camera.yaml, the description of a run's RGB-D camera written by `semchain simulate` and read by
// every stage that uses the frames:
//   width, height, fx, fy, cx, cy      pinhole intrinsics (pixel centres at integer coordinates)
//   max_range                          metres; depth beyond it reads 0
//   depth_scale                        metres per unit of the 16-bit depth PNGs (0.001 = mm)
//   frame_rate_hz                      camera rate
//   robot_from_camera: {translation: [x, y, z], rotation: 3×3 rows, quaternion_xyzw: [...]}
namespace semchain {

struct CameraInfo {
  MountedCamera camera;
  double depth_scale = 0.001;
  double frame_rate_hz = 2.0;
};

std::string FormatCameraYaml(const CameraInfo& info);
Status WriteCameraYaml(const std::filesystem::path& path, const CameraInfo& info);

// Reads camera.yaml; the rotation (a proper rotation matrix within 1e-6) is authoritative and
// the quaternion, when present, must agree with it. Errors name file, line and key.
Result<CameraInfo> ReadCameraYaml(const std::filesystem::path& path);

}  // namespace semchain
