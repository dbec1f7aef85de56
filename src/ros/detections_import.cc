#include "ros/detections_import.h"

#include <std_msgs/String.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include "io/detections_io.h"
#include "ros/bag_time.h"

namespace semchain::ros1 {
namespace {

// The frame whose stamp is nearest 'stamp_ns', if within 'max_gap_ns' ('frames' in stamp order).
std::optional<std::size_t> NearestFrame(const std::vector<ImportedFrame>& frames,
                                        std::int64_t stamp_ns, std::int64_t max_gap_ns) {
  const auto after = std::lower_bound(
      frames.begin(), frames.end(), stamp_ns,
      [](const ImportedFrame& frame, std::int64_t stamp) { return frame.stamp_ns < stamp; });
  std::optional<std::size_t> best;
  std::int64_t best_gap = max_gap_ns;
  for (auto it = after == frames.begin() ? after : after - 1; it != frames.end() && it <= after;
       ++it) {
    const std::int64_t gap = std::llabs(it->stamp_ns - stamp_ns);
    if (gap <= best_gap) {
      best = static_cast<std::size_t>(it - frames.begin());
      best_gap = gap;
    }
  }
  return best;
}

}  // namespace

Result<std::vector<FrameDetections>> ImportDetections(BagReader& reader,
                                                      const std::vector<ImportedFrame>& frames,
                                                      ImportContext& context) {
  std::vector<FrameDetections> records;
  std::vector<std::optional<FrameDetections>> by_frame(frames.size());
  std::size_t unmatched = 0;
  std::size_t repeated = 0;
  const std::int64_t offset = context.stamp_offset_seconds;
  SEMCHAIN_RETURN_IF_ERROR(reader.ForEach<std_msgs::String>(
      {context.options.topics.detections},
      [&](const std_msgs::String& msg, const BagMessage& message) -> Status {
        Result<FrameDetections> record = ParseDetectionsRecord(msg.data, message.where);
        if (!record.ok()) return record.status();
        if (frames.empty()) {
          record->stamp = FromRosSeconds(record->stamp, offset);
          records.push_back(std::move(*record));
          return Status::Ok();
        }
        const std::int64_t stamp_ns = std::llround(record->stamp * 1e9);
        const std::optional<std::size_t> frame =
            NearestFrame(frames, stamp_ns, context.max_pair_gap_ns());
        if (!frame) {
          ++unmatched;
        } else if (by_frame[*frame]) {
          ++repeated;
        } else {
          record->frame = frames[*frame].name;
          record->stamp = frames[*frame].stamp;
          by_frame[*frame] = std::move(*record);
        }
        return Status::Ok();
      }));
  if (unmatched + repeated > 0) {
    context.warnings.push_back(std::to_string(unmatched + repeated) + " records on " +
                               context.options.topics.detections +
                               " left out: " + std::to_string(unmatched) + " match no frame, " +
                               std::to_string(repeated) + " a frame that has one");
  }
  if (frames.empty()) return records;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    records.push_back(by_frame[i] ? std::move(*by_frame[i])
                                  : FrameDetections{frames[i].name, frames[i].stamp, {}});
  }
  return records;
}

}  // namespace semchain::ros1
