#include "mapping/proposal.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <random>

#include "core/angles.h"
#include "mapping/required_matches.h"

namespace semchain::mapping {

bool ProposalOptions::Validate(std::string* error) const {
  if (samples < 2) {
    *error = "samples must be >= 2";
    return false;
  }
  if (!(sample_window_meters > 0.0 && sample_window_radians > 0.0)) {
    *error = "sample_window_meters and sample_window_radians must be positive";
    return false;
  }
  if (!(observation_gain > 0.0)) {
    *error = "observation_gain must be positive";
    return false;
  }
  if (min_matched_points < 0 || !(min_sigma_meters > 0.0 && min_sigma_radians > 0.0)) {
    *error = "min_matched_points must be >= 0 and the minimum sigmas positive";
    return false;
  }
  if (!(recovery_window_meters >= 0.0 && recovery_window_radians > 0.0)) {
    *error = "recovery_window_meters must be >= 0 and recovery_window_radians positive";
    return false;
  }
  return heading_search.Validate(error) && mode_refinement.Validate(error);
}

ProposalEvaluation EvaluateProposal(const LikelihoodField& field, const MatchPoints& points,
                                    const MotionModel& motion, const Pose2& previous,
                                    const MotionStep& step, const HillClimbingOptions& matcher,
                                    const ProposalOptions& options, Rng& rng,
                                    const Pose2* match_start) {
  ProposalEvaluation evaluation;
  const Pose2 prediction = MotionModel::Predict(previous, step.increment);
  evaluation.mode = prediction;
  const Eigen::Vector3d motion_sigmas = motion.Sigmas(step);
  double window_xy = 3.0 * motion_sigmas.x();
  double window_theta = 3.0 * motion_sigmas.z();
  if (options.use_scan_matching) {
    const Pose2 start = match_start != nullptr             ? *match_start
                        : options.match_from_motion_sample ? motion.Sample(previous, step, rng)
                                                           : prediction;
    const MatchResult match = MatchWithHeadingSearch(field, points, start, matcher,
                                                     options.heading_search, motion_sigmas.z());
    evaluation.matched =
        match.evaluation.matched >= RequiredMatches(options.min_matched_points, points.measured);
    if (evaluation.matched) {
      evaluation.mode = match.pose;
      if (options.mode_refinement.enabled) {
        const PosePrior prior{prediction, motion_sigmas};
        evaluation.mode =
            RefineOnSurface(field, points, match.pose, options.mode_refinement, &prior).pose;
      }
      window_xy = options.sample_window_meters;
      window_theta = options.sample_window_radians;
    }
  }
  evaluation.log_volume = std::log(8.0 * window_xy * window_xy * window_theta);
  auto evaluate = [&](const Pose2& pose) {
    const double observation = field.Evaluate(points, pose).log_likelihood;
    evaluation.samples.push_back(
        {pose, options.observation_gain * observation, motion.LogDensity(pose, previous, step)});
  };
  evaluate(evaluation.mode);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int j = 0; j < options.samples; ++j) {
    // θ, y, x, one statement each (unspecified argument order; GCC's, as in SampleGaussian).
    const double theta = evaluation.mode.theta + window_theta * unit(rng);
    const double y = evaluation.mode.y + window_xy * unit(rng);
    const double x = evaluation.mode.x + window_xy * unit(rng);
    evaluate(Pose2(x, y, theta));
  }
  return evaluation;
}

GaussianFit FitProposal(const ProposalEvaluation& evaluation, double observation_exponent,
                        double motion_exponent, const ProposalOptions& options) {
  const auto& samples = evaluation.samples;
  std::vector<double> log_f(samples.size());
  for (std::size_t j = 0; j < samples.size(); ++j) {
    log_f[j] =
        observation_exponent * samples[j].log_observation + motion_exponent * samples[j].log_motion;
  }
  const double max = *std::max_element(log_f.begin(), log_f.end());
  double sum = 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> offsets(samples.size());
  std::vector<double> weights(samples.size());
  for (std::size_t j = 0; j < samples.size(); ++j) {
    weights[j] = std::exp(log_f[j] - max);
    const Pose2& x = samples[j].pose;
    offsets[j] = Eigen::Vector3d(x.x - evaluation.mode.x, x.y - evaluation.mode.y,
                                 AngleDifference(x.theta, evaluation.mode.theta));
    mean += weights[j] * offsets[j];  // eq. 4, μ
    sum += weights[j];
  }
  mean /= sum;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t j = 0; j < samples.size(); ++j) {
    const Eigen::Vector3d d = offsets[j] - mean;
    covariance += weights[j] * d * d.transpose();  // eq. 4, Σ
  }
  covariance /= sum;
  covariance(0, 0) += options.min_sigma_meters * options.min_sigma_meters;
  covariance(1, 1) += options.min_sigma_meters * options.min_sigma_meters;
  covariance(2, 2) += options.min_sigma_radians * options.min_sigma_radians;
  GaussianFit fit;
  fit.mean = mean + Eigen::Vector3d(evaluation.mode.x, evaluation.mode.y, evaluation.mode.theta);
  fit.covariance = covariance;
  // Eq. 5: η ≈ (V / K) Σ_j f(x_j), computed in the log domain.
  fit.log_normalizer =
      evaluation.log_volume + max + std::log(sum / static_cast<double>(samples.size()));
  return fit;
}

Pose2 SampleGaussian(const GaussianFit& fit, Rng& rng) {
  const Eigen::Matrix3d lower = fit.covariance.llt().matrixL();
  std::normal_distribution<double> normal;
  // Last to first, one statement each (see localization::SamplePose): the same draws with GCC,
  // which evaluated the constructor's arguments in that order, and with clang.
  const double z_theta = normal(rng);
  const double z_y = normal(rng);
  const double z_x = normal(rng);
  const Eigen::Vector3d z(z_x, z_y, z_theta);
  const Eigen::Vector3d x = fit.mean + lower * z;
  return Pose2(x.x(), x.y(), x.z());
}

}  // namespace semchain::mapping
