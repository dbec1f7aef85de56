#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "ros/bag_import_options.h"
#include "ros/bag_reader.h"
#include "ros/bag_transforms.h"

// The scans of a bag as a CARMEN log like the simulator's: a header (comments, the PARAM lines
// GMapping's reader wants), then per scan an ODOM line (odometry from tf at the scan's stamp), a
// TRUEPOS line when the bag has a truth pose at that stamp, and a ROBOTLASER1 line (the scan, its
// geometry, and the laser's pose from tf).
namespace semchain::ros1 {

struct ImportedLog {
  carmen::Log log;
  std::size_t scans = 0;
  std::size_t skipped_scans = 0;  // outside the odometry's time span
  std::size_t non_finite_ranges = 0;
  double first_stamp = 0.0;
  double last_stamp = 0.0;
};

// Truth poses by stamp (ns on the bag's clock), for TRUEPOS lines.
using TruthByStamp = std::map<std::int64_t, Pose2>;

// Reads the scans of 'context.options.topics.scan'. Odometry and the laser's mounting come from
// 'transforms' (checked to connect odom, base and laser frames first: an error names the frames
// tf knows). A scan whose odometry tf2 cannot give (before the first or after the last odometry)
// is skipped and counted; no scan left or a tilted laser are errors. Each scan keeps its own
// beam geometry (an interlaced laser's start angle and beam count change from scan to scan).
Result<ImportedLog> ImportScans(BagReader& reader, const BagTransforms& transforms,
                                const TruthByStamp& truth, ImportContext& context);

}  // namespace semchain::ros1
