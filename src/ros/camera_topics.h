#pragma once

#include <string>

#include "core/status.h"
#include "ros/bag_layout.h"
#include "ros/bag_reader.h"

// Which topics of a bag hold its camera, for `bag import`. Robots record cameras under various
// names and often compressed (image_transport's /compressed and /compressedDepth topics), so
// a topic not named by an option is looked for in the camera's namespace NS:
//   colour  NS/color/image_raw, NS/rgb/image_raw, NS/image_raw
//   depth   NS/depth/image_raw, NS/aligned_depth_to_color/image_raw, NS/depth_registered/image_raw
// each as it is or with /compressed (colour) or /compressedDepth (depth) after it, the first the
// bag has; a topic named by an option is taken as it is, or with that suffix when only that is
// in the bag. camera_info is the colour image's (the sibling of its image_raw) unless named.
// The message type (sensor_msgs/Image or sensor_msgs/CompressedImage) decides how an image is
// read.
namespace semchain::ros1 {

struct CameraTopics {
  std::string color;  // empty: the bag has no colour images
  bool color_compressed = false;
  std::string depth;  // empty: the bag has no depth images
  bool depth_compressed = false;
  std::string camera_info;
};

// The camera topics of 'reader' for 'topics'. A topic an option names that the bag lacks, or an
// image topic of another type, is an error naming it.
Result<CameraTopics> ResolveCameraTopics(const BagReader& reader, const BagTopics& topics);

}  // namespace semchain::ros1
