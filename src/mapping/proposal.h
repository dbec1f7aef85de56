#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/rng.h"
#include "mapping/heading_search.h"
#include "mapping/hill_climbing_matcher.h"
#include "mapping/likelihood_field.h"
#include "mapping/motion_model.h"
#include "mapping/surface_refinement.h"

// The improved proposal of GMapping (Grisetti et al. 2007; seed 003 eq. 4–5, seed 004 eq. 4–5):
// scan-match the odometry prediction against the particle's map, evaluate K poses x_j around the
// mode, fit a Gaussian to p(z | m, x_j) p(x_j | x_{t-1}, u) and draw the new pose from it; the
// weight grows by the normaliser η = ∫ p(z | m, x) p(x | x_{t-1}, u) dx. With annealing the two
// factors get exponents 1 - α and α (seed 003 eq. 6).
namespace semchain::mapping {

struct ProposalOptions {
  // false: the basic RBPF of seed 003 §1 (sample the motion model, weight by the likelihood).
  bool use_scan_matching = true;
  int samples = 16;  // K of eq. 4 (the mode is evaluated in addition)
  // Start the scan match from a draw of the motion model instead of the plain prediction (as
  // GMapping does): particles then find different local modes where there are several (a loop
  // closing with drift), which is where the filter needs its diversity.
  bool match_from_motion_sample = true;
  // Sweep the heading around the start before hill climbing, and climb from the best heading
  // too when it differs (heading_search.h): the match then absorbs the heading error of wheel
  // odometry on a turn, which the kernel of the likelihood field alone cannot.
  HeadingSearchOptions heading_search;
  // After hill climbing, refine the mode by Gauss-Newton with the (noise-free) prediction as a
  // prior of the motion model's covariance: along directions the scan does not constrain (a
  // corridor's axis) the mode returns to the prediction instead of keeping the random start,
  // whose noise would otherwise accumulate there.
  SurfaceRefinementOptions mode_refinement{true, 5, 0.02, 1e-4, 0.5, true};
  double sample_window_meters = 0.01;    // the x_j are uniform within ±this of the mode
  double sample_window_radians = 0.005;  // and ±this in heading
  // Multiplies log p(z | m, x) in the proposal (1 = the likelihood field as it is). Lower values
  // widen the proposal: its noise then accumulates into drift (mit-csail: 0.1 gave degrees).
  double observation_gain = 1.0;
  // A match with fewer endpoints on obstacles (or than a third of the points matched, when that
  // is fewer: RequiredMatches) is not trusted: the proposal then centres on the odometry
  // prediction and samples a window as wide as the motion noise.
  int min_matched_points = 30;
  // When no particle's match is trusted — the whole filter lost the scan: a loop closing beyond
  // hill climbing's reach, a turn whose wheel odometry stalled — each particle's match starts
  // instead from the best pose of a correlative search around its prediction, ±3σ of the motion
  // noise capped at these (0: off). ACES on wheel odometry: every failing seed lost
  // all its particles' matches at the central crossing of corridors, where it closes a loop.
  // Searched per particle only in those steps: a search on every untrusted particle's match
  // found trusted but wrong matches along ACES's corridors (docs/experiments.md).
  double recovery_window_meters = 0.0;
  double recovery_window_radians = 0.4;
  // Floors on the fitted Gaussian's standard deviations.
  double min_sigma_meters = 0.002;
  double min_sigma_radians = 0.001;

  bool Validate(std::string* error) const;
};

// One evaluated pose: log p(z | m, x_j) (gain applied) and log p(x_j | x_{t-1}, u).
struct ProposalSample {
  Pose2 pose;
  double log_observation = 0.0;
  double log_motion = 0.0;
};

struct ProposalEvaluation {
  bool matched = false;     // false: the scan match was not trusted (see min_matched_points)
  Pose2 mode;               // the scan-matched pose (or the prediction)
  double log_volume = 0.0;  // log of the sampled window's volume
  std::vector<ProposalSample> samples;
};

// Scan-matches 'points' from the prediction previous ⊕ step.increment (or a motion-model draw)
// and evaluates K poses around the mode (eq. 4 and 5 need both likelihoods at each x_j).
ProposalEvaluation EvaluateProposal(const LikelihoodField& field, const MatchPoints& points,
                                    const MotionModel& motion, const Pose2& previous,
                                    const MotionStep& step, const HillClimbingOptions& matcher,
                                    const ProposalOptions& options, Rng& rng,
                                    const Pose2* match_start = nullptr);

// The Gaussian fitted to the samples weighted by p(z | ·)^a p(· | x_{t-1}, u)^b.
struct GaussianFit {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();  // x, y, θ
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  double log_normalizer = 0.0;  // log η of eq. 5 (window volume included)
};

// Eq. 4 (μ, Σ) and eq. 5 (η) with exponents a = 'observation_exponent', b = 'motion_exponent'
// (1, 1 for GMapping; 1 - α, α with annealing, eq. 6).
GaussianFit FitProposal(const ProposalEvaluation& evaluation, double observation_exponent,
                        double motion_exponent, const ProposalOptions& options);

// Draws a pose from N(mean, covariance).
Pose2 SampleGaussian(const GaussianFit& fit, Rng& rng);

}  // namespace semchain::mapping
