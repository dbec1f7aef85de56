#include "sim/run_directory.h"

#include <signal.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cerrno>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/atomic_file.h"

namespace semchain::sim {
namespace fs = std::filesystem;
namespace {

Status EncodePng(const fs::path& path, const cv::Mat& image) {
  std::vector<unsigned char> bytes;
  // Fixed compression so that the same image always gives the same bytes.
  if (!cv::imencode(".png", image, bytes, {cv::IMWRITE_PNG_COMPRESSION, 3})) {
    return Status::Error(path.string() + ": cannot encode PNG");
  }
  return WriteFileAtomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// Removes what a killed earlier run left beside 'run_dir': its staging directory
// (RUN.partial.PID) or the previous run it was replacing (RUN.old.PID), when no process with
// that PID runs any more. A live process's are its own business.
void RemoveStaleStaging(const fs::path& run_dir) {
  std::error_code error;
  const fs::path parent = run_dir.has_parent_path() ? run_dir.parent_path() : fs::path(".");
  const std::string name = run_dir.filename().string();
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(parent, error)) {
    const std::string file = entry.path().filename().string();
    for (const std::string infix : {".partial.", ".old."}) {
      const std::string prefix = name + infix;
      if (file.size() <= prefix.size() || file.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string pid_text = file.substr(prefix.size());
      if (pid_text.find_first_not_of("0123456789") != std::string::npos || pid_text.size() > 9) {
        continue;
      }
      const auto pid = static_cast<pid_t>(std::stol(pid_text));
      if (pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH) stale.push_back(entry.path());
    }
  }
  for (const fs::path& path : stale) fs::remove_all(path, error);
}

}  // namespace

Result<fs::path> BeginRunDirectory(const fs::path& run_dir, const std::string& marker) {
  std::error_code error;
  const fs::file_status status = fs::status(run_dir, error);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) {
      return Status::Error(run_dir.string() + ": exists and is not a directory");
    }
    if (!fs::is_empty(run_dir, error) && !fs::exists(run_dir / marker)) {
      return Status::Error(run_dir.string() +
                           ": directory is not empty and holds no earlier output (" + marker +
                           "); choose another output directory");
    }
  }
  fs::path parent = run_dir.has_parent_path() ? run_dir.parent_path() : fs::path(".");
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(parent));
  RemoveStaleStaging(run_dir);
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
