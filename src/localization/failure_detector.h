#pragma once

#include "localization/amcl_options.h"

// Online detection of a lost filter (kidnapping, a wrong convergence): see
// FailureDetectorOptions. A caller that sees failed() re-runs pre-localization (seed 000 §3.1)
// and re-initialises the filter, which resets the detector.
namespace semchain::localization {

class FailureDetector {
 public:
  explicit FailureDetector(const FailureDetectorOptions& options) : options_(options) {}

  // Forgets everything (the filter was re-initialised).
  void Reset();
  // Starts watching: called when the filter has localized; until then nothing is flagged (a
  // filter still searching has a low likelihood by nature). The averages restart here, so that
  // w_slow is the likelihood of a localized filter, not of the search before.
  void Arm();
  // One sensor update: the weighted mean of what the beams add to the particle likelihoods
  // (nav2's Σ pz³, without the constant 1 that would dilute a collapse) and the weighted mean
  // per-beam likelihood pz.
  void Update(double beam_likelihood_sum, double mean_beam_likelihood);

  bool failed() const { return failed_; }
  bool armed() const { return armed_; }
  double w_slow() const { return w_slow_; }
  double w_fast() const { return w_fast_; }

 private:
  FailureDetectorOptions options_;
  bool armed_ = false;
  bool failed_ = false;
  int bad_updates_ = 0;
  double w_slow_ = 0.0;
  double w_fast_ = 0.0;
};

}  // namespace semchain::localization
