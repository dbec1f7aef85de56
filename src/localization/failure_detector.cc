#include "localization/failure_detector.h"

namespace semchain::localization {

void FailureDetector::Reset() {
  armed_ = failed_ = false;
  bad_updates_ = 0;
  w_slow_ = w_fast_ = 0.0;
}

void FailureDetector::Arm() {
  if (armed_) return;
  armed_ = true;
  w_slow_ = w_fast_ = 0.0;
}

void FailureDetector::Update(double mean_likelihood, double mean_beam_likelihood) {
  // Probabilistic Robotics Table 8.3 lines 8–10: exponential averages of the likelihood.
  if (w_slow_ == 0.0) {
    w_slow_ = w_fast_ = mean_likelihood;
  } else {
    w_slow_ += options_.alpha_slow * (mean_likelihood - w_slow_);
    w_fast_ += options_.alpha_fast * (mean_likelihood - w_fast_);
  }
  if (!armed_) return;
  const bool collapsed = w_fast_ < options_.min_fast_slow_ratio * w_slow_ ||
                         mean_beam_likelihood < options_.min_mean_beam_likelihood;
  bad_updates_ = collapsed ? bad_updates_ + 1 : 0;
  failed_ = bad_updates_ >= options_.consecutive_updates;
}

}  // namespace semchain::localization
