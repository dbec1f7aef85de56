#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/camera_io.h"
#include "ros/bag_import_options.h"
#include "ros/bag_reader.h"
#include "ros/bag_transforms.h"
#include "ros/camera_topics.h"

// The RGB-D camera of a bag as a run's frames/ and camera.yaml: colour and depth images paired
// by stamp (frame_pairing.h) and written as the simulator writes them (frames/NNNNNN.png RGB,
// NNNNNN_depth.png 16-bit), the intrinsics from camera_info, the mounting from tf (base frame →
// the camera_info's frame), or both from the camera.yaml of --camera-yaml. Images may be raw
// (sensor_msgs/Image) or compressed (sensor_msgs/CompressedImage: ros_compressed_image.h); a
// camera without depth gives frames whose depth images hold no reading.
namespace semchain::ros1 {

struct ImportedFrame {
  std::string name;           // "frames/000123"
  std::int64_t stamp_ns = 0;  // on the bag's clock
  double stamp = 0.0;         // run time
};

struct ImportedCamera {
  std::vector<ImportedFrame> frames;  // in stamp order
  std::optional<CameraInfo> camera;   // when the bag has camera_info
};

// Reads the camera 'topics' and writes the frames under 'run_dir'/frames. A bag without images
// or camera_info has no camera (not an error); images without a calibration (no camera_info,
// or an uncalibrated one, and no --camera-yaml), images of another size than the
// calibration's, an encoding semchain does not read, or no tf pose of the camera are errors.
Result<ImportedCamera> ImportCamera(BagReader& reader, const BagTransforms& transforms,
                                    const CameraTopics& topics,
                                    const std::filesystem::path& run_dir, ImportContext& context);

}  // namespace semchain::ros1
