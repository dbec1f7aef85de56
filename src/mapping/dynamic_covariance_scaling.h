#pragma once

#include <ceres/loss_function.h>

// Dynamic covariance scaling (Agarwal, Tipaldi, Spinello, Stachniss and Burgard, "Robust Map
// Optimization using Dynamic Covariance Scaling", ICRA 2013): a loop-closure edge whose squared
// whitened residual is χ² is scaled by s = min(1, 2Φ / (Φ + χ²)) (their Eq. 14), so that an edge
// the rest of the graph contradicts is switched off, smoothly and without a switch variable of
// its own (DCS is the closed-form optimum of switchable constraints' switch).
namespace semchain::mapping {

// The scale s of an edge with squared whitened residual 'squared_norm' (χ²) under Φ = 'phi'.
double DcsScale(double squared_norm, double phi);

// DCS as an M-estimator for Ceres: ρ' = s² (iteratively reweighted least squares gives the edge
// the weight s² on its χ², as DCS scales its information matrix by s²), hence
//   ρ(χ²) = χ²                          for χ² ≤ Φ,
//   ρ(χ²) = Φ (3χ² − Φ) / (Φ + χ²)      beyond (continuous with its first derivative at Φ),
// which is bounded by 3Φ: an edge however wrong adds at most 3Φ to the cost, and its pull falls
// to zero as it grows.
class DynamicCovarianceScalingLoss : public ceres::LossFunction {
 public:
  // 'phi' > 0.
  explicit DynamicCovarianceScalingLoss(double phi);
  void Evaluate(double squared_norm, double rho[3]) const override;

 private:
  double phi_;
};

}  // namespace semchain::mapping
