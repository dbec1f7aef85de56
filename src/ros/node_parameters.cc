#include "ros/node_parameters.h"

#include <cmath>
#include <cstdio>

#include "ros/parameter_reader.h"

namespace semchain::ros1 {
namespace {

template <typename T>
Status Read(const ::ros::NodeHandle& nh, const std::string& name, T* value) {
  return ReadParameter(nh, name, value);
}

Status ReadInt(const ::ros::NodeHandle& nh, const std::string& name, int* value) {
  return ReadParameter(nh, name, value);
}

Status ReadDouble(const ::ros::NodeHandle& nh, const std::string& name, double* value) {
  return ReadDoubleParameter(nh, name, value);
}

}  // namespace

Result<LocalizationNodeParameters> ReadLocalizationNodeParameters(const ::ros::NodeHandle& nh) {
  LocalizationNodeParameters p;
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "map", &p.map));
  if (p.map.empty()) {
    return Status::Error("parameter ~map: required (a map folder with map.yaml and semantic.json)");
  }
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "method", &p.method));
  if (!localization::ParseLocalizationMethod(p.method)) {
    return Status::Error("parameter ~method: unknown method '" + p.method + "' (" +
                         localization::LocalizationMethodList() + ")");
  }
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "detector", &p.detector));
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "class_map", &p.class_map));
  if (!p.class_map.empty() && p.detector.empty()) {
    return Status::Error("parameter ~class_map: needs ~detector (it maps the model's classes)");
  }
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "vocabulary", &p.vocabulary));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "camera_max_range", &p.camera_max_range));
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "stats_file", &p.stats_file));
  SEMCHAIN_RETURN_IF_ERROR(ReadNodeFrames(nh, &p.frames));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "transform_tolerance", &p.transform_tolerance));
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "tf_broadcast", &p.tf_broadcast));
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "publish_pose_every_scan", &p.publish_pose_every_scan));

  const char* const kPoseNames[3] = {"initial_pose_x", "initial_pose_y", "initial_pose_a"};
  const char* const kCovNames[3] = {"initial_cov_xx", "initial_cov_yy", "initial_cov_aa"};
  for (int i = 0; i < 3; ++i) {
    p.has_initial_pose = p.has_initial_pose || nh.hasParam(kPoseNames[i]);
    SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, kPoseNames[i], &p.initial_pose[i]));
    SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, kCovNames[i], &p.initial_cov[i]));
  }

  localization::AmclOptions& a = p.amcl;
  SEMCHAIN_RETURN_IF_ERROR(ReadInt(nh, "min_particles", &a.min_particles));
  SEMCHAIN_RETURN_IF_ERROR(ReadInt(nh, "max_particles", &a.max_particles));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "kld_err", &a.pf_err));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "kld_z", &a.pf_z));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "odom_alpha1", &a.alpha1));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "odom_alpha2", &a.alpha2));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "odom_alpha3", &a.alpha3));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "odom_alpha4", &a.alpha4));
  std::string odom_model = "diff";
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "odom_model_type", &odom_model));
  if (odom_model != "diff" && odom_model != "diff-corrected") {
    return Status::Error("parameter ~odom_model_type: '" + odom_model +
                         "' (only the differential drive model: diff, diff-corrected)");
  }
  std::string laser_model = "likelihood_field";
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "laser_model_type", &laser_model));
  if (laser_model == "likelihood_field") {
    a.laser_model_type = localization::LaserModelType::kLikelihoodField;
  } else if (laser_model == "beam") {
    a.laser_model_type = localization::LaserModelType::kBeam;
  } else {
    return Status::Error("parameter ~laser_model_type: '" + laser_model +
                         "' (likelihood_field or beam)");
  }
  SEMCHAIN_RETURN_IF_ERROR(ReadInt(nh, "laser_max_beams", &a.max_beams));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "laser_z_hit", &a.z_hit));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "laser_z_short", &a.z_short));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "laser_z_max", &a.z_max));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "laser_z_rand", &a.z_rand));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "laser_sigma_hit", &a.sigma_hit));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "laser_lambda_short", &a.lambda_short));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadDouble(nh, "laser_likelihood_max_dist", &a.laser_likelihood_max_dist));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "laser_min_range", &a.laser_min_range));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "laser_max_range", &a.laser_max_range));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "update_min_d", &a.update_min_d));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "update_min_a", &a.update_min_a));
  SEMCHAIN_RETURN_IF_ERROR(ReadInt(nh, "resample_interval", &a.resample_interval));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "recovery_alpha_slow", &a.recovery_alpha_slow));
  SEMCHAIN_RETURN_IF_ERROR(ReadDouble(nh, "recovery_alpha_fast", &a.recovery_alpha_fast));
  std::string error;
  if (!a.Validate(&error)) return Status::Error("AMCL parameters: " + error);

  int seed = 1;
  SEMCHAIN_RETURN_IF_ERROR(ReadInt(nh, "seed", &seed));
  p.localizer.seed = static_cast<std::uint64_t>(seed);
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "observation_memory", &p.localizer.observation_memory));
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "single_object", &p.localizer.single_object));
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "recheck_lock", &p.localizer.recheck_lock));
  SEMCHAIN_RETURN_IF_ERROR(Read(nh, "scan_tracking", &p.localizer.scan_tracking.enabled));
  SEMCHAIN_RETURN_IF_ERROR(
      Read(nh, "recheck_on_new_evidence_only", &p.localizer.recheck_on_new_evidence_only));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadDouble(nh, "decision_min_laser_score", &p.localizer.decision_min_laser_score));
  if (!(p.localizer.decision_min_laser_score >= 0.0 &&
        p.localizer.decision_min_laser_score <= 1.0)) {
    return Status::Error("parameter ~decision_min_laser_score must be in [0, 1]");
  }
  if (!(p.transform_tolerance >= 0.0) || !(p.camera_max_range > 0.0)) {
    return Status::Error("parameters ~transform_tolerance must be >= 0, ~camera_max_range > 0");
  }
  return p;
}

std::string DescribeLocalizationParameters(const LocalizationNodeParameters& p) {
  const localization::AmclOptions& a = p.amcl;
  char line[512];
  std::snprintf(
      line, sizeof(line),
      "particles %d-%d, laser %s %d beams, update_min_d %.3g m, update_min_a %.3g rad, "
      "resample_interval %d, odom_alpha1-4 %.3g %.3g %.3g %.3g, frames %s/%s/%s, "
      "transform_tolerance %.3g s, /amcl_pose %s, scan tracking %s, seed %llu",
      a.min_particles, a.max_particles,
      a.laser_model_type == localization::LaserModelType::kBeam ? "beam" : "likelihood_field",
      a.max_beams, a.update_min_d, a.update_min_a, a.resample_interval, a.alpha1, a.alpha2,
      a.alpha3, a.alpha4, p.frames.global_frame_id.c_str(), p.frames.odom_frame_id.c_str(),
      p.frames.base_frame_id.c_str(), p.transform_tolerance,
      p.publish_pose_every_scan ? "after every scan" : "on filter updates",
      p.localizer.scan_tracking.enabled ? "on" : "off",
      static_cast<unsigned long long>(p.localizer.seed));
  return line;
}

}  // namespace semchain::ros1
