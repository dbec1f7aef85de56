#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/status.h"
#include "ros/bag_import_options.h"

// `semchain bag import FILE.bag --out RUN`: a robot's bag (or one `bag export` wrote) as a run
// directory that `semchain slam --log RUN/log.clf`, `semchain semantic --run RUN` and
// `semchain localize --run RUN` read:
//   log.clf           scans with odometry from tf (scan_import.h)
//   truth.txt         the bag's /semchain/truth, when it has one
//   camera.yaml       from camera_info, tf and the run info (camera_import.h)
//   frames/           colour and depth images paired by stamp
//   detections.jsonl  the detections topic, one record per frame (detections_import.h)
//   world.yaml        from the run info, when `bag export` had one
//   run.yaml          what the import did
// The directory is assembled beside RUN and moved into place at the end (as `semchain
// simulate` does), so a failed import leaves the earlier RUN, or nothing.
namespace semchain::ros1 {

struct BagImportSummary {
  std::size_t scans = 0;
  std::size_t skipped_scans = 0;
  std::size_t non_finite_ranges = 0;  // stored as max_range
  std::size_t frames = 0;
  std::size_t detection_records = 0;
  std::size_t truth_poses = 0;
  std::string odometry;  // where the odometry came from: "tf odom -> base_link" or "/odom"
  std::int64_t stamp_offset_seconds = 0;
  std::vector<std::string> warnings;  // one line each: what was left out and why
};

Result<BagImportSummary> ImportBagToRun(const std::filesystem::path& bag_path,
                                        const std::filesystem::path& run_dir,
                                        const BagImportOptions& options = {});

}  // namespace semchain::ros1
