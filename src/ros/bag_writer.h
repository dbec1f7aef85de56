#pragma once

#include <ros/message_traits.h>
#include <rosbag/bag.h>

#include <boost/make_shared.hpp>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>

#include "core/status.h"

// Writes a ROS bag atomically: messages go to PATH.tmp.PID beside it, which Finish() renames to
// PATH; a writer dropped before Finish() removes its temporary file, so a failed export leaves
// no half-written bag.
namespace semchain::ros1 {

enum class BagCompression { kNone, kLz4, kBz2 };

class BagWriter {
 public:
  // Starts a bag that Finish() will move to 'path'.
  static Result<std::unique_ptr<BagWriter>> Create(const std::filesystem::path& path,
                                                   BagCompression compression);
  ~BagWriter();
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  // Writes 'msg' on 'topic' at 'time'. A latched topic is recorded as `rosbag record` records
  // a latched publisher (connection header latching=1), so `rosbag play` latches it again.
  template <typename Message>
  Status Write(const std::string& topic, const ros::Time& time, const Message& msg,
               bool latched = false) {
    try {
      bag_.write(topic, time, msg, ConnectionHeader<Message>(topic, latched));
    } catch (const std::exception& error) {
      return Status::Error(temporary_.string() + ": cannot write " + topic + ": " + error.what());
    }
    return Status::Ok();
  }

  // Closes the bag and moves it into place.
  Status Finish();

 private:
  BagWriter(std::filesystem::path path, std::filesystem::path temporary);

  // The fields `rosbag record` stores for a connection; rosbag keeps one connection per
  // distinct header and topic.
  template <typename Message>
  static boost::shared_ptr<ros::M_string> ConnectionHeader(const std::string& topic, bool latched) {
    auto header = boost::make_shared<ros::M_string>();
    (*header)["topic"] = topic;
    (*header)["type"] = ros::message_traits::datatype<Message>();
    (*header)["md5sum"] = ros::message_traits::md5sum<Message>();
    (*header)["message_definition"] = ros::message_traits::definition<Message>();
    (*header)["callerid"] = "/semchain_bag_export";
    (*header)["latching"] = latched ? "1" : "0";
    return header;
  }

  std::filesystem::path path_;
  std::filesystem::path temporary_;
  rosbag::Bag bag_;
  bool finished_ = false;
};

}  // namespace semchain::ros1
