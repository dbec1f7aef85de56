#pragma once

#include <Eigen/Core>

namespace semchain {

// The z component of the cross product of two plane vectors: positive when 'b' lies
// counter-clockwise of 'a'.
inline double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace semchain
