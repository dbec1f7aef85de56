#pragma once

#include <Eigen/Core>
#include <vector>

#include "semantic/semantic_options.h"

// Completes an object from the part of its surface the camera saw (DESIGN.md §3.4): the
// class's shape (a box or a circle) is fitted to the observed surface cells with Ceres, its
// size held near the class prior where the observations leave it free (one face seen) and
// free to follow them where they do not (two faces, or a rounder arc). The fit starts behind
// the surface as seen from the camera, so a face is taken for the object's front, not its back.
namespace semchain::semantic {

// How far beyond the ends of a face FitShape's 'occupied_points' should reach (metres).
inline constexpr double kFaceWallReach = 0.6;

struct FittedShape {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double yaw = 0.0;                        // box: direction of its width axis
  double width = 0.0;                      // box
  double depth = 0.0;                      // box
  double radius = 0.0;                     // circle
  std::vector<Eigen::Vector2d> footprint;  // polygon, counter-clockwise
  double rms_residual = 0.0;               // metres
};

// The largest horizontal extent of a fitted shape (metres).
double ShapeExtent(const FittedShape& shape);

// 'points': the observed surface (cell centres), with 'weights' (same size; e.g. evidence);
// 'view_direction': unit vector from the object towards where it was seen from (zero when
// unknown); 'free_points': centres of cells known to be free space near the object (the laser
// map's), which the shape must not cover — they bound its size where its face was seen whole;
// 'occupied_points': centres of the laser map's occupied cells near the object. A face whose
// line runs on into a line of occupied cells beyond one of its ends lies on a wall (a chair's
// back against it, seen from the room): the object stands in front of that face, not
// behind it, and the laser's free cells there are seen under it, not around it.
FittedShape FitShape(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& weights,
                     const Eigen::Vector2d& view_direction, const ClassShapePrior& prior,
                     const std::vector<Eigen::Vector2d>& free_points = {},
                     const std::vector<Eigen::Vector2d>& occupied_points = {});

}  // namespace semchain::semantic
