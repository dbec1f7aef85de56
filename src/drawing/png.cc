#include "drawing/png.h"

#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <string_view>
#include <vector>

#include "core/atomic_file.h"

namespace semchain::drawing {

Status WritePng(const cv::Mat& bgr, const std::filesystem::path& path) {
  std::vector<std::uint8_t> bytes;
  if (!cv::imencode(".png", bgr, bytes)) {
    return Status::Error(path.string() + ": could not encode the image as PNG");
  }
  return WriteFileAtomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace semchain::drawing
