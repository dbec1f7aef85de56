#pragma once

#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/status.h"
#include "ros/message_bounds.h"

// Reads a ROS bag topic by topic, turning rosbag's exceptions into one-line errors that name
// the bag, and the topic and message where one is to blame.
namespace semchain::ros1 {

// Where a message came from, for the visitor of BagReader::ForEach.
struct BagMessage {
  const std::string& topic;
  const std::string& where;  // "FILE.bag: /scan message 12", to prefix errors
};

class BagReader {
 public:
  // Opens 'path'; a missing file or one that is not a bag (version 2.0) is an error.
  static Result<std::unique_ptr<BagReader>> Open(const std::filesystem::path& path);
  BagReader(const BagReader&) = delete;
  BagReader& operator=(const BagReader&) = delete;

  const std::filesystem::path& path() const { return path_; }
  bool Has(const std::string& topic) const { return topics_.count(topic) > 0; }
  // "/odom (nav_msgs/Odometry, 120 messages), /scan (...)", or "no topics".
  std::string DescribeTopics() const;
  // An error when 'topic' is not in the bag or carries another type than 'Message' (types
  // are compared by their MD5 sum, so an old bag's tf/tfMessage reads as tf2_msgs/TFMessage).
  template <typename Message>
  Status Require(const std::string& topic) const {
    return CheckTopic(topic, ros::message_traits::datatype<Message>(),
                      ros::message_traits::md5sum<Message>());
  }
  // Whether the bag has 'topic' carrying 'Message'.
  template <typename Message>
  bool Carries(const std::string& topic) const {
    const auto it = topics_.find(topic);
    return it != topics_.end() && it->second.md5sum == ros::message_traits::md5sum<Message>();
  }
  // The type 'topic' carries ("sensor_msgs/Image"), empty when the bag lacks it.
  std::string TypeOf(const std::string& topic) const;
  // Messages on 'topics' (those the bag has).
  std::size_t MessageCount(const std::vector<std::string>& topics) const;

  // Calls 'visit' with each message of 'topics' in bag-time order; the first error stops the
  // walk and is returned. Topics the bag lacks are skipped; a topic of another type than
  // 'Message' is an error.
  template <typename Message>
  Status ForEach(const std::vector<std::string>& topics,
                 const std::function<Status(const Message&, const BagMessage&)>& visit);
  // The same for two message types in one walk: 'visit_a' with the messages of 'topics_a' and
  // 'visit_b' with those of 'topics_b', all in bag-time order (an RGB-D camera whose colour
  // and depth topics carry different types).
  template <typename A, typename B>
  Status ForEach(const std::vector<std::string>& topics_a,
                 const std::function<Status(const A&, const BagMessage&)>& visit_a,
                 const std::vector<std::string>& topics_b,
                 const std::function<Status(const B&, const BagMessage&)>& visit_b);

  // Called once per message read by ForEach (a progress bar).
  void set_on_message(std::function<void()> on_message) { on_message_ = std::move(on_message); }

 private:
  explicit BagReader(std::filesystem::path path) : path_(std::move(path)) {}
  Status CheckTopic(const std::string& topic, const std::string& datatype,
                    const std::string& md5sum) const;
  std::vector<std::string> Present(const std::vector<std::string>& topics) const;
  // Calls 'visit' with each message instance of 'topics' (present ones) in bag-time order.
  using InstanceVisitor =
      std::function<Status(const rosbag::MessageInstance& instance, const BagMessage& message)>;
  Status Walk(const std::vector<std::string>& topics, const InstanceVisitor& visit);
  // 'instance' as a 'Message', its bytes checked against the type first.
  template <typename Message>
  static Status Decode(const rosbag::MessageInstance& instance, const std::string& where,
                       Message* msg);

  struct TopicInfo {
    std::string datatype;
    std::string md5sum;
    std::size_t messages = 0;
  };
  std::filesystem::path path_;
  rosbag::Bag bag_;
  std::map<std::string, TopicInfo> topics_;
  std::function<void()> on_message_;
};

template <typename Message>
Status BagReader::Decode(const rosbag::MessageInstance& instance, const std::string& where,
                         Message* msg) {
  // The bytes are checked against the type before roscpp reads them: its serializer sizes an
  // array by the length it reads, before it knows the bytes are there.
  std::vector<std::uint8_t> bytes(instance.size());
  ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  instance.write(out);
  SEMCHAIN_RETURN_IF_ERROR(
      LayoutOf<Message>().Check(bytes.data(), bytes.size()).WithContext(where));
  ros::serialization::IStream in(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::deserialize(in, *msg);
  return Status::Ok();
}

template <typename Message>
Status BagReader::ForEach(const std::vector<std::string>& topics,
                          const std::function<Status(const Message&, const BagMessage&)>& visit) {
  const std::vector<std::string> present = Present(topics);
  for (const std::string& topic : present) SEMCHAIN_RETURN_IF_ERROR(Require<Message>(topic));
  return Walk(
      present,
      [&visit](const rosbag::MessageInstance& instance, const BagMessage& message) -> Status {
        Message msg;
        SEMCHAIN_RETURN_IF_ERROR(Decode(instance, message.where, &msg));
        return visit(msg, message);
      });
}

template <typename A, typename B>
Status BagReader::ForEach(const std::vector<std::string>& topics_a,
                          const std::function<Status(const A&, const BagMessage&)>& visit_a,
                          const std::vector<std::string>& topics_b,
                          const std::function<Status(const B&, const BagMessage&)>& visit_b) {
  const std::vector<std::string> present_a = Present(topics_a);
  const std::vector<std::string> present_b = Present(topics_b);
  for (const std::string& topic : present_a) SEMCHAIN_RETURN_IF_ERROR(Require<A>(topic));
  for (const std::string& topic : present_b) SEMCHAIN_RETURN_IF_ERROR(Require<B>(topic));
  std::vector<std::string> present = present_a;
  present.insert(present.end(), present_b.begin(), present_b.end());
  return Walk(
      present, [&](const rosbag::MessageInstance& instance, const BagMessage& message) -> Status {
        if (std::find(present_a.begin(), present_a.end(), message.topic) != present_a.end()) {
          A msg;
          SEMCHAIN_RETURN_IF_ERROR(Decode(instance, message.where, &msg));
          return visit_a(msg, message);
        }
        B msg;
        SEMCHAIN_RETURN_IF_ERROR(Decode(instance, message.where, &msg));
        return visit_b(msg, message);
      });
}

}  // namespace semchain::ros1
