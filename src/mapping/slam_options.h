#pragma once

#include <string>

#include "mapping/laser_odometry.h"
#include "mapping/loop_closure.h"
#include "mapping/rbpf_slam.h"
#include "mapping/scan_localizer.h"

// The options of `semchain slam`'s computation (RunSlam, IncrementalSlam).
namespace semchain::mapping {

struct SlamOptions {
  LaserOdometryOptions laser_odometry;
  RbpfOptions rbpf;
  EveryScanOptions every_scan;
  // The pose graph behind the filter (loop_closure.h): the best particle's nodes optimized
  // with the loop closures found among them before the final passes. Off by default until it
  // is shown not to cost the building-sized logs anything (docs/results.md, campus logs).
  bool pose_graph = false;
  LoopClosureOptions loop_closure;

  bool Validate(std::string* error) const;
};

}  // namespace semchain::mapping
