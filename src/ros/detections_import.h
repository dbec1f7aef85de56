#pragma once

#include <vector>

#include "core/status.h"
#include "ros/bag_import_options.h"
#include "ros/bag_reader.h"
#include "ros/camera_import.h"
#include "sensors/detection.h"

// detections.jsonl from the bag's detections topic (std_msgs/String, one record each).
namespace semchain::ros1 {

// With 'frames' (the images written): one record per frame in frame order, named and stamped as
// the frame; a record joins the frame whose stamp is within max_pair_gap_s of its own, and a
// frame without one gets an empty record, so that detections.jsonl lists every frame (it is
// the run's frame index). A record that matches no frame, or a frame already taken, is left
// out with a warning. Without frames (a bag exported with --no-images): the records as they
// are, their stamps on the run's clock. A record that is not valid §5.5 JSON is an error
// naming the message.
Result<std::vector<FrameDetections>> ImportDetections(BagReader& reader,
                                                      const std::vector<ImportedFrame>& frames,
                                                      ImportContext& context);

}  // namespace semchain::ros1
