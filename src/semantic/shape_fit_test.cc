#include "semantic/shape_fit.h"

#include <gtest/gtest.h>

#include <cmath>

namespace semchain::semantic {
namespace {

ClassShapePrior Box(double width, double depth) {
  ClassShapePrior prior;
  prior.shape = ClassShapePrior::Shape::kBox;
  prior.width = width;
  prior.depth = depth;
  return prior;
}

std::vector<Eigen::Vector2d> Segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, int n) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < n; ++i) points.push_back(a + (b - a) * (i + 0.5) / n);
  return points;
}

TEST(ShapeFitTest, OneFaceIsCompletedBehindItByThePriorDepth) {
  // The front face of a 0.8 m wide box, y = 1, seen from the south.
  const auto points = Segment({1.0, 1.0}, {1.8, 1.0}, 16);
  const FittedShape shape =
      FitShape(points, std::vector<double>(points.size(), 1.0), {0.0, -1.0}, Box(0.6, 0.4));
  EXPECT_NEAR(shape.center.x(), 1.4, 0.02);
  EXPECT_NEAR(shape.center.y(), 1.2, 0.02);  // half the prior depth behind the face
  EXPECT_NEAR(shape.width, 0.8, 0.06);       // the observed width, not the prior's 0.6
  ASSERT_EQ(shape.footprint.size(), 4u);
}

TEST(ShapeFitTest, ANarrowFaceIsNotGivenMoreDepthThanWidth) {
  // A 0.28 m face of a class whose prior is 0.4 m deep: depth ≤ width puts the centre 0.14 m back.
  const auto points = Segment({2.0, 1.0}, {2.0, 1.28}, 6);
  const FittedShape shape =
      FitShape(points, std::vector<double>(points.size(), 1.0), {-1.0, 0.0}, Box(0.6, 0.4));
  EXPECT_NEAR(shape.center.x(), 2.14, 0.03);
  EXPECT_NEAR(shape.center.y(), 1.14, 0.02);
}

TEST(ShapeFitTest, TwoFacesFixBothSizes) {
  // Front (y = 1, x 1–1.5) and right side (x = 1.5, y 1–1.4) of a 0.5 × 0.4 box: the side
  // shows the depth, which neither the prior (0.6) nor the face width (0.5) gives.
  auto points = Segment({1.0, 1.0}, {1.5, 1.0}, 10);
  const auto side = Segment({1.5, 1.0}, {1.5, 1.4}, 8);
  points.insert(points.end(), side.begin(), side.end());
  const FittedShape shape = FitShape(points, std::vector<double>(points.size(), 1.0),
                                     Eigen::Vector2d(0.0, -1.0), Box(0.6, 0.6));
  EXPECT_NEAR(shape.center.x(), 1.25, 0.03);
  EXPECT_NEAR(shape.center.y(), 1.2, 0.02);
}

TEST(ShapeFitTest, FreeSpaceBoundsTheBox) {
  // A short face whose ends are known free: the box may not grow over them.
  const auto points = Segment({1.0, 1.0}, {1.3, 1.0}, 6);
  std::vector<Eigen::Vector2d> free;
  for (double x = 0.6; x < 0.98; x += 0.05) free.emplace_back(x, 1.1);
  for (double x = 1.33; x < 1.7; x += 0.05) free.emplace_back(x, 1.1);
  const FittedShape shape =
      FitShape(points, std::vector<double>(points.size(), 1.0), {0.0, -1.0}, Box(0.9, 0.3), free);
  EXPECT_LT(shape.width, 0.4);
  EXPECT_NEAR(shape.center.x(), 1.15, 0.03);
}

TEST(ShapeFitTest, AnArcGivesItsCircleCentre) {
  ClassShapePrior prior;
  prior.shape = ClassShapePrior::Shape::kCircle;
  prior.radius = 0.15;
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 10; ++i) {
    const double a = -M_PI / 2 - 0.8 + 1.6 * i / 9.0;  // the side facing −y
    points.emplace_back(3.0 + 0.15 * std::cos(a), 2.0 + 0.15 * std::sin(a));
  }
  const FittedShape shape =
      FitShape(points, std::vector<double>(points.size(), 1.0), {0.0, -1.0}, prior);
  EXPECT_NEAR(shape.center.x(), 3.0, 0.01);
  EXPECT_NEAR(shape.center.y(), 2.0, 0.01);
  EXPECT_NEAR(shape.radius, 0.15, 0.01);
}

}  // namespace
}  // namespace semchain::semantic
