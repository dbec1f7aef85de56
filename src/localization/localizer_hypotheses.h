#pragma once

#include <Eigen/Core>
#include <vector>

#include "localization/pose_hypothesis.h"
#include "localization/prelocalization.h"

// How the Localizer turns what pre-localization found into the filter's and the scan matcher's
// hypotheses, and the covariances it starts the filter with.
namespace semchain::localization {

// The candidates as hypotheses: more objects in agreement, more weight; the laser fit separates
// look-alikes.
std::vector<PoseHypothesis> ToHypotheses(const std::vector<PoseCandidate>& candidates);

// Drops the hypotheses explaining fewer objects than the best (the first; 'candidates' not
// empty).
void KeepMostExplaining(std::vector<PoseCandidate>* candidates);

// Tracking covariance after a scan matcher found the robot.
Eigen::Matrix3d TrackingCovariance();

// An initial pose's covariance as the filter can sample it: RViz and scripts send zeros or
// tiny values; a floor of 1 cm and 0.6° keeps the Gaussian proper.
Eigen::Matrix3d SampleableCovariance(const Eigen::Matrix3d& covariance);

}  // namespace semchain::localization
