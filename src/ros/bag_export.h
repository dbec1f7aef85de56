#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "core/status.h"
#include "ros/bag_layout.h"
#include "ros/bag_writer.h"

// `semchain bag export RUN --out FILE.bag`: a run directory as a ROS bag with the topics of
// bag_layout.h, for `rosbag play` into a ROS system (the semchain_ros node, rviz, amcl,
// slam_gmapping). Per scan: /scan, /tf (odom → base_link) and /odom at the scan's stamp; per
// truth pose: /semchain/truth; per camera frame: the colour and depth images, camera_info and
// its detections.jsonl record. /tf_static and /semchain/run_info once, latched, at the start.
// RUN may also be a CARMEN log itself (a raw data set's .clf or .clf.gz): its scans and odometry
// alone, as a run directory holding only log.clf gives them.
// The scans keep the log's order: a scan stamped at or before the scan before it (the Intel
// log's clock steps back by up to 0.9 s 631 times) is stamped 1 ms after that one, so that a
// player, and tf, see the odometry in the order the robot drove.
namespace semchain::ros1 {

struct BagExportOptions {
  // false: no colour or depth images (camera_info and detections still go), for small bags.
  bool images = true;
  BagCompression compression = BagCompression::kNone;
  bool show_progress = true;  // a progress bar on stderr when it is a terminal
  BagTopics topics;
  BagFrames frames;
};

struct BagExportSummary {
  std::size_t scans = 0;
  std::size_t frames = 0;  // camera frames (with or without images)
  std::size_t images = 0;  // colour and depth images written
  std::size_t messages = 0;
  std::int64_t stamp_offset_seconds = 0;  // added to the run's stamps (bag_time.h)
  std::size_t restamped_scans = 0;        // stamped after the scan before them (see above)
};

// Writes the run in 'run_dir' (a run directory or a CARMEN log) to the bag 'bag_path' (replaced
// atomically when it exists).
Result<BagExportSummary> ExportRunToBag(const std::filesystem::path& run_dir,
                                        const std::filesystem::path& bag_path,
                                        const BagExportOptions& options = {});

}  // namespace semchain::ros1
