#pragma once

#include <ros/node_handle.h>

#include <string>

#include "core/status.h"
#include "mapping/slam_options.h"
#include "ros/node_inputs.h"
#include "semantic/semantic_options.h"

// The private parameters of semchain_ros in mapping mode. Where slam_gmapping has a parameter
// of the same meaning it has the same name: particles, delta (the map's resolution),
// maxUrange, linearUpdate, angularUpdate, resampleThreshold, srr, srt, str, stt,
// map_update_interval, base_frame, odom_frame, map_frame; an unset one keeps semchain's
// default (config/slam.yaml), or the value of ~slam_config when given.
namespace semchain::ros1 {

struct MappingNodeParameters {
  std::string out;                // ~out: the map folder /semchain/save_map writes (required)
  std::string slam_config;        // ~slam_config: SLAM options YAML (as `slam --config`)
  std::string detector;           // ~detector: ONNX model; empty: the detections topic
  std::string class_map;          // ~class_map: ~detector's classes mapped to semchain's
  double camera_max_range = 6.0;  // ~camera_max_range: depth beyond is no reading
  // ~min_detection_score: detections scoring lower do not enter the semantic map (as
  // `slam --semantic --min-detection-score`).
  double min_detection_score = semantic::DetectionPointOptions().min_score;
  std::string stats_file;            // ~stats_file: CPU and latency JSON at exit
  NodeFrames frames;                 // ~base_frame, ~odom_frame, ~map_frame, ~tf_wait
  double map_update_interval = 5.0;  // s of scan time between two /map publications
  double transform_tolerance = 0.1;  // s: map → odom is future-dated by this much
  bool save_on_shutdown = true;      // ~save_on_shutdown: write ~out when the node stops
  // ~keyframe_images: keep the keyframes' colour images (PNG in memory, ~50 KB each) and save
  // them in ~out, so that the saved map serves semantic-amcl-bow; with /semchain/detections the
  // images come from /camera/color/image_raw when it is published.
  bool keyframe_images = true;
  // ~frame_queue_size: camera frames (colour and depth images each) waiting for the detector, or
  // for the camera, before the oldest are dropped. Deeper keeps every frame of a bag played
  // faster than the detector can take it, at the cost of memory (~0.4 MB a 320×240 RGB-D frame)
  // and, live, of objects appearing later; 100 is 20 s of a 5 Hz camera.
  int frame_queue_size = 100;
  mapping::SlamOptions slam;
};

// Reads and validates the parameters; an error names the parameter.
Result<MappingNodeParameters> ReadMappingNodeParameters(const ::ros::NodeHandle& private_nh);

// The parameters in force, for the node's start-up line ("particles ..., delta ..., ...").
std::string DescribeMappingParameters(const MappingNodeParameters& parameters);

}  // namespace semchain::ros1
