// Bag-of-words place recognition and occlusion immunity end to end (seed 000 §3.1 steps 1–4,
// §4.2; DESIGN.md §3.7), in the simulator's look-alike rooms:
//   1. a vocabulary trained on the frames of a mapping run of two_similar_rooms, every frame a
//      keyframe at its true pose; a second pass along the mapping route shifted by 0.16 m and
//      started half a frame later queries each of its frames; the best keyframe is right when
//      within 1.0 m and 30° of the query's true pose: precision and recall;
//   2. the semantic map of the mapping run (simulate → slam → semantic); a run in
//      two_similar_rooms_changed, where a column hides room A's bucket: in the frames that see
//      cabinet and chair of room A with the bucket in the field of view but not detected, the
//      best keyframe's class vector must name the bucket and its chain node.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "bow/bow_occlusion.h"
#include "bow/bow_vocabulary_io.h"
#include "bow/keyframe_recognizer.h"
#include "bow/run_features.h"
#include "core/angles.h"
#include "io/carmen.h"
#include "io/detections_io.h"
#include "io/rgbd_frame_io.h"
#include "io/trajectory_io.h"
#include "io/trajectory_lookup.h"
#include "mapping/slam_pipeline.h"
#include "semantic/semantic_run.h"
#include "sim/simulator.h"
#include "sim/world_io.h"

namespace semchain {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxDistance = 1.0;                           // metres
constexpr double kMaxAngle = 30.0 * std::numbers::pi / 180.0;  // radians

sim::World LoadBundledWorld(const std::string& name) {
  const Result<sim::World> world =
      sim::LoadWorld(fs::path(SEMCHAIN_SOURCE_DIR) / "worlds" / (name + ".yaml"));
  SEMCHAIN_CHECK(world.ok());
  return *world;
}

void SimulateRun(const sim::World& world, const sim::SimulationOptions& options,
                 const fs::path& run) {
  const Status status = sim::Simulate(world, options, run);
  ASSERT_TRUE(status.ok()) << status.message();
}

// A run's frames with their detections and true poses.
struct RunFrames {
  std::vector<FrameDetections> frames;
  std::vector<Pose2> truth;
  std::vector<cv::Mat> descriptors;
};

RunFrames LoadRunFrames(const fs::path& run) {
  RunFrames out;
  Result<std::vector<FrameDetections>> frames = ReadDetectionsJsonl(run / "detections.jsonl");
  Result<std::vector<StampedPose>> truth = ReadTrajectory(run / "truth.txt");
  SEMCHAIN_CHECK(frames.ok() && truth.ok());
  const TrajectoryLookup lookup(*truth);
  std::vector<fs::path> images;
  for (const FrameDetections& frame : *frames) {
    const std::optional<Pose2> pose = lookup.Nearest(frame.stamp, 0.02);
    SEMCHAIN_CHECK(pose.has_value());
    out.truth.push_back(*pose);
    images.push_back(ColorImagePath(run, frame.frame));
  }
  Result<std::vector<cv::Mat>> descriptors =
      bow::ExtractImageDescriptors(images, bow::OrbOptions());
  SEMCHAIN_CHECK(descriptors.ok());
  out.frames = std::move(*frames);
  out.descriptors = std::move(*descriptors);
  return out;
}

bool Near(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y) <= kMaxDistance &&
         std::abs(NormalizeAngle(a.theta - b.theta)) <= kMaxAngle;
}

class BowEndToEndTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() /
                         ("semchain_bow_e2e_" + std::to_string(::getpid())));
    fs::remove_all(*root_);
    sim::SimulationOptions options;
    options.seed = 1;
    options.show_progress = false;
    SimulateRun(LoadBundledWorld("two_similar_rooms"), options, *root_ / "mapping");
    mapping_ = new RunFrames(LoadRunFrames(*root_ / "mapping"));
    bow::VocabularyOptions vocabulary_options;
    vocabulary_options.seed = 1;
    Result<bow::Vocabulary> vocabulary =
        bow::Vocabulary::Train(mapping_->descriptors, vocabulary_options);
    SEMCHAIN_CHECK(vocabulary.ok());
    vocabulary_ = new bow::Vocabulary(*vocabulary);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
    delete mapping_;
    delete vocabulary_;
  }

  static fs::path* root_;
  static RunFrames* mapping_;
  static bow::Vocabulary* vocabulary_;
};

fs::path* BowEndToEndTest::root_ = nullptr;
RunFrames* BowEndToEndTest::mapping_ = nullptr;
bow::Vocabulary* BowEndToEndTest::vocabulary_ = nullptr;

TEST_F(BowEndToEndTest, SecondPassPrecisionAndRecall) {
  const sim::World world = LoadBundledWorld("two_similar_rooms");
  // The mapping route shifted by (0.1, 0.12) m, started 0.1 m behind its first waypoint so that
  // frames fall between the first pass's.
  sim::SimulationOptions options;
  options.seed = 2;
  options.show_progress = false;
  options.route.kind = sim::RouteSpec::Kind::kWaypoints;
  for (const Eigen::Vector2d& p : world.mapping_route) {
    options.route.waypoints.push_back(p + Eigen::Vector2d(0.1, 0.12));
  }
  options.start = Pose2(world.mapping_route[0].x(), world.mapping_route[0].y() + 0.12, 0.0);
  SimulateRun(world, options, *root_ / "second");
  const RunFrames second = LoadRunFrames(*root_ / "second");

  semantic::KeyframeDatabase keyframes;
  for (std::size_t i = 0; i < mapping_->frames.size(); ++i) {
    semantic::Keyframe keyframe;
    keyframe.frame = mapping_->frames[i].frame;
    keyframe.pose = mapping_->truth[i];
    keyframes.keyframes.push_back(keyframe);
  }
  const bow::KeyframeRecognizer recognizer =
      bow::KeyframeRecognizer::FromDescriptors(*vocabulary_, keyframes, mapping_->descriptors, {});

  struct Retrieval {
    double score;
    bool correct;
  };
  std::vector<Retrieval> retrievals;
  int positives = 0;  // queries with a keyframe within 1 m and 30°
  for (std::size_t q = 0; q < second.frames.size(); ++q) {
    const bool has_true_match =
        std::any_of(mapping_->truth.begin(), mapping_->truth.end(),
                    [&](const Pose2& p) { return Near(p, second.truth[q]); });
    positives += has_true_match ? 1 : 0;
    const auto best = recognizer.QueryDescriptors(second.descriptors[q], 1);
    if (best.empty()) continue;
    const Pose2& found = recognizer.keyframe(best[0].keyframe).pose;
    retrievals.push_back({best[0].score, Near(found, second.truth[q])});
    if (!retrievals.back().correct) {
      std::printf(
          "wrong: query %s at (%.2f, %.2f, %.0f°) -> keyframe at (%.2f, %.2f, %.0f°), "
          "score %.3f\n",
          second.frames[q].frame.c_str(), second.truth[q].x, second.truth[q].y,
          second.truth[q].theta * 180 / std::numbers::pi, found.x, found.y,
          found.theta * 180 / std::numbers::pi, best[0].score);
    }
  }
  ASSERT_GT(positives, 200);
  const auto precision_recall = [&](double threshold) {
    int accepted = 0, correct = 0;
    for (const Retrieval& r : retrievals) {
      if (r.score < threshold) continue;
      ++accepted;
      correct += r.correct ? 1 : 0;
    }
    return std::pair<double, double>(accepted == 0 ? 1.0 : double(correct) / accepted,
                                     double(correct) / positives);
  };
  for (double threshold : {0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3}) {
    const auto [precision, recall] = precision_recall(threshold);
    std::printf("score >= %.2f: precision %.3f recall %.3f (%zu queries, %d with a true match)\n",
                threshold, precision, recall, second.frames.size(), positives);
  }
  // Measured: precision 0.991, recall 0.991 at 0.1; the misses are room B frames facing the
  // dividing wall, whose two sides share one texture, matched to room A frames facing it.
  const auto [precision, recall] = precision_recall(0.1);
  EXPECT_GE(precision, 0.97);
  EXPECT_GE(recall, 0.95);
}

// The files a localizer loads: the vocabulary file and MAP/keyframes.json with the run's frames.
TEST_F(BowEndToEndTest, LoadedRecognizerFindsTheFrameItself) {
  const fs::path vocabulary = *root_ / "vocab.bin";
  const fs::path keyframes_json = *root_ / "keyframes.json";
  ASSERT_TRUE(bow::WriteVocabulary(vocabulary, *vocabulary_).ok());
  semantic::KeyframeDatabase keyframes;
  keyframes.run = (*root_ / "mapping").string();
  for (std::size_t i = 0; i < 40; ++i) {
    semantic::Keyframe keyframe;
    keyframe.frame = mapping_->frames[i * 8].frame;
    keyframe.pose = mapping_->truth[i * 8];
    keyframes.keyframes.push_back(keyframe);
  }
  ASSERT_TRUE(semantic::WriteKeyframes(keyframes_json, keyframes).ok());
  const Result<bow::KeyframeRecognizer> recognizer =
      bow::LoadKeyframeRecognizer(vocabulary, keyframes_json);
  ASSERT_TRUE(recognizer.ok()) << recognizer.status().message();
  ASSERT_EQ(recognizer->database().size(), 40);
  for (int k : {0, 13, 39}) {
    const auto best = recognizer->QueryDescriptors(mapping_->descriptors[k * 8], 1);
    ASSERT_EQ(best.size(), 1u);
    EXPECT_EQ(best[0].keyframe, k);
    EXPECT_NEAR(best[0].score, 1.0, 1e-9);
  }
  const Result<bow::KeyframeRecognizer> missing =
      bow::LoadKeyframeRecognizer(vocabulary, *root_ / "none.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("none.json"), std::string::npos);
}

// The id of the mapped object of class 'name' nearest to 'where' (within 0.3 m), or -1.
int MappedId(const semantic::SemanticMap& map, const std::string& name,
             const Eigen::Vector2d& where) {
  int id = -1;
  double best = 0.3;
  for (const semantic::SemanticObject& object : map.objects) {
    const double d = (object.center - where).norm();
    if (object.class_name == name && d <= best) {
      id = object.id;
      best = d;
    }
  }
  return id;
}

bool Detected(const FrameDetections& frame, const std::string& name) {
  return std::any_of(frame.detections.begin(), frame.detections.end(),
                     [&](const Detection& d) { return d.class_name == name; });
}

TEST_F(BowEndToEndTest, OccludedBucketInTheChangedWorld) {
  // Semantic map of the unchanged world from the mapping run: slam, then semantic mapping.
  const fs::path mapping_run = *root_ / "mapping";
  const Result<carmen::Log> log = carmen::ReadLog(mapping_run / "log.clf");
  ASSERT_TRUE(log.ok());
  const auto scans = mapping::ScansFromLog(*log, "log.clf");
  ASSERT_TRUE(scans.ok());
  mapping::SlamOptions slam_options;
  slam_options.rbpf.seed = 1;
  // 10 particles instead of 30: the same result below (8 of 11, the same misses) in less time,
  // which keeps this test under a minute on a loaded machine.
  slam_options.rbpf.particles = 10;
  const mapping::SlamResult slam = mapping::RunSlam(*scans, slam_options);
  semantic::SemanticRunInputs inputs;
  inputs.run_dir = mapping_run;
  inputs.occupancy = mapping::GridToMapImage(slam.map);
  inputs.trajectory = slam.trajectory;
  const Result<semantic::SemanticMappingResult> mapped =
      semantic::MapRun(inputs, semantic::SemanticMapOptions());
  ASSERT_TRUE(mapped.ok()) << mapped.status().message();
  const semantic::SemanticMap& map = mapped->map;

  const sim::World world = LoadBundledWorld("two_similar_rooms");
  const Eigen::Vector2d bucket_center = world.objects[3].footprint.center;
  ASSERT_EQ(world.objects[3].class_name, "bucket");
  const int bucket = MappedId(map, "bucket", bucket_center);
  const int cabinet = MappedId(map, "cabinet", world.objects[2].footprint.center);
  const int chair = MappedId(map, "chair", world.objects[4].footprint.center);
  ASSERT_GE(bucket, 0);
  ASSERT_GE(cabinet, 0);
  ASSERT_GE(chair, 0);

  // The keyframes of semantic mapping, described by the mapping run's descriptors.
  semantic::KeyframeDatabase keyframes;
  keyframes.run = mapping_run.string();
  std::vector<cv::Mat> descriptors;
  for (const semantic::Keyframe& keyframe : mapped->keyframes) {
    const auto it = std::find_if(mapping_->frames.begin(), mapping_->frames.end(),
                                 [&](const auto& f) { return f.frame == keyframe.frame; });
    ASSERT_NE(it, mapping_->frames.end());
    descriptors.push_back(mapping_->descriptors[it - mapping_->frames.begin()]);
    keyframes.keyframes.push_back(keyframe);
  }
  const bow::KeyframeRecognizer recognizer =
      bow::KeyframeRecognizer::FromDescriptors(*vocabulary_, keyframes, descriptors, {});

  // Runs in the changed world: its mapping route and 12 trials (a full turn in place, then a
  // short drive) from seeded random poses inside room A's mapping loop. Scored: frames in room A
  // that see cabinet and chair, have the bucket inside the field of view (25° of the 30°
  // half-angle, within range) and do not detect it.
  const sim::World changed = LoadBundledWorld("two_similar_rooms_changed");
  std::vector<sim::SimulationOptions> runs(13);
  Rng rng = MakeRng(4);
  std::uniform_real_distribution<double> x(1.0, 4.6), y(2.2, 4.6), theta(-3.14159, 3.14159);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    runs[r].seed = 3 + r;
    runs[r].show_progress = false;
    if (r == 0) continue;
    runs[r].route.kind = sim::RouteSpec::Kind::kTrial;
    // One draw a statement, θ first: argument order is unspecified (GCC's, last to first).
    const double start_theta = theta(rng), start_y = y(rng), start_x = x(rng);
    runs[r].start = Pose2(start_x, start_y, start_theta);
  }
  constexpr int kRanked = 5;  // bag-of-words matches the inference may choose from
  int frames = 0, named = 0, correct = 0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const fs::path run = *root_ / ("changed_" + std::to_string(r));
    SimulateRun(changed, runs[r], run);
    const RunFrames live = LoadRunFrames(run);
    for (std::size_t q = 0; q < live.frames.size(); ++q) {
      const Pose2& pose = live.truth[q];
      const Eigen::Vector2d to_bucket = bucket_center - Eigen::Vector2d(pose.x, pose.y);
      const double bearing = NormalizeAngle(std::atan2(to_bucket.y(), to_bucket.x()) - pose.theta);
      const bool in_room_a = pose.x < 6.0 && pose.y > 1.4;
      const bool in_view = std::abs(bearing) < 25.0 * std::numbers::pi / 180.0 &&
                           to_bucket.norm() < changed.robot.camera.max_range;
      const FrameDetections& frame = live.frames[q];
      if (!in_room_a || !in_view || Detected(frame, "bucket") || !Detected(frame, "cabinet") ||
          !Detected(frame, "chair")) {
        continue;
      }
      ++frames;
      bow::OcclusionQueryOptions occlusion;
      occlusion.candidates = kRanked;
      const bow::OcclusionQuery query = bow::QueryOccludedObjects(
          recognizer, map, live.descriptors[q], frame.detections, occlusion);
      if (query.inference.used < 0) continue;
      const bow::OcclusionInference& inference = query.inference.inference;
      const bool names_bucket = std::any_of(inference.occluded.begin(), inference.occluded.end(),
                                            [](const auto& o) { return o.class_name == "bucket"; });
      const bool right_node =
          std::any_of(inference.occluded.begin(), inference.occluded.end(), [&](const auto& o) {
            return o.id == bucket && ((o.upstream == cabinet && o.downstream == chair) ||
                                      (o.upstream == chair && o.downstream == cabinet));
          });
      named += names_bucket ? 1 : 0;
      correct += right_node ? 1 : 0;
      if (!right_node) {
        std::printf("missed: run %zu %s at (%.2f, %.2f, %.0f°) -> keyframe %s: %s\n", r,
                    frame.frame.c_str(), pose.x, pose.y, pose.theta * 180 / std::numbers::pi,
                    recognizer.keyframe(query.matches[query.inference.used].keyframe).frame.c_str(),
                    inference.reason.c_str());
      }
    }
  }
  std::printf(
      "occluded bucket: %d frames, bucket named in %d, bucket node and neighbours right "
      "in %d (%.3f)\n",
      frames, named, correct, frames == 0 ? 0.0 : double(correct) / frames);
  // Measured: 11 frames, the bucket and its node (with cabinet and chair as neighbours) right
  // in 8 (0.727; 6 of 11 when only the single most similar keyframe is used). The misses: the
  // keyframe chosen shows the door too, or the bucket was not detected in it during mapping.
  ASSERT_GE(frames, 10);
  EXPECT_GE(double(correct) / frames, 0.7);
  EXPECT_EQ(named, correct);  // whenever a bucket is named, it is the right node
}

}  // namespace
}  // namespace semchain
