#include "ros/bag_transforms.h"

#include <console_bridge/console.h>
#include <tf2/exceptions.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "ros/ros_geometry.h"

namespace semchain::ros1 {
namespace {

// tf2 warns on stderr about data it ignores (a stamp seen twice); the importer counts what tf2
// refuses instead, so that its output stays one line per problem.
class QuietTf2 {
 public:
  QuietTf2() : level_(console_bridge::getLogLevel()) {
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  }
  ~QuietTf2() { console_bridge::setLogLevel(level_); }
  QuietTf2(const QuietTf2&) = delete;
  QuietTf2& operator=(const QuietTf2&) = delete;

 private:
  console_bridge::LogLevel level_;
};

struct StampRange {
  ros::Time first = ros::TIME_MAX;
  ros::Time last = ros::TIME_MIN;
  void Add(const ros::Time& stamp) {
    first = std::min(first, stamp);
    last = std::max(last, stamp);
  }
};

// tf2 keeps dynamic transforms for its cache time before the newest one: the cache must cover
// the stamps of the whole bag (of /tf and of the odometry topic that may stand in for it),
// which need not follow the recording clock (a simulation that ran faster than real time).
Result<ros::Duration> CacheSpan(BagReader& reader, const BagTopics& topics) {
  StampRange range;
  SEMCHAIN_RETURN_IF_ERROR(reader.ForEach<tf2_msgs::TFMessage>(
      {topics.tf}, [&range](const tf2_msgs::TFMessage& msg, const BagMessage&) {
        for (const geometry_msgs::TransformStamped& t : msg.transforms) range.Add(t.header.stamp);
        return Status::Ok();
      }));
  SEMCHAIN_RETURN_IF_ERROR(reader.ForEach<nav_msgs::Odometry>(
      {topics.odom}, [&range](const nav_msgs::Odometry& msg, const BagMessage&) {
        range.Add(msg.header.stamp);
        return Status::Ok();
      }));
  const double seconds = range.last > range.first ? (range.last - range.first).toSec() : 0.0;
  constexpr double kMargin = 10.0;
  return ros::Duration(
      std::min(seconds + kMargin, static_cast<double>(std::numeric_limits<std::int32_t>::max())));
}

}  // namespace

std::string TfFrameId(const std::string& frame_id, const std::string& fallback) {
  const std::size_t begin = frame_id.find_first_not_of('/');
  return begin == std::string::npos ? fallback : frame_id.substr(begin);
}

Result<std::unique_ptr<BagTransforms>> BagTransforms::Load(BagReader& reader,
                                                           const BagTopics& topics) {
  Result<ros::Duration> span = CacheSpan(reader, topics);
  if (!span.ok()) return span.status();
  std::unique_ptr<BagTransforms> transforms(new BagTransforms(*span));
  const QuietTf2 quiet;
  for (const bool is_static : {true, false}) {
    const std::string& topic = is_static ? topics.tf_static : topics.tf;
    SEMCHAIN_RETURN_IF_ERROR(reader.ForEach<tf2_msgs::TFMessage>(
        {topic}, [&transforms, is_static](const tf2_msgs::TFMessage& msg, const BagMessage&) {
          for (const geometry_msgs::TransformStamped& transform : msg.transforms) {
            if (!transforms->buffer_.setTransform(transform, "bag", is_static)) {
              ++transforms->rejected_;
            }
          }
          return Status::Ok();
        }));
  }
  return transforms;
}

Status BagTransforms::AddOdometry(BagReader& reader, const std::string& topic,
                                  const std::string& odom_frame, const std::string& base_frame) {
  const QuietTf2 quiet;
  return reader.ForEach<nav_msgs::Odometry>(
      {topic}, [&](const nav_msgs::Odometry& msg, const BagMessage&) {
        geometry_msgs::TransformStamped transform;
        transform.header.stamp = msg.header.stamp;
        transform.header.frame_id = odom_frame;
        transform.child_frame_id = base_frame;
        transform.transform.translation.x = msg.pose.pose.position.x;
        transform.transform.translation.y = msg.pose.pose.position.y;
        transform.transform.translation.z = msg.pose.pose.position.z;
        transform.transform.rotation = msg.pose.pose.orientation;
        if (!buffer_.setTransform(transform, "bag", false)) ++rejected_;
        return Status::Ok();
      });
}

bool BagTransforms::Connects(const std::string& target_frame,
                             const std::string& source_frame) const {
  // Time 0 asks for the latest time at which both frames are known.
  return buffer_.canTransform(target_frame, source_frame, ros::Time());
}

Result<Eigen::Isometry3d> BagTransforms::Lookup(const std::string& target_frame,
                                                const std::string& source_frame,
                                                const ros::Time& time) const {
  try {
    return ToIsometry(buffer_.lookupTransform(target_frame, source_frame, time).transform);
  } catch (const tf2::TransformException& error) {
    return Status::Error(error.what());
  }
}

std::string BagTransforms::Frames() const {
  std::vector<std::string> frames;
  buffer_._getFrameStrings(frames);
  std::sort(frames.begin(), frames.end());
  std::string text;
  for (const std::string& frame : frames) text += (text.empty() ? "" : ", ") + frame;
  return text.empty() ? "none" : text;
}

}  // namespace semchain::ros1
