#include "mapping/dynamic_covariance_scaling.h"

#include <algorithm>

#include "core/check.h"

namespace semchain::mapping {

double DcsScale(double squared_norm, double phi) {
  return std::min(1.0, 2.0 * phi / (phi + squared_norm));
}

DynamicCovarianceScalingLoss::DynamicCovarianceScalingLoss(double phi) : phi_(phi) {
  SEMCHAIN_CHECK(phi > 0.0);
}

void DynamicCovarianceScalingLoss::Evaluate(double squared_norm, double rho[3]) const {
  if (squared_norm <= phi_) {
    rho[0] = squared_norm;
    rho[1] = 1.0;
    rho[2] = 0.0;
    return;
  }
  const double sum = phi_ + squared_norm;
  rho[0] = phi_ * (3.0 * squared_norm - phi_) / sum;
  rho[1] = 4.0 * phi_ * phi_ / (sum * sum);  // s²
  rho[2] = -8.0 * phi_ * phi_ / (sum * sum * sum);
}

}  // namespace semchain::mapping
