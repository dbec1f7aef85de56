// SLAM on the simulator's mapping runs of every bundled world: the trajectory must match the
// truth (ATE <= 0.05 m) and the map must agree with the world's surfaces, which a map
// whose loop failed to close (doubled walls) does not.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "eval/ate.h"
#include "io/carmen.h"
#include "io/trajectory_io.h"
#include "mapping/map_io.h"
#include "mapping/slam_pipeline.h"
#include "sim/scene.h"
#include "sim/simulator.h"
#include "sim/world_io.h"

namespace semchain {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kSeed = 11;

class SlamWorldsTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    run_ = fs::temp_directory_path() /
           ("semchain_slam_e2e_" + std::to_string(::getpid()) + "_" + GetParam());
    fs::remove_all(run_);
  }
  void TearDown() override { fs::remove_all(run_); }
  fs::path run_;
};

// The fraction of the map's occupied cells whose centre lies within 'tolerance' of a surface of
// the world (any height: the lidar sees walls and the solids crossing its plane).
double FractionOfOccupiedCellsOnSurfaces(const mapping::MapImage& map, const sim::Scene& scene,
                                         double tolerance) {
  int occupied = 0;
  int on_surface = 0;
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      if (map.At(x, y) != 100) continue;
      ++occupied;
      const Eigen::Vector2d center(map.origin.x() + (x + 0.5) * map.resolution,
                                   map.origin.y() + (y + 0.5) * map.resolution);
      if (scene.IsOccupied(center, tolerance)) ++on_surface;
    }
  }
  return occupied == 0 ? 0.0 : static_cast<double>(on_surface) / occupied;
}

TEST_P(SlamWorldsTest, MappingRunGivesAccurateTrajectoryAndConsistentMap) {
  const Result<sim::World> world =
      sim::LoadWorld(fs::path(SEMCHAIN_SOURCE_DIR) / "worlds" / (GetParam() + ".yaml"));
  ASSERT_TRUE(world.ok()) << world.status().message();
  sim::SimulationOptions simulation;
  simulation.seed = kSeed;
  simulation.write_frames = false;
  simulation.show_progress = false;
  ASSERT_TRUE(sim::Simulate(*world, simulation, run_).ok());

  const Result<carmen::Log> log = carmen::ReadLog(run_ / "log.clf");
  ASSERT_TRUE(log.ok()) << log.status().message();
  const auto scans = mapping::ScansFromLog(*log, "log.clf");
  ASSERT_TRUE(scans.ok()) << scans.status().message();
  mapping::SlamOptions options;
  options.rbpf.seed = kSeed;
  const mapping::SlamResult slam = mapping::RunSlam(*scans, options);

  const auto truth = ReadTrajectory(run_ / "truth.txt");
  ASSERT_TRUE(truth.ok()) << truth.status().message();
  const auto ate = eval::EvaluateAte(slam.trajectory, *truth);
  ASSERT_TRUE(ate.ok()) << ate.status().message();
  EXPECT_EQ(ate->matched, truth->size());  // a pose for every scan
  EXPECT_LE(ate->ate_rmse_m, 0.05);
  EXPECT_LE(ate->rot_rmse_deg, 1.0);

  const sim::Scene scene(*world);
  const mapping::MapImage map = mapping::GridToMapImage(slam.map);
  EXPECT_GE(FractionOfOccupiedCellsOnSurfaces(map, scene, 0.1), 0.95);
}

INSTANTIATE_TEST_SUITE_P(BundledWorlds, SlamWorldsTest,
                         ::testing::Values("two_similar_rooms", "two_similar_rooms_changed",
                                           "long_corridor", "lab_loop", "low_obstacles"),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace
}  // namespace semchain
