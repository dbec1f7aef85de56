#include "sim/run_directory.h"

#include <unistd.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/atomic_file.h"

namespace semchain::sim {
namespace fs = std::filesystem;
namespace {

constexpr char kRunMarker[] = "run.yaml";

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

Status EncodePng(const fs::path& path, const cv::Mat& image) {
  std::vector<unsigned char> bytes;
  // Fixed compression so that the same image always gives the same bytes.
  if (!cv::imencode(".png", image, bytes, {cv::IMWRITE_PNG_COMPRESSION, 3})) {
    return Status::Error(path.string() + ": cannot encode PNG");
  }
  return WriteFileAtomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace

Result<fs::path> BeginRunDirectory(const fs::path& run_dir) {
  std::error_code error;
  const fs::file_status status = fs::status(run_dir, error);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) {
      return Status::Error(run_dir.string() + ": exists and is not a directory");
    }
    if (!fs::is_empty(run_dir, error) && !fs::exists(run_dir / kRunMarker)) {
      return Status::Error(run_dir.string() +
                           ": directory is not empty and holds no earlier run (run.yaml); "
                           "choose another output directory");
    }
  }
  fs::path parent = run_dir.has_parent_path() ? run_dir.parent_path() : fs::path(".");
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(parent));
  fs::path staging = run_dir;
  staging += ".partial." + std::to_string(::getpid());
  fs::remove_all(staging, error);
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(staging));
  return staging;
}

Status FinishRunDirectory(const fs::path& staging, const fs::path& run_dir) {
  std::error_code error;
  fs::path old = run_dir;
  old += ".old." + std::to_string(::getpid());
  const bool replace = fs::exists(run_dir, error);
  if (replace) {
    fs::rename(run_dir, old, error);
    if (error) return Status::Error(run_dir.string() + ": cannot replace: " + error.message());
  }
  fs::rename(staging, run_dir, error);
  if (error) {
    if (replace) fs::rename(old, run_dir, error);  // put the earlier run back
    return Status::Error(run_dir.string() + ": cannot move the run into place: " + error.message());
  }
  if (replace) fs::remove_all(old, error);
  return Status::Ok();
}

void AbandonRunDirectory(const fs::path& staging) {
  std::error_code ignored;
  fs::remove_all(staging, ignored);
}

std::string FormatCameraYaml(const MountedCamera& camera, double frame_rate_hz) {
  const PinholeCamera& k = camera.intrinsics;
  const Eigen::Matrix3d r = camera.robot_from_camera.rotation();
  const Eigen::Vector3d t = camera.robot_from_camera.translation();
  const Eigen::Quaterniond q(r);
  std::string text =
      "# The simulated RGB-D camera (semchain simulate). Pinhole model without distortion;\n"
      "# pixel centres at integer coordinates. The optical frame has z forward, x right, y down;\n"
      "# the robot frame x forward, y left, z up (z = 0 on the floor). Depth PNGs hold\n"
      "# millimetres along the optical axis (depth_scale metres per unit); 0 = no measurement.\n";
  text += "width: " + std::to_string(k.width) + "\n";
  text += "height: " + std::to_string(k.height) + "\n";
  text += "fx: " + Number(k.fx) + "\nfy: " + Number(k.fy) + "\n";
  text += "cx: " + Number(k.cx) + "\ncy: " + Number(k.cy) + "\n";
  text += "max_range: " + Number(camera.max_range) + "\n";
  text += "depth_scale: 0.001\n";
  text += "frame_rate_hz: " + Number(frame_rate_hz) + "\n";
  text += "robot_from_camera:\n";
  text += "  translation: " + List({t.x(), t.y(), t.z()}) + "\n";
  text += "  rotation: [" + List({r(0, 0), r(0, 1), r(0, 2)}) + ", " +
          List({r(1, 0), r(1, 1), r(1, 2)}) + ", " + List({r(2, 0), r(2, 1), r(2, 2)}) + "]\n";
  text += "  quaternion_xyzw: " + List({q.x(), q.y(), q.z(), q.w()}) + "\n";
  return text;
}

std::string FrameName(int index) {
  char text[32];
  std::snprintf(text, sizeof(text), "frames/%06d", index);
  return text;
}

Status WriteFrame(const fs::path& frames_dir, int index, const RgbdImage& image) {
  char stem[16];
  std::snprintf(stem, sizeof(stem), "%06d", index);
  cv::Mat bgr;
  cv::cvtColor(image.rgb, bgr, cv::COLOR_RGB2BGR);  // OpenCV writes BGR
  SEMCHAIN_RETURN_IF_ERROR(EncodePng(frames_dir / (std::string(stem) + ".png"), bgr));
  return EncodePng(frames_dir / (std::string(stem) + "_depth.png"), image.depth);
}

}  // namespace semchain::sim
