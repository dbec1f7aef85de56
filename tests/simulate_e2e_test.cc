// Whole simulation runs of a bundled world: reproducible to the byte from the seed, and readable
// by the CARMEN reader that SLAM uses.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>

#include "core/angles.h"
#include "core/atomic_file.h"
#include "io/carmen.h"
#include "io/detections_io.h"
#include "io/trajectory_io.h"
#include "sim/simulator.h"
#include "sim/world_io.h"

namespace semchain::sim {
namespace {

namespace fs = std::filesystem;

World TwoSimilarRooms() {
  const Result<World> world =
      LoadWorld(fs::path(SEMCHAIN_SOURCE_DIR) / "worlds" / "two_similar_rooms.yaml");
  EXPECT_TRUE(world.ok()) << world.status().message();
  return world.ok() ? *world : World{};
}

// A trial run (one turn in place, then a metre ahead) with frames: short, yet every file.
SimulationOptions TrialOptions(std::uint64_t seed) {
  SimulationOptions options;
  options.seed = seed;
  options.route.kind = RouteSpec::Kind::kTrial;
  options.start = Pose2(3.0, 3.5, 0.5);  // in room A
  options.show_progress = false;
  return options;
}

// Relative path → contents of every file under 'dir'.
std::map<std::string, std::string> ReadTree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const Result<std::string> contents = ReadFile(entry.path());
    EXPECT_TRUE(contents.ok());
    files[fs::relative(entry.path(), dir).string()] = contents.ok() ? *contents : "";
  }
  return files;
}

fs::path Fresh(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("semchain_e2e_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  return dir;
}

TEST(SimulateE2eTest, SameSeedGivesAByteIdenticalRunDirectory) {
  const World world = TwoSimilarRooms();
  const fs::path a = Fresh("seed7_a"), b = Fresh("seed7_b"), c = Fresh("seed8");
  ASSERT_TRUE(Simulate(world, TrialOptions(7), a).ok());
  ASSERT_TRUE(Simulate(world, TrialOptions(7), b).ok());
  ASSERT_TRUE(Simulate(world, TrialOptions(8), c).ok());
  const auto files_a = ReadTree(a), files_b = ReadTree(b), files_c = ReadTree(c);
  EXPECT_GT(files_a.size(), 10u);
  ASSERT_EQ(files_a.size(), files_b.size());
  for (const auto& [name, contents] : files_a) {
    ASSERT_TRUE(files_b.count(name)) << name;
    EXPECT_TRUE(contents == files_b.at(name)) << name << " differs between two runs of seed 7";
  }
  for (const char* name : {"log.clf", "detections.jsonl"}) {
    EXPECT_NE(files_a.at(name), files_c.at(name)) << name << " is the same for seeds 7 and 8";
  }
  // The truth does not depend on the noise seed.
  EXPECT_EQ(files_a.at("truth.txt"), files_c.at("truth.txt"));
  for (const fs::path& dir : {a, b, c}) fs::remove_all(dir);
}

TEST(SimulateE2eTest, LogReadsBackWithTheLidarLayout) {
  const World world = TwoSimilarRooms();
  SimulationOptions options = TrialOptions(3);
  options.write_frames = false;
  const fs::path run = Fresh("read_back");
  ASSERT_TRUE(Simulate(world, options, run).ok());
  const auto log = carmen::ReadLog(run / "log.clf");
  ASSERT_TRUE(log.ok()) << log.status().message();
  const auto truth = ReadTrajectory(run / "truth.txt");
  ASSERT_TRUE(truth.ok()) << truth.status().message();
  const auto lasers = log->Lasers();
  ASSERT_EQ(lasers.size(), truth->size());
  // A full turn at 0.8 rad/s and a metre at up to 0.4 m/s: about 8 s + 3 s at 10 Hz.
  EXPECT_GT(lasers.size(), 100u);
  for (std::size_t i = 0; i < lasers.size(); ++i) {
    const LaserScan& scan = lasers[i]->scan.scan;
    // The bundled worlds' lidar: 359 beams 1 degree apart, centred on the heading.
    ASSERT_EQ(scan.size(), 359u);
    EXPECT_NEAR(scan.angle_min, DegToRad(-179.0), 1e-9);
    EXPECT_NEAR(scan.angle_increment, DegToRad(1.0), 1e-9);
    EXPECT_DOUBLE_EQ(scan.max_range, 12.0);
    EXPECT_EQ(lasers[i]->kind, carmen::Laser::Kind::kRobotLaser1);
    EXPECT_DOUBLE_EQ(lasers[i]->stamp.timestamp, (*truth)[i].timestamp);
  }
  // Odometry starts at the true start pose.
  const auto odometry = log->Odometries();
  ASSERT_FALSE(odometry.empty());
  EXPECT_DOUBLE_EQ(odometry.front()->pose.x, 3.0);
  EXPECT_DOUBLE_EQ(odometry.front()->pose.y, 3.5);
  EXPECT_DOUBLE_EQ(odometry.front()->pose.theta, 0.5);
  fs::remove_all(run);
}

}  // namespace
}  // namespace semchain::sim
