#include "ros/truth_import.h"

#include <geometry_msgs/PoseStamped.h>

#include <cmath>

#include "ros/bag_time.h"
#include "ros/ros_geometry.h"

namespace semchain::ros1 {

Result<ImportedTruth> ImportTruth(BagReader& reader, const ImportContext& context) {
  ImportedTruth truth;
  const Status status = reader.ForEach<geometry_msgs::PoseStamped>(
      {context.options.topics.truth},
      [&truth, &context](const geometry_msgs::PoseStamped& msg, const BagMessage& message) {
        const Pose2 pose = PlanarPose(ToIsometry(msg.pose));
        if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
          return Status::Error(message.where + ": pose is not finite (a zero quaternion?)");
        }
        truth.poses.push_back({FromRosTime(msg.header.stamp, context.stamp_offset_seconds), pose});
        truth.by_stamp[Nanoseconds(msg.header.stamp)] = pose;
        return Status::Ok();
      });
  if (!status.ok()) return status;
  return truth;
}

}  // namespace semchain::ros1
