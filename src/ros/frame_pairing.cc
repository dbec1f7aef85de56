#include "ros/frame_pairing.h"

#include <cstdlib>
#include <utility>

namespace semchain::ros1 {

Status FramePairer::AddColor(StampedImage image) {
  color_.push_back(std::move(image));
  return Match();
}

Status FramePairer::AddDepth(StampedImage image) {
  depth_.push_back(std::move(image));
  return Match();
}

Status FramePairer::Match() {
  while (!color_.empty() && !depth_.empty()) {
    const std::int64_t color = color_.front().stamp_ns;
    const std::int64_t depth = depth_.front().stamp_ns;
    if (std::llabs(color - depth) <= max_gap_ns_) {
      StampedImage c = std::move(color_.front());
      StampedImage d = std::move(depth_.front());
      color_.pop_front();
      depth_.pop_front();
      SEMCHAIN_RETURN_IF_ERROR(sink_(std::move(c), std::move(d)));
    } else if (color < depth) {
      color_.pop_front();
      ++unpaired_color_;
    } else {
      depth_.pop_front();
      ++unpaired_depth_;
    }
  }
  return Status::Ok();
}

void FramePairer::Finish() {
  unpaired_color_ += color_.size();
  unpaired_depth_ += depth_.size();
  color_.clear();
  depth_.clear();
}

}  // namespace semchain::ros1
