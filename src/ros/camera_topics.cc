#include "ros/camera_topics.h"

#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>

#include <vector>

namespace semchain::ros1 {
namespace {

constexpr const char* kCompressed = "/compressed";
constexpr const char* kCompressedDepth = "/compressedDepth";

// 'topic' when the bag has it, else 'topic' + 'suffix' when it has that; empty when neither.
std::string PresentAs(const BagReader& reader, const std::string& topic, const char* suffix) {
  if (reader.Has(topic)) return topic;
  if (reader.Has(topic + suffix)) return topic + suffix;
  return "";
}

// The topic 'named' by an option, or the first of 'names' in 'ns' that the bag has.
Result<std::string> Find(const BagReader& reader, const std::string& named, const std::string& ns,
                         const std::vector<const char*>& names, const char* suffix,
                         const char* what) {
  if (!named.empty()) {
    std::string found = PresentAs(reader, named, suffix);
    if (found.empty()) {
      return Status::Error(reader.path().string() + ": no " + what + " topic " + named + " (nor " +
                           named + suffix + "); the bag has " + reader.DescribeTopics());
    }
    return found;
  }
  for (const char* name : names) {
    std::string found = PresentAs(reader, ns + "/" + name, suffix);
    if (!found.empty()) return found;
  }
  return std::string();
}

// Whether 'topic' carries sensor_msgs/CompressedImage (else sensor_msgs/Image).
Result<bool> IsCompressed(const BagReader& reader, const std::string& topic) {
  if (reader.Carries<sensor_msgs::CompressedImage>(topic)) return true;
  if (reader.Carries<sensor_msgs::Image>(topic)) return false;
  return Status::Error(reader.path().string() + ": topic " + topic + " carries " +
                       reader.TypeOf(topic) +
                       ", expected sensor_msgs/Image or sensor_msgs/CompressedImage");
}

// The camera_info beside an image topic: /cam/color/image_raw[/compressed] ->
// /cam/color/camera_info.
std::string SiblingCameraInfo(std::string image_topic) {
  for (const std::string suffix : {kCompressed, kCompressedDepth}) {
    if (image_topic.ends_with(suffix)) image_topic.resize(image_topic.size() - suffix.size());
  }
  const std::size_t slash = image_topic.rfind('/');
  return (slash == std::string::npos ? std::string() : image_topic.substr(0, slash)) +
         "/camera_info";
}

}  // namespace

Result<CameraTopics> ResolveCameraTopics(const BagReader& reader, const BagTopics& topics) {
  CameraTopics camera;
  Result<std::string> color =
      Find(reader, topics.color_image, topics.camera,
           {"color/image_raw", "rgb/image_raw", "image_raw"}, kCompressed, "colour image");
  if (!color.ok()) return color.status();
  Result<std::string> depth =
      Find(reader, topics.depth_image, topics.camera,
           {"depth/image_raw", "aligned_depth_to_color/image_raw", "depth_registered/image_raw"},
           kCompressedDepth, "depth image");
  if (!depth.ok()) return depth.status();
  camera.color = *color;
  camera.depth = *depth;
  if (!camera.color.empty()) {
    Result<bool> compressed = IsCompressed(reader, camera.color);
    if (!compressed.ok()) return compressed.status();
    camera.color_compressed = *compressed;
  }
  if (!camera.depth.empty()) {
    Result<bool> compressed = IsCompressed(reader, camera.depth);
    if (!compressed.ok()) return compressed.status();
    camera.depth_compressed = *compressed;
  }
  camera.camera_info = !topics.camera_info.empty() ? topics.camera_info
                       : !camera.color.empty()     ? SiblingCameraInfo(camera.color)
                                                   : topics.CameraInfo();
  return camera;
}

}  // namespace semchain::ros1
