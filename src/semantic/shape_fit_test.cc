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

// The occupied cells (5 cm) of a wall along y = 'y' from x0 to x1.
std::vector<Eigen::Vector2d> WallCells(double x0, double x1, double y) {
  std::vector<Eigen::Vector2d> cells;
  for (double x = x0; x <= x1 + 1e-9; x += 0.05) cells.emplace_back(x, y);
  return cells;
}

// A chair (0.5 m, prior 0.5 × 0.5) with its back against the wall y = 2.0, seen from the room
// (south): the camera sees its back, 0.45 m wide, a few centimetres in front of the wall. The
// laser sees the wall beside it, and under the seat (free).
struct ChairAgainstAWall {
  std::vector<Eigen::Vector2d> points = Segment({1.05, 1.96}, {1.45, 1.96}, 9);
  std::vector<double> weights = std::vector<double>(points.size(), 1.0);
  std::vector<Eigen::Vector2d> wall = WallCells(0.0, 3.0, 2.0);
  std::vector<Eigen::Vector2d> under_the_seat;
  ChairAgainstAWall() {
    for (double x = 1.05; x < 1.46; x += 0.05) {
      for (double y = 1.55; y < 1.9; y += 0.05) under_the_seat.emplace_back(x, y);
    }
  }
};

TEST(ShapeFitTest, AFaceOnAWallIsTheBackOfAnObjectInFrontOfIt) {
  const ChairAgainstAWall scene;
  const FittedShape shape = FitShape(scene.points, scene.weights, {0.0, -1.0}, Box(0.5, 0.5),
                                     scene.under_the_seat, scene.wall);
  EXPECT_NEAR(shape.center.x(), 1.25, 0.03);
  // In the room: its back at the face, its depth (no more than the face is wide) in front.
  EXPECT_NEAR(shape.center.y() + 0.5 * shape.depth, 1.96, 0.03);
  EXPECT_GT(shape.depth, 0.3);
  // Without the wall the same face is taken for the front: the chair lands beyond the wall.
  const FittedShape unaware =
      FitShape(scene.points, scene.weights, {0.0, -1.0}, Box(0.5, 0.5), scene.under_the_seat);
  EXPECT_GT(unaware.center.y(), 2.0);
}

TEST(ShapeFitTest, AFaceBesideAWallCornerIsOnTheWall) {
  // The same chair in the corner of the wall y = 2 and a wall x = 1.5: beyond the face's east
  // end is the corner; beyond its west end the wall runs on.
  ChairAgainstAWall scene;
  scene.wall = WallCells(0.0, 1.5, 2.0);
  for (double y = 0.0; y < 2.0; y += 0.05) scene.wall.emplace_back(1.5, y);
  const FittedShape shape =
      FitShape(scene.points, scene.weights, {0.0, -1.0}, Box(0.5, 0.5), {}, scene.wall);
  EXPECT_LT(shape.center.y(), 1.96);
}

TEST(ShapeFitTest, AFaceWellInFrontOfAWallIsTheFrontOfTheObject) {
  // A cabinet 0.4 m deep against the wall y = 2: its front, y = 1.6, is what the camera sees;
  // the wall beside it is 0.4 m behind the face.
  const auto points = Segment({1.0, 1.6}, {1.6, 1.6}, 12);
  std::vector<Eigen::Vector2d> wall = WallCells(0.0, 0.95, 2.0);
  const auto east = WallCells(1.65, 3.0, 2.0);
  wall.insert(wall.end(), east.begin(), east.end());
  const FittedShape shape = FitShape(points, std::vector<double>(points.size(), 1.0), {0.0, -1.0},
                                     Box(0.6, 0.4), {}, wall);
  EXPECT_NEAR(shape.center.y(), 1.8, 0.03);
}

TEST(ShapeFitTest, AWallMetAtAnAngleDoesNotTurnTheObject) {
  // A cabinet front y = 1.6 whose line runs into a wall at 30°: the wall crosses the line in a
  // short run, and the box stays behind its face.
  const auto points = Segment({1.0, 1.6}, {1.6, 1.6}, 12);
  std::vector<Eigen::Vector2d> wall;
  for (double t = 0.0; t < 2.0; t += 0.05) wall.emplace_back(1.65 + t * 0.866, 1.45 + t * 0.5);
  const FittedShape shape = FitShape(points, std::vector<double>(points.size(), 1.0), {0.0, -1.0},
                                     Box(0.6, 0.4), {}, wall);
  EXPECT_NEAR(shape.center.y(), 1.8, 0.03);
}

TEST(ShapeFitTest, AThinObjectOnAWallStaysInItsPlace) {
  // A door leaf (prior 0.05 deep) in the wall's line: in front of the face or behind it, it
  // is in the wall; the fit is the one without the wall.
  const auto points = Segment({1.0, 2.0}, {1.9, 2.0}, 18);
  const std::vector<double> weights(points.size(), 1.0);
  const FittedShape with_wall =
      FitShape(points, weights, {0.0, -1.0}, Box(0.9, 0.05), {}, WallCells(0.0, 3.0, 2.0));
  const FittedShape without = FitShape(points, weights, {0.0, -1.0}, Box(0.9, 0.05));
  EXPECT_NEAR(with_wall.center.y(), without.center.y(), 1e-9);
  EXPECT_GT(with_wall.center.y(), 2.0);
}

TEST(ShapeFitTest, AStoolAgainstAWallIsInFrontOfIt) {
  ClassShapePrior prior;
  prior.shape = ClassShapePrior::Shape::kCircle;
  prior.radius = 0.17;
  std::vector<Eigen::Vector2d> points;  // the arc facing −y of a stool whose back touches y = 2
  for (int i = 0; i < 9; ++i) {
    const double a = -M_PI / 2 - 0.7 + 1.4 * i / 8.0;
    points.emplace_back(1.0 + 0.17 * std::cos(a), 1.83 + 0.17 * std::sin(a));
  }
  // What the camera took for the stool reaches back to the wall (its pixels beside the seat).
  const auto on_wall = Segment({0.85, 1.98}, {1.15, 1.98}, 7);
  points.insert(points.end(), on_wall.begin(), on_wall.end());
  const std::vector<double> weights(points.size(), 1.0);
  const FittedShape shape =
      FitShape(points, weights, {0.0, -1.0}, prior, {}, WallCells(0.0, 3.0, 2.0));
  EXPECT_LT(shape.center.y() + shape.radius, 2.05);
  EXPECT_NEAR(shape.center.x(), 1.0, 0.03);
}

TEST(ShapeFitTest, AStoolSeenAtAnAngleAgainstAWallIsInFrontOfIt) {
  ClassShapePrior prior;
  prior.shape = ClassShapePrior::Shape::kCircle;
  prior.radius = 0.17;
  // Seen at 30° from the wall's normal, what the camera took for the stool lies along the wall
  // (its back and the wall beside it): the line across the view does not run along the wall,
  // the points do.
  const auto points = Segment({0.8, 1.97}, {1.2, 1.97}, 9);
  const std::vector<double> weights(points.size(), 1.0);
  const Eigen::Vector2d oblique(-0.5, -std::sqrt(0.75));
  const FittedShape shape = FitShape(points, weights, oblique, prior, {}, WallCells(0.0, 3.0, 2.0));
  EXPECT_LT(shape.center.y(), 1.9);
  EXPECT_GT(FitShape(points, weights, oblique, prior).center.y(), 2.0);
}

}  // namespace
}  // namespace semchain::semantic
