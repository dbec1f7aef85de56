#pragma once

#include <Eigen/Core>

#include "semantic/semantic_map.h"

// The geometry of pre-localization (seed 001 §2.2): the circles around two mapped objects' centres
// with the measured ranges as radii, and how far behind the surface the camera sees an object's
// centre lies.
namespace semchain::localization {

// The intersections of the circle (c0, r0) with (c1, r1): 0, 1 (tangent, or circles that miss
// each other by at most 'slack', giving the point between them) or 2 points, written to 'out'.
int IntersectCircles(const Eigen::Vector2d& c0, double r0, const Eigen::Vector2d& c1, double r1,
                     double slack, Eigen::Vector2d out[2]);

// Distance from an object's centre to its outline in 'direction' (unit): how far behind the
// surface the camera sees the centre lies.
double CenterBehindSurface(const semantic::SemanticObject& object,
                           const Eigen::Vector2d& direction);

// The mean distance from the centre to the outline: the centre's depth behind a surface seen
// from an unknown side.
double MeanCenterBehindSurface(const semantic::SemanticObject& object);

// 'v' scaled to length 1 (the x axis when it is nearly zero).
Eigen::Vector2d UnitDirection(const Eigen::Vector2d& v);

// The robot heading, as (cos, sin), that turns the direction 'seen' (robot frame) into the
// direction from 'at' to 'centre' (world): the complex product of the one by the conjugate of
// the other. Headings compared and averaged this way need no arc tangent.
Eigen::Vector2d HeadingFrom(const Eigen::Vector2d& at, const Eigen::Vector2d& centre,
                            const Eigen::Vector2d& seen);

}  // namespace semchain::localization
