#include "localization/kld_sampling.h"

#include <cmath>

namespace semchain::localization {

double KldSampleBound(int k, double epsilon, double z) {
  if (k <= 1) return 0.0;
  const double b = 2.0 / (9.0 * (k - 1));
  const double x = 1.0 - b + std::sqrt(b) * z;
  return (k - 1) / (2.0 * epsilon) * x * x * x;
}

bool PoseBins::Insert(const Pose2& pose) {
  // Three 21-bit signed indices packed into one key.
  const auto index = [](double value, double size) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(value / size)) &
                                      0x1FFFFF);
  };
  const std::uint64_t key =
      (index(pose.x, bin_x_) << 42) | (index(pose.y, bin_y_) << 21) | index(pose.theta, bin_theta_);
  return bins_.Insert(key).second;
}

}  // namespace semchain::localization
