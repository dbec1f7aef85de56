#include "localization/object_circles.h"

#include <gtest/gtest.h>

#include <cmath>

namespace semchain::localization {
namespace {

TEST(IntersectCirclesTest, TwoPointsTangentDisjointConcentric) {
  Eigen::Vector2d p[2];
  // 3-4-5: circles around (0, 0) r 5 and (6, 0) r 5 meet at (3, ±4).
  ASSERT_EQ(IntersectCircles({0, 0}, 5, {6, 0}, 5, 0.0, p), 2);
  EXPECT_NEAR(p[0].x(), 3.0, 1e-12);
  EXPECT_NEAR(std::abs(p[0].y()), 4.0, 1e-12);
  EXPECT_NEAR(p[1].y(), -p[0].y(), 1e-12);
  // Externally tangent.
  ASSERT_EQ(IntersectCircles({0, 0}, 2, {5, 0}, 3, 0.0, p), 1);
  EXPECT_NEAR((p[0] - Eigen::Vector2d(2, 0)).norm(), 0.0, 1e-9);
  // Internally tangent.
  ASSERT_EQ(IntersectCircles({0, 0}, 5, {2, 0}, 3, 0.0, p), 1);
  EXPECT_NEAR((p[0] - Eigen::Vector2d(5, 0)).norm(), 0.0, 1e-9);
  // Disjoint: apart, one inside the other, concentric.
  EXPECT_EQ(IntersectCircles({0, 0}, 1, {5, 0}, 1, 0.0, p), 0);
  EXPECT_EQ(IntersectCircles({0, 0}, 5, {1, 0}, 1, 0.0, p), 0);
  EXPECT_EQ(IntersectCircles({1, 1}, 2, {1, 1}, 2, 0.5, p), 0);
  // Apart by less than the slack: the point between them.
  ASSERT_EQ(IntersectCircles({0, 0}, 2, {5, 0}, 2.9, 0.2, p), 1);
  EXPECT_NEAR(p[0].x(), 2.05, 1e-9);
}

TEST(CenterBehindSurfaceTest, DistanceToTheOutline) {
  semantic::SemanticObject box;  // a 0.4 m square around (1, 1)
  box.class_name = "cabinet";
  box.center = {1.0, 1.0};
  box.footprint = {{1.2, 1.2}, {0.8, 1.2}, {0.8, 0.8}, {1.2, 0.8}};
  EXPECT_NEAR(CenterBehindSurface(box, {1.0, 0.0}), 0.2, 1e-12);
  EXPECT_NEAR(CenterBehindSurface(box, Eigen::Vector2d(1.0, 1.0).normalized()),
              0.2 * std::sqrt(2.0), 1e-12);
}

}  // namespace
}  // namespace semchain::localization
