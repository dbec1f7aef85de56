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
  // with the loop closures found among them before the final passes. On by default: with
  // closure covariances from the match it is no worse than the filter alone on the building
  // logs and worlds and closes the campus logs' loops, which the filter alone cannot
  // (docs/results.md, "The pose graph by default").
  bool pose_graph = true;
  LoopClosureOptions loop_closure;

  bool Validate(std::string* error) const;
};

}  // namespace semchain::mapping
