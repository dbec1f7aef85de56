// A quick real-data check on the first scans of the raw MIT CSAIL log (the full benchmark is
// `semchain bench slam`): accuracy against the relations that fall inside, and copy-on-write
// map sharing between the particles of a building-sized run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/angles.h"
#include "io/carmen.h"
#include "mapping/rbpf_slam.h"
#include "mapping/slam_pipeline.h"

namespace semchain::mapping {
namespace {

constexpr std::size_t kScans = 300;

std::filesystem::path DataDir() {
  return std::filesystem::path(SEMCHAIN_SHARED_DATA_DIR) / "mit-csail";
}

class MitCsailSmokeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(DataDir() / "mit-csail.clf")) {
      GTEST_SKIP() << "shared data not available";
    }
    const Result<carmen::Log> log = carmen::ReadLog(DataDir() / "mit-csail.clf");
    ASSERT_TRUE(log.ok()) << log.status().message();
    Result<std::vector<StampedScan>> scans = ScansFromLog(*log, "mit-csail.clf");
    ASSERT_TRUE(scans.ok());
    scans_ = std::move(*scans);
    scans_.resize(kScans);
  }
  std::vector<StampedScan> scans_;
};

// Mean translational / rotational relation error over the relations whose two timestamps are
// among 'trajectory' (a minimal version of eval's metric, which mapping may not depend on).
std::pair<double, double> RelationError(const std::vector<StampedPose>& trajectory, int* count) {
  std::ifstream in(DataDir() / "mit-csail.relations");
  std::string line;
  double trans = 0.0, rot = 0.0;
  *count = 0;
  auto find = [&trajectory](double t) -> const Pose2* {
    for (const StampedPose& p : trajectory) {
      if (std::abs(p.timestamp - t) < 1e-3) return &p.pose;
    }
    return nullptr;
  };
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    double t1, t2, dx, dy, dz, roll, pitch, dyaw;
    if (!(fields >> t1 >> t2 >> dx >> dy >> dz >> roll >> pitch >> dyaw)) continue;
    const Pose2* a = find(t1);
    const Pose2* b = find(t2);
    if (a == nullptr || b == nullptr) continue;
    const Pose2 estimate = a->Between(*b);
    trans += std::hypot(estimate.x - dx, estimate.y - dy);
    rot += std::abs(AngleDifference(estimate.theta, dyaw));
    ++*count;
  }
  return {trans / *count, RadToDeg(rot / *count)};
}

TEST_F(MitCsailSmokeTest, FirstScansMatchTheRelations) {
  SlamOptions options;
  options.rbpf.particles = 8;
  options.rbpf.threads = 2;
  const SlamResult result = RunSlam(scans_, options);
  ASSERT_EQ(result.trajectory.size(), kScans);
  int count = 0;
  const auto [trans, rot] = RelationError(result.trajectory, &count);
  EXPECT_GT(count, 100);
  EXPECT_LT(trans, 0.04);
  EXPECT_LT(rot, 0.6);
}

TEST_F(MitCsailSmokeTest, ParticlesShareTheirMaps) {
  RbpfOptions options;
  options.particles = 16;
  options.threads = 2;
  options.linear_update_meters = 0.5;
  options.angular_update_radians = 0.25;
  RbpfSlam slam(options);
  for (std::size_t i = 0; i < kScans; ++i) slam.AddScan(scans_[i], static_cast<int>(i));
  std::vector<const OccupancyGrid*> maps;
  std::size_t separately = 0;
  for (const Particle& p : slam.particles()) {
    maps.push_back(p.map.get());
    separately += UniquePatchBytes({p.map.get()});
  }
  // Every particle's map covers the whole explored area, but together they hold less than half
  // of N separate maps (a scan rewrites the patches along its beams, up to 30 m, so particles
  // differ in those between resamplings).
  const std::size_t together = UniquePatchBytes(maps);
  EXPECT_LT(together * 2, separately);
  EXPECT_LT(together,
            slam.particles().size() / 2 * UniquePatchBytes({slam.BestParticle().map.get()}));
}

}  // namespace
}  // namespace semchain::mapping
