#pragma once

#include <ros/node_handle.h>

#include <string>

#include "core/status.h"
#include "localization/amcl_options.h"
#include "localization/localizer.h"
#include "ros/node_inputs.h"

// The node's private parameters. Where ROS amcl has a parameter of the same meaning it has the
// same name (min_particles, max_particles, kld_err, kld_z, odom_alpha1..4, laser_model_type,
// laser_max_beams, laser_z_hit, laser_z_short, laser_z_max, laser_z_rand, laser_sigma_hit,
// laser_lambda_short, laser_likelihood_max_dist, laser_min_range, laser_max_range,
// update_min_d, update_min_a, resample_interval, recovery_alpha_slow, recovery_alpha_fast,
// transform_tolerance, base_frame_id, odom_frame_id, global_frame_id, tf_broadcast,
// initial_pose_x/y/a, initial_cov_xx/yy/aa); an unset one keeps semchain's default (nav2's).
namespace semchain::ros1 {

struct LocalizationNodeParameters {
  std::string map;                            // ~map: a semchain map folder
  std::string method = "semantic-scanmatch";  // ~method (DESIGN.md §4)
  std::string detector;                       // ~detector: ONNX model; empty: detections topic
  std::string class_map;                      // ~class_map: YAML map of ~detector's classes
  std::string vocabulary;                     // ~vocabulary: semantic-amcl-bow's vocabulary
  double camera_max_range = 6.0;              // ~camera_max_range: depth beyond is no reading
  std::string stats_file;                     // ~stats_file: CPU and latency JSON at exit
  NodeFrames frames;                 // ~base_frame_id, ~odom_frame_id, ~global_frame_id, ~tf_wait
  double transform_tolerance = 0.1;  // s: map → odom is future-dated by this much (as amcl)
  bool tf_broadcast = true;
  // ~publish_pose_every_scan: /amcl_pose after every scan. False (the default, as amcl): after
  // the filter's updates only (the robot moved update_min_d or turned update_min_a), after
  // /initialpose and when the localizer's state changes.
  bool publish_pose_every_scan = false;
  bool has_initial_pose = false;  // initial_pose_x/y/a given
  double initial_pose[3] = {0.0, 0.0, 0.0};
  double initial_cov[3] = {0.5 * 0.5, 0.5 * 0.5, (M_PI / 12.0) * (M_PI / 12.0)};
  localization::AmclOptions amcl;
  localization::LocalizerOptions localizer;
};

// Reads and validates the parameters; an error names the parameter.
Result<LocalizationNodeParameters> ReadLocalizationNodeParameters(
    const ::ros::NodeHandle& private_nh);

// The parameters in force, for the node's start-up line ("method ..., particles ..., ...").
std::string DescribeLocalizationParameters(const LocalizationNodeParameters& parameters);

}  // namespace semchain::ros1
