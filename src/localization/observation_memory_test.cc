#include "localization/observation_memory.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace semchain::localization {
namespace {

ObservedObject Seen(const std::string& class_name, const Eigen::Vector2d& surface) {
  ObservedObject seen;
  seen.class_name = class_name;
  seen.surface = surface;
  seen.range = surface.norm();
  seen.bearing = std::atan2(surface.y(), surface.x());
  return seen;
}

TEST(ObservationMemoryTest, CarriesEarlierObjectsIntoTheCurrentFrame) {
  ObservationMemory memory;
  // A bucket 2 m ahead; then the robot turns 90° left in place: the bucket is 2 m to its right.
  memory.Add(Pose2(1.0, 1.0, 0.0), {Seen("bucket", {2.0, 0.0})});
  memory.Add(Pose2(1.0, 1.0, M_PI / 2), {Seen("door", {3.0, 0.0})});
  const std::vector<ObservedObject> now = memory.Recall(Pose2(1.0, 1.0, M_PI / 2));
  ASSERT_EQ(now.size(), 2u);
  EXPECT_EQ(now[0].class_name, "door");  // newest first
  EXPECT_EQ(now[0].frames_ago, 0);
  EXPECT_EQ(now[1].class_name, "bucket");
  EXPECT_EQ(now[1].frames_ago, 1);
  EXPECT_NEAR(now[1].surface.x(), 0.0, 1e-12);
  EXPECT_NEAR(now[1].surface.y(), -2.0, 1e-12);
  EXPECT_NEAR(now[1].range, 2.0, 1e-12);
  EXPECT_NEAR(now[1].bearing, -M_PI / 2, 1e-12);
  // Driving 0.5 m forward (along +y in the odometry frame) moves the door closer.
  const std::vector<ObservedObject> later = memory.Recall(Pose2(1.0, 1.5, M_PI / 2));
  EXPECT_NEAR(later[0].surface.x(), 2.5, 1e-12);
}

TEST(ObservationMemoryTest, KeepsTheLatestViewOfAnObject) {
  ObservationMemory memory;
  // Two cabinets side by side in one frame are two objects; the next frame sees one of them
  // again (slightly different depth): it replaces the earlier view, the other stays.
  memory.Add(Pose2(0, 0, 0), {Seen("cabinet", {2.0, 0.3}), Seen("cabinet", {2.0, -0.3})});
  memory.Add(Pose2(0, 0, 0.1), {Seen("cabinet", {2.05, 0.1})});
  const std::vector<ObservedObject> now = memory.Recall(Pose2(0, 0, 0.1));
  ASSERT_EQ(now.size(), 2u);
  EXPECT_EQ(now[0].frames_ago, 0);
  EXPECT_EQ(now[1].frames_ago, 1);
  // The one kept from the older frame is the cabinet the new frame did not see (to the right).
  EXPECT_LT(now[1].bearing, -0.1);
}

TEST(ObservationMemoryTest, ForgetsAfterATurnOrAMetre) {
  ObservationMemoryOptions options;
  options.max_rotation = 2.0 * M_PI;
  options.max_travel = 1.0;
  ObservationMemory memory(options);
  memory.Add(Pose2(0, 0, 0), {Seen("bucket", {2.0, 0.0})});
  // Turn a full circle in 16 frames, then a bit more: the first view is forgotten.
  for (int k = 1; k <= 17; ++k) memory.Add(Pose2(0, 0, NormalizeAngle(k * M_PI / 8)), {});
  EXPECT_TRUE(memory.Recall(Pose2(0, 0, NormalizeAngle(17 * M_PI / 8))).empty());

  ObservationMemory driven(options);
  driven.Add(Pose2(0, 0, 0), {Seen("bucket", {2.0, 0.0})});
  driven.Add(Pose2(0.6, 0, 0), {});
  EXPECT_EQ(driven.Recall(Pose2(0.9, 0, 0)).size(), 1u);
  EXPECT_TRUE(driven.Recall(Pose2(1.1, 0, 0)).empty());  // recall also counts the travel since
}

}  // namespace
}  // namespace semchain::localization
