// One result, not two: the semantic map grown while SLAM runs (`slam --semantic`)
// equals `slam` followed by `semantic` on the same final trajectory — every object with the
// same class and its centre within 0.02 m, the same chains — also when the trajectory is
// corrected late (a loop closing), after the last correction; and it scores as the batch map
// does against the world.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/carmen.h"
#include "mapping/map_io.h"
#include "mapping/slam_pipeline.h"
#include "semantic/live_semantic_run.h"
#include "semantic/semantic_run.h"
#include "sim/simulator.h"
#include "sim/world_io.h"
#include "testing/truth_maps.h"

namespace semchain {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kSeed = 11;

std::unique_ptr<semantic::LiveSemanticRun> OpenLive(const fs::path& run,
                                                    std::vector<std::string>* warnings) {
  semantic::GridGeometry lattice;
  lattice.resolution = mapping::OccupancyGridOptions().resolution_meters;
  auto live = semantic::LiveSemanticRun::Open(
      run, std::nullopt, lattice, semantic::LiveSemanticOptions(),
      [warnings](const std::string& line) { warnings->push_back(line); });
  EXPECT_TRUE(live.ok()) << live.status().message();
  return live.ok() ? std::move(*live) : nullptr;
}

semantic::SemanticMappingResult Batch(const fs::path& run, const mapping::MapImage& map,
                                      const std::vector<StampedPose>& trajectory) {
  semantic::SemanticRunInputs inputs;
  inputs.run_dir = run;
  inputs.occupancy = map;
  inputs.trajectory = trajectory;
  const auto result = semantic::MapRun(inputs, semantic::SemanticMapOptions());
  EXPECT_TRUE(result.ok()) << result.status().message();
  return result.ok() ? *result : semantic::SemanticMappingResult();
}

// Objects paired by class and nearest centre; chains compared through the pairing.
void ExpectSameMap(const semantic::SemanticMap& live, const semantic::SemanticMap& batch) {
  ASSERT_EQ(live.objects.size(), batch.objects.size());
  std::map<int, int> live_to_batch;
  for (const semantic::SemanticObject& a : live.objects) {
    const semantic::SemanticObject* nearest = nullptr;
    for (const semantic::SemanticObject& b : batch.objects) {
      if (b.class_name != a.class_name) continue;
      if (!nearest || (b.center - a.center).norm() < (nearest->center - a.center).norm())
        nearest = &b;
    }
    ASSERT_NE(nearest, nullptr) << "no " << a.class_name << " in the batch map";
    EXPECT_LE((nearest->center - a.center).norm(), 0.02) << a.class_name << " " << a.id;
    live_to_batch[a.id] = nearest->id;
  }
  ASSERT_EQ(live.chains.size(), batch.chains.size());
  for (std::size_t c = 0; c < live.chains.size(); ++c) {
    std::vector<int> mapped;
    for (const int id : live.chains[c].order) mapped.push_back(live_to_batch[id]);
    EXPECT_EQ(mapped, batch.chains[c].order) << "chain " << c;
  }
  EXPECT_EQ(live.neighbours.size(), batch.neighbours.size());
}

// Precision, recall and mean centre error against the world (as semantic_worlds_e2e_test).
void ExpectQuality(const semantic::SemanticMap& map, const sim::World& world,
                   const std::string& name) {
  std::vector<bool> taken(world.objects.size(), false);
  int matched = 0;
  double error = 0.0;
  for (const semantic::SemanticObject& object : map.objects) {
    int best = -1;
    for (std::size_t j = 0; j < world.objects.size(); ++j) {
      const double d = (object.center - world.objects[j].footprint.center).norm();
      if (taken[j] || world.objects[j].class_name != object.class_name || d > 0.3) continue;
      if (best < 0 || d < (world.objects[best].footprint.center - object.center).norm())
        best = static_cast<int>(j);
    }
    if (best < 0) continue;
    taken[static_cast<std::size_t>(best)] = true;
    ++matched;
    error +=
        (object.center - world.objects[static_cast<std::size_t>(best)].footprint.center).norm();
  }
  const double precision =
      map.objects.empty() ? 0.0 : double(matched) / static_cast<double>(map.objects.size());
  const double recall = double(matched) / static_cast<double>(world.objects.size());
  const double mean_error = matched == 0 ? 1e9 : error / matched;
  std::printf("%s live: %zu objects, precision %.3f recall %.3f mean centre error %.3f m\n",
              name.c_str(), map.objects.size(), precision, recall, mean_error);
  EXPECT_GE(precision, 0.97);
  EXPECT_GE(recall, 0.97);
  EXPECT_LE(mean_error, 0.08);
}

// One simulated mapping run of two_similar_rooms (two look-alike rooms and a corridor) for
// the tests below.
class LiveSemanticTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    run_ = new fs::path(fs::temp_directory_path() /
                        ("semchain_live_e2e_" + std::to_string(::getpid())));
    fs::remove_all(*run_);
    const auto world =
        sim::LoadWorld(fs::path(SEMCHAIN_SOURCE_DIR) / "worlds" / "two_similar_rooms.yaml");
    ASSERT_TRUE(world.ok()) << world.status().message();
    world_ = new sim::World(*world);
    sim::SimulationOptions simulation;
    simulation.seed = kSeed;
    simulation.show_progress = false;
    const Status simulated = sim::Simulate(*world_, simulation, *run_);
    ASSERT_TRUE(simulated.ok()) << simulated.message();
  }
  static void TearDownTestSuite() {
    fs::remove_all(*run_);
    delete run_;
    delete world_;
  }

  static fs::path* run_;
  static sim::World* world_;
};

fs::path* LiveSemanticTest::run_ = nullptr;
sim::World* LiveSemanticTest::world_ = nullptr;

// SLAM with the semantic mapper fed as it runs, against `semantic` on SLAM's final output.
TEST_F(LiveSemanticTest, OnePassEqualsSlamThenSemantic) {
  const auto log = carmen::ReadLog(*run_ / "log.clf");
  ASSERT_TRUE(log.ok());
  const auto scans = mapping::ScansFromLog(*log, "log.clf");
  ASSERT_TRUE(scans.ok());
  std::vector<std::string> warnings;
  auto live = OpenLive(*run_, &warnings);
  ASSERT_NE(live, nullptr);
  mapping::SlamOptions options;
  options.rbpf.seed = kSeed;
  Status fed = Status::Ok();
  const mapping::SlamResult slam =
      mapping::RunSlam(*scans, options, {}, [&](const mapping::SlamStep& step) {
        const double stamp = (*step.scans)[step.scan].scan.timestamp;
        if (!fed.ok() || (!step.processed && live->next_stamp() > stamp)) return;
        fed = live->Advance(step.source->Trajectory(), step.processed, [&step] {
          return mapping::GridToMapImage(*step.slam->BestParticle().map);
        });
      });
  ASSERT_TRUE(fed.ok()) << fed.message();
  const mapping::MapImage map = mapping::GridToMapImage(slam.map);
  const auto result = live->Finish(slam.trajectory, map);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_EQ(result->skipped_frames, 0);
  const semantic::SemanticMappingResult batch = Batch(*run_, map, slam.trajectory);
  ExpectSameMap(result->mapping.map, batch.map);
  EXPECT_EQ(result->mapping.keyframes.size(), batch.keyframes.size());
  ExpectQuality(result->mapping.map, *world_, "two_similar_rooms");
  const semantic::SemanticMapperStatistics& s = result->statistics;
  std::printf(
      "two_similar_rooms: %zu frames, %d re-projections (%d incremental, %d frames, "
      "%.3f s)\n",
      s.frame_seconds.size(), s.reprojections, s.incremental_reprojections, s.reprojected_frames,
      s.reprojection_seconds);
  // Every object was seen by some frame, and the growth ends with the final count.
  for (const double stamp : result->first_seen_stamp) EXPECT_GE(stamp, 0.0);
  ASSERT_FALSE(result->growth.empty());
  EXPECT_EQ(result->growth.back().objects, static_cast<int>(result->mapping.map.objects.size()));
}

// A loop closing late: at three quarters of the run the second half of the trajectory moves
// (0.15 m and 2°); the mapper re-projects what moved, incrementally, and after the last
// correction equals `semantic` on the corrected trajectory.
TEST_F(LiveSemanticTest, LateCorrectionEqualsBatchOnTheCorrectedTrajectory) {
  const fs::path& run = *run_;
  const sim::World* world = world_;
  // The simulator's truth as SLAM's trajectory: the test is about the mapper, not SLAM.
  const auto truth = ReadTrajectory(run / "truth.txt");
  ASSERT_TRUE(truth.ok()) << truth.status().message();
  const std::vector<StampedPose>& original = *truth;
  std::vector<StampedPose> corrected = original;
  const Pose2 shift(0.15, -0.1, 2.0 * M_PI / 180.0);
  for (std::size_t i = original.size() / 2; i < original.size(); ++i)
    corrected[i].pose = shift * original[i].pose;

  std::vector<std::string> warnings;
  auto live = OpenLive(run, &warnings);
  ASSERT_NE(live, nullptr);
  const std::size_t closure = 3 * original.size() / 4;
  for (std::size_t n = 1; n <= original.size(); n += 5) {
    const std::vector<StampedPose>& source = n < closure ? original : corrected;
    const std::vector<StampedPose> prefix(source.begin(), source.begin() + static_cast<long>(n));
    ASSERT_TRUE(live->Advance(prefix, /*corrected=*/true, {}).ok());
  }
  const mapping::MapImage map = e2e::MapsFromTruth(*world).occupancy;
  const auto result = live->Finish(corrected, map);
  ASSERT_TRUE(result.ok()) << result.status().message();
  const semantic::SemanticMapperStatistics& s = result->statistics;
  std::printf("late correction: %d re-projections (%d incremental, %d frames, %.3f s)\n",
              s.reprojections, s.incremental_reprojections, s.reprojected_frames,
              s.reprojection_seconds);
  EXPECT_GE(s.incremental_reprojections, 1);
  const semantic::SemanticMappingResult batch = Batch(run, map, corrected);
  ExpectSameMap(result->mapping.map, batch.map);
}

}  // namespace
}  // namespace semchain
