#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "bow/orb_features.h"
#include "core/status.h"

// The training images of a vocabulary: a run's colour frames (RUN/frames/*.png, the depth
// frames *_depth.png left out) and their ORB descriptors.
namespace semchain::bow {

// The colour frames of 'run_dir', sorted by name; an error when there is no frames/ folder
// or no colour frame in it.
Result<std::vector<std::filesystem::path>> ListColorFrames(const std::filesystem::path& run_dir);

// The ORB descriptors of each image in 'images' (one Mat per image, in order). An unreadable
// image is an error naming it. 'progress' (may be empty) gets (done, total) images.
Result<std::vector<cv::Mat>> ExtractImageDescriptors(
    const std::vector<std::filesystem::path>& images, const OrbOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace semchain::bow
