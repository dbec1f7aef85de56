#pragma once

#include <string>

#include "mapping/laser_odometry.h"
#include "mapping/rbpf_slam.h"
#include "mapping/scan_localizer.h"

// The options of `semchain slam`'s computation (RunSlam, IncrementalSlam).
namespace semchain::mapping {

struct SlamOptions {
  LaserOdometryOptions laser_odometry;
  RbpfOptions rbpf;
  EveryScanOptions every_scan;

  bool Validate(std::string* error) const;
};

}  // namespace semchain::mapping
