// MessageLayout against messages serialized by roscpp itself, and the corrupt lengths that
// would make roscpp's deserializer allocate gigabytes.
#include "ros/message_bounds.h"

#include <geometry_msgs/PoseStamped.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/serialization.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <cstdint>
#include <random>
#include <vector>

namespace semchain::ros1 {
namespace {

using ::testing::HasSubstr;

template <typename M>
std::vector<std::uint8_t> Serialize(const M& message) {
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(message));
  ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::serialize(stream, message);
  return bytes;
}

template <typename M>
Status CheckAs(const std::vector<std::uint8_t>& bytes) {
  return LayoutOf<M>().Check(bytes.data(), bytes.size());
}

void PutUint32(std::vector<std::uint8_t>& bytes, std::size_t offset, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes.at(offset + i) = static_cast<std::uint8_t>(value >> (8 * i));
}

std_msgs::Header MakeHeader(const std::string& frame_id) {
  std_msgs::Header header;
  header.seq = 7;
  header.stamp = ros::Time(1700000000, 5);
  header.frame_id = frame_id;
  return header;
}

sensor_msgs::LaserScan MakeScan() {
  sensor_msgs::LaserScan scan;
  scan.header = MakeHeader("laser");
  scan.angle_min = -1.5f;
  scan.angle_max = 1.5f;
  scan.range_max = 12.0f;
  scan.ranges.assign(181, 3.0f);
  scan.intensities.assign(181, 100.0f);
  return scan;
}

tf2_msgs::TFMessage MakeTf() {
  tf2_msgs::TFMessage tf;
  for (const char* child : {"base_link", "laser"}) {
    geometry_msgs::TransformStamped transform;
    transform.header = MakeHeader("odom");
    transform.child_frame_id = child;
    transform.transform.rotation.w = 1.0;
    tf.transforms.push_back(transform);
  }
  return tf;
}

TEST(MessageLayoutTest, RealMessagesPass) {
  EXPECT_TRUE(CheckAs<sensor_msgs::LaserScan>(Serialize(MakeScan())).ok());
  EXPECT_TRUE(CheckAs<sensor_msgs::LaserScan>(Serialize(sensor_msgs::LaserScan())).ok());
  EXPECT_TRUE(CheckAs<tf2_msgs::TFMessage>(Serialize(MakeTf())).ok());

  nav_msgs::Odometry odometry;
  odometry.header = MakeHeader("odom");
  odometry.child_frame_id = "base_link";
  odometry.pose.covariance[0] = 0.1;
  EXPECT_TRUE(CheckAs<nav_msgs::Odometry>(Serialize(odometry)).ok());

  sensor_msgs::Image image;
  image.header = MakeHeader("camera");
  image.height = 3;
  image.width = 4;
  image.encoding = "rgb8";
  image.step = 12;
  image.data.assign(36, 9);
  EXPECT_TRUE(CheckAs<sensor_msgs::Image>(Serialize(image)).ok());

  sensor_msgs::CameraInfo info;
  info.header = MakeHeader("camera");
  info.distortion_model = "plumb_bob";
  info.D = {0.1, -0.2, 0.0, 0.0, 0.01};
  info.K[0] = 500.0;
  EXPECT_TRUE(CheckAs<sensor_msgs::CameraInfo>(Serialize(info)).ok());

  std_msgs::String text;
  text.data = "hello";
  EXPECT_TRUE(CheckAs<std_msgs::String>(Serialize(text)).ok());

  geometry_msgs::PoseStamped pose;
  pose.header = MakeHeader("map");
  pose.pose.orientation.w = 1.0;
  EXPECT_TRUE(CheckAs<geometry_msgs::PoseStamped>(Serialize(pose)).ok());
}

TEST(MessageLayoutTest, AHugeRangesCountIsAnError) {
  const sensor_msgs::LaserScan scan = MakeScan();
  std::vector<std::uint8_t> bytes = Serialize(scan);
  // The header, then seven float32 fields before 'ranges'.
  PutUint32(bytes, ros::serialization::serializationLength(scan.header) + 7 * 4, 0xFFFFFFF0);
  const Status status = CheckAs<sensor_msgs::LaserScan>(bytes);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("field ranges: 4294967280 elements of 4 bytes, "));
}

TEST(MessageLayoutTest, AStringLongerThanTheBytesIsAnError) {
  std_msgs::String text;
  text.data = "hello";
  std::vector<std::uint8_t> bytes = Serialize(text);
  PutUint32(bytes, 0, 6);
  const Status status = CheckAs<std_msgs::String>(bytes);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "field data: string of 6 bytes, 5 bytes left");
}

TEST(MessageLayoutTest, ANestedFieldIsNamedByItsPath) {
  std::vector<std::uint8_t> bytes = Serialize(MakeTf());
  // transforms[1].header.frame_id: after the count, transform 0, seq and stamp.
  PutUint32(bytes, 4 + ros::serialization::serializationLength(MakeTf().transforms[0]) + 12, 1000);
  const Status status = CheckAs<tf2_msgs::TFMessage>(bytes);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("field transforms[1].header.frame_id: string of 1000"));
}

TEST(MessageLayoutTest, TruncatedBytesAreAnError) {
  const std::vector<std::uint8_t> scan = Serialize(MakeScan());
  for (std::size_t size = 0; size < scan.size(); ++size) {
    ASSERT_FALSE(LayoutOf<sensor_msgs::LaserScan>().Check(scan.data(), size).ok()) << size;
  }
  const std::vector<std::uint8_t> tf = Serialize(MakeTf());
  for (std::size_t size = 0; size < tf.size(); ++size) {
    ASSERT_FALSE(LayoutOf<tf2_msgs::TFMessage>().Check(tf.data(), size).ok()) << size;
  }
}

TEST(MessageLayoutTest, ATrailingByteIsAnError) {
  std::vector<std::uint8_t> bytes = Serialize(MakeScan());
  bytes.push_back(0);
  const Status status = CheckAs<sensor_msgs::LaserScan>(bytes);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), "1 byte left over after the sensor_msgs/LaserScan message");
}

// Whatever passes Check, roscpp reads without running past the end of the bytes.
TEST(MessageLayoutTest, CorruptLengthsThatPassAreSafeToDeserialize) {
  const std::vector<std::uint8_t> original = Serialize(MakeTf());
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::size_t> offset(0, original.size() - 4);
  std::uniform_int_distribution<std::uint32_t> value(0, 200);
  int passed = 0;
  for (int i = 0; i < 20000; ++i) {
    std::vector<std::uint8_t> bytes = original;
    PutUint32(bytes, offset(rng), value(rng));
    if (!CheckAs<tf2_msgs::TFMessage>(bytes).ok()) continue;
    ++passed;
    tf2_msgs::TFMessage tf;
    ros::serialization::IStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    ASSERT_NO_THROW(ros::serialization::deserialize(stream, tf)) << i;
    ASSERT_EQ(stream.getLength(), 0u) << i;
  }
  EXPECT_GT(passed, 0);
}

TEST(MessageLayoutTest, FixedArraysTakeNoCount) {
  const Result<MessageLayout> layout = MessageLayout::Parse("pkg/Calibration", "float64[9] K\n");
  ASSERT_TRUE(layout.ok()) << layout.status().message();
  const std::vector<std::uint8_t> bytes(72);
  EXPECT_TRUE(layout->Check(bytes.data(), 72).ok());
  EXPECT_FALSE(layout->Check(bytes.data(), 71).ok());
  EXPECT_FALSE(layout->Check(bytes.data(), 76).ok());
}

TEST(MessageLayoutTest, ParsesCommentsConstantsAndNestedTypes) {
  const Result<MessageLayout> layout = MessageLayout::Parse(
      "pkg/Outer",
      "# A comment line\n"
      "Header header  # the bare name is std_msgs/Header\n"
      "uint8 KIND=3 # a constant takes no bytes\n"
      "string NAME=a#b\n"
      "\n"
      "Inner[2] pair   # bare: pkg/Inner\n"
      "other/Leaf[] leaves\n"
      "================================================================================\n"
      "MSG: std_msgs/Header\n"
      "uint32 seq\ntime stamp\nstring frame_id\n"
      "================================================================================\n"
      "MSG: pkg/Inner\n"
      "int16 a\n"
      "================================================================================\n"
      "MSG: other/Leaf\n"
      "string text\n");
  ASSERT_TRUE(layout.ok()) << layout.status().message();
  // seq, stamp, frame_id "", pair (2 x int16), one leaf with text "ab".
  const std::vector<std::uint8_t> bytes = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,   0,
                                           0, 1, 0, 2, 0, 1, 0, 0, 0, 2, 0, 0, 0, 'a', 'b'};
  EXPECT_TRUE(layout->Check(bytes.data(), bytes.size()).ok());
}

TEST(MessageLayoutTest, BadDefinitionsAreErrors) {
  const auto error = [](const std::string& definition) {
    const Result<MessageLayout> layout = MessageLayout::Parse("pkg/A", definition);
    return layout.ok() ? std::string("ok") : layout.status().message();
  };
  EXPECT_THAT(error("Unknown x\n"), HasSubstr("unknown type pkg/Unknown"));
  EXPECT_THAT(error("float64[x] K\n"), HasSubstr("bad array type"));
  EXPECT_THAT(error("float64[9 K\n"), HasSubstr("bad array type"));
  EXPECT_THAT(error("float64\n"), HasSubstr("no field name"));
  EXPECT_THAT(error("B b\n===\nMSG: pkg/B\nA a\n"), HasSubstr("contains itself"));
  std::string deep = "pkg/T0 t\n";
  for (int i = 0; i < 100; ++i) {
    deep += "===\nMSG: pkg/T" + std::to_string(i) + "\npkg/T" + std::to_string(i + 1) + " t\n";
  }
  deep += "===\nMSG: pkg/T100\nint8 x\n";
  EXPECT_THAT(error(deep), HasSubstr("nested too deep"));
}

// roscpp would resize to the count even for elements that take no bytes.
TEST(MessageLayoutTest, ACountOfEmptyElementsIsBoundedByTheBytes) {
  const Result<MessageLayout> layout =
      MessageLayout::Parse("pkg/A", "Empty[] e\nuint8 x\n===\nMSG: pkg/Empty\n");
  ASSERT_TRUE(layout.ok()) << layout.status().message();
  const std::vector<std::uint8_t> none = {0, 0, 0, 0, 7};
  EXPECT_TRUE(layout->Check(none.data(), none.size()).ok());
  const std::vector<std::uint8_t> huge = {0xF0, 0xFF, 0xFF, 0xFF, 7};
  EXPECT_FALSE(layout->Check(huge.data(), huge.size()).ok());
}

}  // namespace
}  // namespace semchain::ros1
