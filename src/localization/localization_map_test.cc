#include "localization/localization_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace semchain::localization {
namespace {

// 4 × 3 cells of 0.5 m at (1, 2): row 0 free, row 1 occupied, row 2 unknown except one free cell.
mapping::MapImage SmallMap() {
  return {.width = 4,
          .height = 3,
          .resolution = 0.5,
          .origin = Eigen::Vector3d(1.0, 2.0, 0.0),
          .cells = {0, 0, 0, 0, 100, 100, 100, 100, -1, -1, 0, -1}};
}

// nav2's uniform_pose_generator: a free cell drawn uniformly, the pose at that cell (its centre
// here, where our cell lookups put it), a uniform heading.
TEST(LocalizationMapTest, RandomFreePoseIsAFreeCellCentre) {
  const LocalizationMap map(SmallMap(), 2.0);
  ASSERT_EQ(map.free_cells().size(), 5u);
  Rng rng = MakeRng(3);
  int top_row = 0;
  double heading_sum = 0.0;
  const int n = 5000;
  for (int i = 0; i < n; ++i) {
    const Pose2 p = map.RandomFreePose(rng);
    EXPECT_TRUE(map.IsFree(p.translation())) << p;
    const double fx = (p.x - 1.0) / 0.5 - 0.5;
    const double fy = (p.y - 2.0) / 0.5 - 0.5;
    EXPECT_NEAR(fx, std::round(fx), 1e-9);
    EXPECT_NEAR(fy, std::round(fy), 1e-9);
    top_row += p.y > 3.0 ? 1 : 0;
    heading_sum += p.theta;
  }
  EXPECT_NEAR(static_cast<double>(top_row) / n, 0.2, 0.02);  // 1 free cell of 5
  EXPECT_NEAR(heading_sum / n, 0.0, 0.1);                    // uniform over the circle
}

}  // namespace
}  // namespace semchain::localization
