#include "ros/bag_reader.h"

#include <system_error>

#include "ros/bag_structure.h"

namespace semchain::ros1 {
namespace fs = std::filesystem;

Result<std::unique_ptr<BagReader>> BagReader::Open(const fs::path& path) {
  std::error_code ignored;
  if (!fs::is_regular_file(path, ignored))
    return Status::Error(path.string() + ": no such bag file");
  // rosbag follows the lengths and offsets it reads without comparing them with the file.
  SEMCHAIN_RETURN_IF_ERROR(CheckBagStructure(path));
  std::unique_ptr<BagReader> reader(new BagReader(path));
  try {
    reader->bag_.open(path.string(), rosbag::bagmode::Read);
    rosbag::View view(reader->bag_);
    for (const rosbag::ConnectionInfo* connection : view.getConnections()) {
      TopicInfo& info = reader->topics_[connection->topic];
      info.datatype = connection->datatype;
      info.md5sum = connection->md5sum;
    }
    for (auto& [topic, info] : reader->topics_) {
      info.messages = rosbag::View(reader->bag_, rosbag::TopicQuery(topic)).size();
    }
  } catch (const std::exception& error) {
    return Status::Error(path.string() + ": not a readable ROS bag: " + error.what());
  }
  return reader;
}

std::string BagReader::DescribeTopics() const {
  if (topics_.empty()) return "no topics";
  std::string text;
  for (const auto& [topic, info] : topics_) {
    if (!text.empty()) text += ", ";
    text += topic + " (" + info.datatype + ", " + std::to_string(info.messages) + " messages)";
  }
  return text;
}

Status BagReader::CheckTopic(const std::string& topic, const std::string& datatype,
                             const std::string& md5sum) const {
  const auto it = topics_.find(topic);
  if (it == topics_.end()) {
    return Status::Error(path_.string() + ": no topic " + topic + " (" + datatype +
                         "); the bag has " + DescribeTopics());
  }
  if (it->second.md5sum != md5sum) {
    return Status::Error(path_.string() + ": topic " + topic + " carries " + it->second.datatype +
                         ", expected " + datatype);
  }
  return Status::Ok();
}

std::size_t BagReader::MessageCount(const std::vector<std::string>& topics) const {
  std::size_t count = 0;
  for (const std::string& topic : topics) {
    const auto it = topics_.find(topic);
    if (it != topics_.end()) count += it->second.messages;
  }
  return count;
}

std::string BagReader::TypeOf(const std::string& topic) const {
  const auto it = topics_.find(topic);
  return it == topics_.end() ? std::string() : it->second.datatype;
}

Status BagReader::Walk(const std::vector<std::string>& topics, const InstanceVisitor& visit) {
  if (topics.empty()) return Status::Ok();
  std::map<std::string, std::size_t> counts;
  try {
    rosbag::View view(bag_, rosbag::TopicQuery(topics));
    for (const rosbag::MessageInstance& instance : view) {
      const std::string& topic = instance.getTopic();
      const std::string where =
          path_.string() + ": " + topic + " message " + std::to_string(++counts[topic]);
      SEMCHAIN_RETURN_IF_ERROR(visit(instance, BagMessage{topic, where}));
      if (on_message_) on_message_();
    }
  } catch (const std::exception& error) {
    return Status::Error(path_.string() + ": cannot read: " + error.what());
  }
  return Status::Ok();
}

std::vector<std::string> BagReader::Present(const std::vector<std::string>& topics) const {
  std::vector<std::string> present;
  for (const std::string& topic : topics) {
    if (Has(topic)) present.push_back(topic);
  }
  return present;
}

}  // namespace semchain::ros1
