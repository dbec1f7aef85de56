#pragma once

#include <vector>

#include "core/status.h"
#include "io/trajectory_io.h"
#include "ros/bag_import_options.h"
#include "ros/bag_reader.h"
#include "ros/scan_import.h"

// The bag's truth poses (geometry_msgs/PoseStamped on /semchain/truth, as `bag export` writes
// the simulator's truth.txt), for RUN/truth.txt and the log's TRUEPOS lines.
namespace semchain::ros1 {

struct ImportedTruth {
  std::vector<StampedPose> poses;  // run time, in bag order
  TruthByStamp by_stamp;           // the same poses by their bag stamp
};

// Reads 'context.options.topics.truth' when the bag has it (else nothing). A pose that is not
// finite is an error naming the message.
Result<ImportedTruth> ImportTruth(BagReader& reader, const ImportContext& context);

}  // namespace semchain::ros1
