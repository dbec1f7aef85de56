#include "ros/mapping_parameters.h"

#include <cstdio>

#include "mapping/slam_options_io.h"
#include "ros/parameter_reader.h"

namespace semchain::ros1 {
namespace {

// A double parameter that must satisfy 'valid' ("must be ..." names the condition).
Status ReadChecked(const ::ros::NodeHandle& nh, const std::string& name, double* value,
                   bool valid(double), const std::string& condition) {
  SEMCHAIN_RETURN_IF_ERROR(ReadDoubleParameter(nh, name, value));
  if (!valid(*value)) return Status::Error("parameter ~" + name + ": must be " + condition);
  return Status::Ok();
}

bool Positive(double v) { return v > 0.0; }
bool NonNegative(double v) { return v >= 0.0; }
bool UnitInterval(double v) { return v >= 0.0 && v <= 1.0; }
bool Fraction(double v) { return v > 0.0 && v <= 1.0; }

// slam_gmapping's names for what semchain's SLAM has too.
Status ReadGmappingNames(const ::ros::NodeHandle& nh, mapping::SlamOptions* slam) {
  mapping::RbpfOptions& rbpf = slam->rbpf;
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "particles", &rbpf.particles));
  if (rbpf.particles < 1) return Status::Error("parameter ~particles: must be >= 1");
  int seed = static_cast<int>(rbpf.seed);
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "seed", &seed));
  if (seed < 0) return Status::Error("parameter ~seed: must be >= 0");
  rbpf.seed = static_cast<std::uint64_t>(seed);
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "threads", &rbpf.threads));
  if (rbpf.threads < 0) return Status::Error("parameter ~threads: must be >= 0");
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "delta", &rbpf.grid.resolution_meters, Positive, "> 0 (metres per cell)"));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "maxUrange", &rbpf.scan.max_range_meters, Positive, "> 0 (metres)"));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "linearUpdate", &rbpf.linear_update_meters, NonNegative, ">= 0 (metres)"));
  SEMCHAIN_RETURN_IF_ERROR(ReadChecked(nh, "angularUpdate", &rbpf.angular_update_radians,
                                       NonNegative, ">= 0 (radians)"));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "resampleThreshold", &rbpf.resample_threshold, Fraction, "in (0, 1]"));
  // GMapping's odometry model as its code uses it (openslam_gmapping motionmodel.cpp: the
  // translation noise is srr·|Δx| + str·|Δθ|, the heading noise stt·|Δθ| + srt·distance), so that
  // the same values give the same noise as slam_gmapping. The ROS wiki describes srt and str the
  // other way round.
  mapping::MotionModelOptions& motion = rbpf.motion;
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "srr", &motion.translation_per_meter, NonNegative, ">= 0"));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "str", &motion.translation_per_radian, NonNegative, ">= 0"));
  SEMCHAIN_RETURN_IF_ERROR(ReadChecked(nh, "srt", &motion.rotation_per_meter, NonNegative, ">= 0"));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "stt", &motion.rotation_per_radian, NonNegative, ">= 0"));
  return Status::Ok();
}

}  // namespace

Result<MappingNodeParameters> ReadMappingNodeParameters(const ::ros::NodeHandle& nh) {
  MappingNodeParameters p;
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "out", &p.out));
  if (p.out.empty()) {
    return Status::Error("parameter ~out: required (the map folder /semchain/save_map writes)");
  }
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "slam_config", &p.slam_config));
  if (!p.slam_config.empty()) {
    const Status loaded = mapping::LoadSlamOptions(p.slam_config, &p.slam);
    if (!loaded.ok()) return Status::Error("parameter ~slam_config: " + loaded.message());
  }
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "detector", &p.detector));
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "class_map", &p.class_map));
  if (!p.class_map.empty() && p.detector.empty()) {
    return Status::Error("parameter ~class_map: needs ~detector (it maps the model's classes)");
  }
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "camera_max_range", &p.camera_max_range, Positive, "> 0 (metres)"));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "min_detection_score", &p.min_detection_score, UnitInterval, "in [0, 1]"));
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "stats_file", &p.stats_file));
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "save_on_shutdown", &p.save_on_shutdown));
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "keyframe_images", &p.keyframe_images));
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "frame_queue_size", &p.frame_queue_size));
  if (p.frame_queue_size < 1) return Status::Error("parameter ~frame_queue_size: must be >= 1");
  // slam_gmapping's frame names.
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "base_frame", &p.frames.base_frame_id));
  SEMCHAIN_RETURN_IF_ERROR(ReadParameter(nh, "odom_frame", &p.frames.odom_frame_id));
  SEMCHAIN_RETURN_IF_ERROR(ReadNodeFrames(nh, &p.frames, "map_frame"));
  SEMCHAIN_RETURN_IF_ERROR(
      ReadChecked(nh, "map_update_interval", &p.map_update_interval, Positive, "> 0 (seconds)"));
  SEMCHAIN_RETURN_IF_ERROR(ReadChecked(nh, "transform_tolerance", &p.transform_tolerance,
                                       NonNegative, ">= 0 (seconds)"));
  SEMCHAIN_RETURN_IF_ERROR(ReadGmappingNames(nh, &p.slam));
  std::string error;
  if (!p.slam.Validate(&error)) return Status::Error("SLAM parameters: " + error);
  return p;
}

std::string DescribeMappingParameters(const MappingNodeParameters& p) {
  const mapping::RbpfOptions& rbpf = p.slam.rbpf;
  char line[512];
  std::snprintf(
      line, sizeof(line),
      "slam_config %s, particles %d, delta %.3g m, maxUrange %.3g m, linearUpdate %.3g m, "
      "angularUpdate %.3g rad, resampleThreshold %.3g, map_update_interval %.3g s, "
      "frames %s/%s/%s, keyframe_images %s, frame_queue_size %d, min_detection_score %.3g, "
      "save_on_shutdown %s, "
      "seed %llu, threads %d",
      p.slam_config.empty() ? "(defaults)" : p.slam_config.c_str(), rbpf.particles,
      rbpf.grid.resolution_meters, rbpf.scan.max_range_meters, rbpf.linear_update_meters,
      rbpf.angular_update_radians, rbpf.resample_threshold, p.map_update_interval,
      p.frames.global_frame_id.c_str(), p.frames.odom_frame_id.c_str(),
      p.frames.base_frame_id.c_str(), p.keyframe_images ? "true" : "false", p.frame_queue_size,
      p.min_detection_score, p.save_on_shutdown ? "true" : "false",
      static_cast<unsigned long long>(rbpf.seed), rbpf.threads);
  return line;
}

}  // namespace semchain::ros1
