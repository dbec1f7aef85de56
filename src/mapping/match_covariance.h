#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "mapping/match_grid.h"

// The covariance of a scan match from the score around it (the correlative matcher's response,
// Olson, "Real-Time Correlative Scan Matching", ICRA 2009, §III-D; Karto computes its loop
// closures' covariances this way): every pose of a grid around the match whose score is within
// 'score_drop' of the match's counts with its score as weight, and the weighted spread of those
// poses about the match is its covariance. A match in a room is certain in every direction; one
// down a corridor scores alike all along it, and its covariance says so.
namespace semchain::mapping {

struct MatchCovarianceOptions {
  // Poses within ± this of the match in x and y (wide enough for a corridor's look-alike
  // stretch several doors away: ±2 m left the simulated campus bent by a closure 7.5 m off) ...
  double window_meters = 8.0;
  double window_radians = 0.05;  // ... and ± this in θ
  double linear_step_meters = 0.1;
  double angular_step_radians = 0.01;
  double score_drop = 0.1;  // poses scoring at least the match's score minus this count

  bool Validate(std::string* error) const;
};

// The covariance of (x, y, θ) of 'match' (the pose of 'points', robot frame, in 'grid'), about
// 'match' itself; the grid's own discretisation (a step's uniform variance) is its floor.
Eigen::Matrix3d MatchCovariance(const MatchGrid& grid, const std::vector<Eigen::Vector2d>& points,
                                const Pose2& match, const MatchCovarianceOptions& options = {});

}  // namespace semchain::mapping
