#include "bow/run_features.h"

#include <algorithm>
#include <string>
#include <system_error>

#include "io/rgbd_frame_io.h"

namespace semchain::bow {

namespace fs = std::filesystem;

Result<std::vector<fs::path>> ListColorFrames(const fs::path& run_dir) {
  const fs::path frames = run_dir / "frames";
  std::error_code error;
  if (!fs::is_directory(frames, error)) {
    return Status::Error(frames.string() + ": no frames directory (a run without frames?)");
  }
  std::vector<fs::path> images;
  for (const fs::directory_entry& entry : fs::directory_iterator(frames, error)) {
    const std::string name = entry.path().filename().string();
    const bool png = entry.path().extension() == ".png";
    const bool depth = name.size() >= 10 && name.ends_with("_depth.png");
    if (entry.is_regular_file() && png && !depth) images.push_back(entry.path());
  }
  if (error) return Status::Error(frames.string() + ": " + error.message());
  if (images.empty()) return Status::Error(frames.string() + ": no colour frames (*.png)");
  std::sort(images.begin(), images.end());
  return images;
}

Result<std::vector<cv::Mat>> ExtractImageDescriptors(
    const std::vector<fs::path>& images, const OrbOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  std::vector<cv::Mat> descriptors;
  descriptors.reserve(images.size());
  for (std::size_t i = 0; i < images.size(); ++i) {
    Result<cv::Mat> image = ReadColorImage(images[i]);
    if (!image.ok()) return image.status();
    descriptors.push_back(ExtractOrbDescriptors(*image, options));
    if (progress) progress(i + 1, images.size());
  }
  return descriptors;
}

}  // namespace semchain::bow
