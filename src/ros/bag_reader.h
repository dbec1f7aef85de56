#pragma once

#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

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
  // Messages on 'topics' (those the bag has).
  std::size_t MessageCount(const std::vector<std::string>& topics) const;

  // Calls 'visit' with each message of 'topics' in bag-time order; the first error stops the
  // walk and is returned. Topics the bag lacks are skipped; a topic of another type than
  // 'Message' is an error.
  template <typename Message>
  Status ForEach(const std::vector<std::string>& topics,
                 const std::function<Status(const Message&, const BagMessage&)>& visit);

  // Called once per message read by ForEach (a progress bar).
  void set_on_message(std::function<void()> on_message) { on_message_ = std::move(on_message); }

 private:
  explicit BagReader(std::filesystem::path path) : path_(std::move(path)) {}
  Status CheckTopic(const std::string& topic, const std::string& datatype,
                    const std::string& md5sum) const;
  std::vector<std::string> Present(const std::vector<std::string>& topics) const;

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
Status BagReader::ForEach(const std::vector<std::string>& topics,
                          const std::function<Status(const Message&, const BagMessage&)>& visit) {
  const std::vector<std::string> present = Present(topics);
  for (const std::string& topic : present) SEMCHAIN_RETURN_IF_ERROR(Require<Message>(topic));
  if (present.empty()) return Status::Ok();
  std::map<std::string, std::size_t> counts;
  try {
    rosbag::View view(bag_, rosbag::TopicQuery(present));
    for (const rosbag::MessageInstance& instance : view) {
      const std::string& topic = instance.getTopic();
      const std::string where =
          path_.string() + ": " + topic + " message " + std::to_string(++counts[topic]);
      // The bytes are checked against the type before roscpp reads them: its serializer sizes
      // an array by the length it reads, before it knows the bytes are there.
      std::vector<std::uint8_t> bytes(instance.size());
      ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
      instance.write(out);
      SEMCHAIN_RETURN_IF_ERROR(
          LayoutOf<Message>().Check(bytes.data(), bytes.size()).WithContext(where));
      Message msg;
      ros::serialization::IStream in(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
      ros::serialization::deserialize(in, msg);
      SEMCHAIN_RETURN_IF_ERROR(visit(msg, BagMessage{topic, where}));
      if (on_message_) on_message_();
    }
  } catch (const std::exception& error) {
    return Status::Error(path_.string() + ": cannot read: " + error.what());
  }
  return Status::Ok();
}

}  // namespace semchain::ros1
