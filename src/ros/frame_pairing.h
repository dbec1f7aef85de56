#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <opencv2/core.hpp>

#include "core/status.h"

// Pairs colour and depth images into RGB-D frames as they stream out of a bag. A depth image
// aligned to colour has the colour image's stamp (or one within 'max_gap_ns'); each stream's
// stamps rise, so an image older than the other stream's oldest beyond the gap can never be
// paired and is dropped. At most a few images wait at any time.
namespace semchain::ros1 {

struct StampedImage {
  std::int64_t stamp_ns = 0;
  cv::Mat image;
};

class FramePairer {
 public:
  // Called with each pair, colour first; its stamp is the colour image's. An error stops the
  // pairing and is returned by the Add call that made the pair.
  using Sink = std::function<Status(StampedImage color, StampedImage depth)>;

  FramePairer(std::int64_t max_gap_ns, Sink sink)
      : max_gap_ns_(max_gap_ns), sink_(std::move(sink)) {}

  Status AddColor(StampedImage image);
  Status AddDepth(StampedImage image);
  // Drops what is still waiting (no partner came); call after the last image.
  void Finish();

  std::size_t unpaired_color() const { return unpaired_color_; }
  std::size_t unpaired_depth() const { return unpaired_depth_; }

 private:
  Status Match();

  std::int64_t max_gap_ns_;
  Sink sink_;
  std::deque<StampedImage> color_;
  std::deque<StampedImage> depth_;
  std::size_t unpaired_color_ = 0;
  std::size_t unpaired_depth_ = 0;
};

}  // namespace semchain::ros1
