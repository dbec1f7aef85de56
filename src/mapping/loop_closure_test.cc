#include "mapping/loop_closure.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "core/angles.h"
#include "core/rng.h"
#include "mapping/incremental_slam.h"
#include "mapping/testing/synthetic_world.h"

namespace semchain::mapping {
namespace {

using testing::Segment;

// A corridor 2 m wide around a 40 m × 20 m block, with door niches and boxes scattered along
// both walls so that places differ.
std::vector<Segment> CorridorLoopWorld() {
  std::vector<Segment> world;
  auto box = [&world](double x0, double y0, double x1, double y1) {
    world.push_back({{x0, y0}, {x1, y0}});
    world.push_back({{x1, y0}, {x1, y1}});
    world.push_back({{x1, y1}, {x0, y1}});
    world.push_back({{x0, y1}, {x0, y0}});
  };
  box(-2.0, -2.0, 42.0, 22.0);  // outer wall
  box(0.0, 0.0, 40.0, 20.0);    // the block
  Rng rng = MakeRng(11);
  std::uniform_real_distribution<double> along(0.0, 1.0);
  std::uniform_real_distribution<double> size(0.2, 0.5);
  for (int k = 0; k < 60; ++k) {
    // A box against one of the eight walls.
    const int wall = k % 8;
    const double t = along(rng);
    const double s = size(rng);
    const double x = 1.0 + 38.0 * t, y = 1.0 + 18.0 * t;
    switch (wall) {
      case 0:
        box(x, -2.0, x + s, -2.0 + s);
        break;
      case 1:
        box(x, 0.0 - s, x + s, 0.0);
        break;
      case 2:
        box(x, 22.0 - s, x + s, 22.0);
        break;
      case 3:
        box(x, 20.0, x + s, 20.0 + s);
        break;
      case 4:
        box(-2.0, y, -2.0 + s, y + s);
        break;
      case 5:
        box(0.0 - s, y, 0.0, y + s);
        break;
      case 6:
        box(42.0 - s, y, 42.0, y + s);
        break;
      default:
        box(40.0, y, 40.0 + s, y + s);
        break;
    }
  }
  return world;
}

struct LoopRun {
  std::vector<LaserScan> raw;  // as the laser gave them (DriveTwoLaps)
  std::vector<PreparedScan> scans;
  std::vector<Pose2> truth;
  std::vector<Pose2> drifted;  // what a filter with a slow heading drift would give
};

// Two laps anticlockwise along the corridor's centre line, a node every 0.5 m.
LoopRun DriveTwoLaps(double drift_radians_per_meter) {
  const std::vector<Segment> world = CorridorLoopWorld();
  const std::vector<Eigen::Vector2d> corners = {{-1, -1}, {41, -1}, {41, 21}, {-1, 21}};
  LoopRun run;
  Rng rng = MakeRng(2);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int lap = 0; lap < 2; ++lap) {
    for (int side = 0; side < 4; ++side) {
      const Eigen::Vector2d a = corners[static_cast<std::size_t>(side)];
      const Eigen::Vector2d b = corners[static_cast<std::size_t>((side + 1) % 4)];
      const int steps = static_cast<int>((b - a).norm() / 0.5);
      const double heading = std::atan2(b.y() - a.y(), b.x() - a.x());
      for (int k = 0; k < steps; ++k) {
        const Eigen::Vector2d at = a + (b - a) * (static_cast<double>(k) / steps);
        run.truth.emplace_back(at.x(), at.y(), heading);
      }
    }
  }
  run.drifted.push_back(run.truth.front());
  for (std::size_t i = 0; i < run.truth.size(); ++i) {
    LaserScan scan = testing::SimulateScan(world, run.truth[i], 271, 1.5 * kPi, 30.0);
    for (double& r : scan.ranges) r += noise(rng);
    scan.timestamp = 0.25 * static_cast<double>(i);
    run.scans.push_back(PrepareScan(scan, Pose2(), {}));
    run.raw.push_back(scan);
    if (i == 0) continue;
    Pose2 step = run.truth[i - 1].Between(run.truth[i]);
    step.theta += drift_radians_per_meter * step.translation().norm();
    run.drifted.push_back(run.drifted.back() * step);
  }
  return run;
}

// Closures with the fixed loop sigmas, not covariances from their matches (match_covariance,
// on by default). Along this loop's bare corridors the match score hardly drops within the
// covariance window, so with covariances from the matches every closure away from a corner is
// loose along its corridor and the heading drift's error there stays:
// ClosingTheLoopsRemovesTheDrift ends 0.42 m off instead of under 0.3 m. The tests of verification
// and of the optimizer need closures that pull; the covariances have their own tests
// (match_covariance_test.cc), and their ±8 m window costs minutes per run of this loop under the
// sanitizers.
LoopClosureOptions SigmaClosures() {
  LoopClosureOptions options;
  options.match_covariance = false;
  return options;
}

std::vector<const PreparedScan*> Pointers(const std::vector<PreparedScan>& scans) {
  std::vector<const PreparedScan*> pointers;
  for (const PreparedScan& scan : scans) pointers.push_back(&scan);
  return pointers;
}

TEST(LoopClosureTest, ClosingTheLoopsRemovesTheDrift) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  const double before = testing::MaxPositionError(run.drifted, run.truth);
  ASSERT_GT(before, 1.5);
  const LoopClosureResult result = CloseLoops(Pointers(run.scans), run.drifted, SigmaClosures());
  const LoopClosureStatistics& stats = result.statistics;
  EXPECT_GE(stats.accepted, 5);
  EXPECT_GT(stats.searches, stats.accepted);
  for (const double residual : stats.residuals) EXPECT_LT(residual, 5.0);
  EXPECT_LT(testing::MaxPositionError(result.poses, run.truth), 0.3)
      << "before: " << before << "; " << stats.found << " found, " << stats.accepted
      << " accepted, " << stats.gated << " gated, " << stats.rejected << " rejected";
}

// With every match under min_score (it is set out of reach) but above consistent_min_score, no
// closure is added on its own score: the first one found waits, and is added with the next that
// agrees with it. Without consistent_min_score the same matches are dropped and the drift stays.
TEST(LoopClosureTest, WeakMatchesAreAddedOnlyWhenTheyAgree) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  LoopClosureOptions weak_only = SigmaClosures();
  weak_only.min_score = 1.0;
  weak_only.consistent_min_score = 0.5;
  LoopCloser closer(weak_only);
  std::size_t i = 0;
  while (i < run.scans.size() && closer.statistics().found == 0) {
    closer.AddNode(run.scans[i], run.drifted[i]);
    ++i;
  }
  ASSERT_EQ(closer.statistics().found, 1);
  EXPECT_EQ(closer.statistics().accepted, 0);
  EXPECT_EQ(closer.statistics().gated, 1);
  for (; i < run.scans.size(); ++i) closer.AddNode(run.scans[i], run.drifted[i]);
  const LoopClosureStatistics stats = closer.statistics();
  EXPECT_GE(stats.accepted, 5);
  EXPECT_LT(testing::MaxPositionError(closer.estimate(), run.truth), 0.3)
      << stats.found << " found, " << stats.accepted << " accepted, " << stats.gated
      << " held back, " << stats.rejected << " rejected";

  LoopClosureOptions dropped = weak_only;
  dropped.consistent_min_score = 0.0;
  const LoopClosureResult none = CloseLoops(Pointers(run.scans), run.drifted, dropped);
  EXPECT_EQ(none.statistics.found, 0);
  EXPECT_GT(testing::MaxPositionError(none.poses, run.truth), 1.5);
}

// The oracle (bench closures --oracle) replaces verification: a closure goes in exactly when it
// says so, whatever the gate would have made of it. Here the gate holds back every closure
// (gate_sigmas near 0, nothing to confirm it within 1 cm of travel): alone it adds none, with an
// oracle that judges by the truth every closure it found true goes in, and one that refuses
// everything leaves the filter's poses as they were (fed until it has refused three).
TEST(LoopClosureTest, AnOracleDecidesWhichClosuresGoIn) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  LoopClosureOptions held = SigmaClosures();
  held.gate_sigmas = 1e-3;
  held.confirm_within_meters = 0.01;
  const LoopClosureResult gated = CloseLoops(Pointers(run.scans), run.drifted, held);
  ASSERT_GT(gated.statistics.found, 5);
  EXPECT_EQ(gated.statistics.accepted, 0);

  int asked = 0, said_true = 0;
  LoopClosureOptions by_truth = held;
  by_truth.oracle = [&](const LoopClosureCandidate& c) {
    ++asked;
    EXPECT_TRUE(c.passed_score && c.best_of_search);
    EXPECT_GE(c.score, by_truth.min_score);
    const Pose2 truth = run.truth[static_cast<std::size_t>(c.from)].Between(
        run.truth[static_cast<std::size_t>(c.to)]);
    const bool right = (c.relative.translation() - truth.translation()).norm() < 0.1;
    said_true += right ? 1 : 0;
    return right;
  };
  const LoopClosureResult judged = CloseLoops(Pointers(run.scans), run.drifted, by_truth);
  EXPECT_EQ(asked, judged.statistics.found);
  EXPECT_GE(said_true, 5);
  EXPECT_EQ(judged.statistics.accepted + judged.statistics.rejected, said_true);
  EXPECT_EQ(judged.statistics.gated, asked - said_true);
  EXPECT_LT(testing::MaxPositionError(judged.poses, run.truth), 0.3);

  LoopClosureOptions refusing = held;
  refusing.oracle = [](const LoopClosureCandidate&) { return false; };
  LoopCloser closer(refusing);
  std::size_t fed = 0;
  while (fed < run.scans.size() && closer.statistics().found < 3) {
    closer.AddNode(run.scans[fed], run.drifted[fed]);
    ++fed;
  }
  ASSERT_EQ(closer.statistics().found, 3);
  EXPECT_EQ(closer.statistics().accepted, 0);
  const std::vector<Pose2> given(run.drifted.begin(),
                                 run.drifted.begin() + static_cast<std::ptrdiff_t>(fed));
  EXPECT_LT(testing::MaxPositionError(closer.estimate(), given), 1e-9);
}

// With oracle_relative (bench closures --oracle-poses) every closure that passed the score goes
// in at the relative pose the oracle gives, whatever its match said and the gate would have made
// of it: given the truth, the drifted laps come back onto it at least as well as with the same
// closures at their matched poses; given nothing, no closure goes in.
TEST(LoopClosureTest, AnOracleCanGiveTheClosuresTheirRelativePoses) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  LoopClosureOptions held = SigmaClosures();
  held.gate_sigmas = 1e-3;
  held.confirm_within_meters = 0.01;
  int asked = 0;
  LoopClosureOptions exact = held;
  exact.oracle_relative = [&](const LoopClosureCandidate& c) -> std::optional<Pose2> {
    ++asked;
    return run.truth[static_cast<std::size_t>(c.from)].Between(
        run.truth[static_cast<std::size_t>(c.to)]);
  };
  // 'oracle' is not asked when oracle_relative is there.
  exact.oracle = [](const LoopClosureCandidate&) {
    ADD_FAILURE() << "oracle asked";
    return false;
  };
  const LoopClosureResult given = CloseLoops(Pointers(run.scans), run.drifted, exact);
  ASSERT_GT(asked, 5);
  EXPECT_EQ(given.statistics.accepted + given.statistics.rejected, asked);
  EXPECT_EQ(given.statistics.rejected, 0);
  LoopClosureOptions matched = held;
  matched.oracle = [](const LoopClosureCandidate&) { return true; };
  const LoopClosureResult as_matched = CloseLoops(Pointers(run.scans), run.drifted, matched);
  EXPECT_EQ(as_matched.statistics.found, given.statistics.found);
  const double exact_error = testing::MaxPositionError(given.poses, run.truth);
  EXPECT_LE(exact_error, testing::MaxPositionError(as_matched.poses, run.truth) + 1e-3);
  EXPECT_LT(exact_error, 0.3);
  EXPECT_GT(testing::MaxPositionError(run.drifted, run.truth), 1.0);

  LoopClosureOptions nothing = held;
  nothing.oracle_relative = [](const LoopClosureCandidate&) -> std::optional<Pose2> {
    return std::nullopt;
  };
  const LoopClosureResult none = CloseLoops(Pointers(run.scans), run.drifted, nothing);
  EXPECT_EQ(none.statistics.accepted, 0);
  EXPECT_EQ(none.statistics.gated, none.statistics.found);
}

void ExpectSameResult(const LoopClosureResult& a, const LoopClosureResult& b) {
  EXPECT_EQ(a.statistics.found, b.statistics.found);
  EXPECT_EQ(a.statistics.accepted, b.statistics.accepted);
  EXPECT_EQ(a.statistics.residuals, b.statistics.residuals);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t i = 0; i < a.poses.size(); ++i) {
    EXPECT_EQ(a.poses[i].x, b.poses[i].x) << i;
    EXPECT_EQ(a.poses[i].y, b.poses[i].y) << i;
    EXPECT_EQ(a.poses[i].theta, b.poses[i].theta) << i;
  }
}

// Submaps freed from the cache are rebuilt identically: keeping one built, all of them, or as
// many as a tiny memory budget allows gives the same closures and the same poses.
TEST(LoopClosureTest, TheBuiltSubmapCacheDoesNotChangeTheResult) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  LoopClosureOptions one = SigmaClosures(), all = SigmaClosures(), tight = SigmaClosures();
  one.max_built_submaps = 1;
  all.max_built_submaps = 1000;
  all.max_built_submaps_megabytes = 1e6;
  tight.max_built_submaps_megabytes = 1e-3;
  const LoopClosureResult a = CloseLoops(Pointers(run.scans), run.drifted, one);
  const LoopClosureResult b = CloseLoops(Pointers(run.scans), run.drifted, all);
  const LoopClosureResult c = CloseLoops(Pointers(run.scans), run.drifted, tight);
  ASSERT_GT(a.statistics.submaps, 2);
  ExpectSameResult(a, b);
  ExpectSameResult(c, b);
  // The budget bounds what is held: with it only the submap searched and the best one so far
  // stay built.
  EXPECT_GT(c.statistics.built_submaps_peak_megabytes, 0.0);
  EXPECT_LT(c.statistics.built_submaps_peak_megabytes, b.statistics.built_submaps_peak_megabytes);
}

// Recording every match (bench closures) searches each submap down to a lower score but picks
// the same closures: the same poses. The candidates hold every closure the graph kept, each
// where the truth puts its node relative to the submap's first node, and matches below
// min_score that never reach verification.
TEST(LoopClosureTest, RecordingTheCandidatesDoesNotChangeTheResult) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  LoopClosureOptions recording = SigmaClosures();
  recording.record_candidates = true;
  const LoopClosureResult plain = CloseLoops(Pointers(run.scans), run.drifted, SigmaClosures());
  const LoopClosureResult recorded = CloseLoops(Pointers(run.scans), run.drifted, recording);
  ExpectSameResult(plain, recorded);
  EXPECT_TRUE(plain.candidates.empty());
  int in_graph = 0, below = 0, best = 0;
  for (const LoopClosureCandidate& c : recorded.candidates) {
    EXPECT_GE(c.score, recording.record_min_score);
    if (c.best_of_search) ++best;
    if (c.score < recording.min_score) {
      ++below;
      EXPECT_FALSE(c.passed_score);
      EXPECT_EQ(c.verification, ClosureVerification::kNotReached);
    }
    if (!c.in_graph) continue;
    ++in_graph;
    EXPECT_TRUE(c.passed_score && c.best_of_search);
    EXPECT_NE(c.verification, ClosureVerification::kNotReached);
    EXPECT_NE(c.verification, ClosureVerification::kHeldBack);
    EXPECT_GT(c.weight, 0.0);
    const Pose2 truth = run.truth[static_cast<std::size_t>(c.from)].Between(
        run.truth[static_cast<std::size_t>(c.to)]);
    EXPECT_LT((c.relative.translation() - truth.translation()).norm(), 0.3)
        << c.from << "-" << c.to;
  }
  EXPECT_EQ(in_graph, recorded.statistics.accepted);
  EXPECT_GT(below, 0);
  EXPECT_LE(best, recorded.statistics.searches);
}

// Closures that land where a drift-free filter predicts (within their own noise) make the
// chain stiff: the graph then keeps the filter's poses instead of following each closure's few
// centimetres and milliradians of match noise.
TEST(LoopClosureTest, ClosuresThatAgreeWithTheFilterDoNotBendIt) {
  const LoopRun run = DriveTwoLaps(0.0);
  LoopClosureOptions fixed = SigmaClosures();
  fixed.adapt_motion_noise = false;
  const LoopClosureResult adapted = CloseLoops(Pointers(run.scans), run.drifted, SigmaClosures());
  const LoopClosureResult kept = CloseLoops(Pointers(run.scans), run.drifted, fixed);
  ASSERT_GE(adapted.statistics.accepted, 1);
  EXPECT_LT(adapted.statistics.motion_noise_scale, 0.01);
  EXPECT_LT(testing::MaxPositionError(adapted.poses, run.truth), 0.02);
  // The same closures under the fixed motion model move the poses by centimetres (the aliased
  // ones along the corridor most): the case above is not trivially met.
  EXPECT_GT(testing::MaxPositionError(kept.poses, run.truth), 0.05);
}

// A filter that drifts through its first lap and, back at the start, snaps onto its map there:
// the one step into the second lap carries the whole lap's error, and the second lap is right
// (ACES on wheel odometry, seed 3). Held at the model's noise, that step agrees with every
// closure back to the start, and the closures from the second lap to the drifted first lap's
// submaps fall outside windows sized by a chain that looks certain. A local estimate of the
// steps (the laser odometry's; here the true steps with noise) shows the snap, its edge is
// loosened, and the graph ends as well as it does for a filter that never snapped (the same
// second lap carried on from the drifted end of the first).
TEST(LoopClosureTest, AFilterThatSnappedOntoItsStartIsClosedAsIfItHadNot) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  const std::size_t lap = run.truth.size() / 2;
  std::vector<Pose2> snapped = run.drifted;
  std::vector<Pose2> unsnapped = run.drifted;
  // Where the truth's second lap lies when carried on from the drifted first lap's end.
  const Pose2 carried = run.drifted[lap - 1] * run.truth[lap - 1].Inverse();
  for (std::size_t i = lap; i < snapped.size(); ++i) {
    snapped[i] = run.truth[i];
    unsnapped[i] = carried * run.truth[i];
  }
  Rng rng = MakeRng(5);
  std::normal_distribution<double> noise(0.0, 0.002);
  std::vector<Pose2> local = {run.truth.front()};
  for (std::size_t i = 1; i < run.truth.size(); ++i) {
    Pose2 step = run.truth[i - 1].Between(run.truth[i]);
    step.x += noise(rng);
    step.y += noise(rng);
    step.theta += 0.1 * noise(rng);
    local.push_back(local.back() * step);
  }
  const std::vector<const PreparedScan*> scans = Pointers(run.scans);
  const LoopClosureResult kept = CloseLoops(scans, snapped, SigmaClosures());
  const LoopClosureResult loosened = CloseLoops(scans, snapped, local, SigmaClosures());
  const LoopClosureResult never = CloseLoops(scans, unsnapped, SigmaClosures());
  EXPECT_EQ(kept.statistics.loosened, 0);
  EXPECT_EQ(loosened.statistics.loosened, 1);
  const double never_error = testing::MaxPositionError(never.poses, run.truth);
  ASSERT_LT(never_error, 0.5);
  EXPECT_GT(testing::MaxPositionError(kept.poses, run.truth), 1.0);
  EXPECT_LT(testing::MaxPositionError(loosened.poses, run.truth), never_error + 0.02)
      << loosened.statistics.found << " found, " << loosened.statistics.accepted << " accepted, "
      << loosened.statistics.gated << " gated";
}

TEST(LoopClosureTest, NoDriftNoHarm) {
  const LoopRun run = DriveTwoLaps(0.0);
  const LoopClosureResult result = CloseLoops(Pointers(run.scans), run.drifted, SigmaClosures());
  EXPECT_GE(result.statistics.accepted, 1);
  EXPECT_LT(testing::MaxPositionError(result.poses, run.truth), 0.1)
      << result.statistics.found << " found, " << result.statistics.accepted << " accepted, "
      << result.statistics.gated << " gated, " << result.statistics.rejected << " rejected";
}

// A row of identical 6 m × 6 m rooms off a 2 m corridor (the office_floor world in small): a
// scan in one room matches the next room's submap perfectly, 6 m off.
std::vector<Segment> LookAlikeRoomsWorld(int rooms) {
  const double width = 6.0 * rooms;
  std::vector<Segment> world = {
      {{0, 0}, {width, 0}}, {{width, 0}, {width, 8}}, {{width, 8}, {0, 8}}, {{0, 8}, {0, 0}}};
  for (int k = 0; k < rooms; ++k) {
    const double x = 6.0 * k;
    world.push_back({{x, 2}, {x + 1, 2}});  // the corridor wall, a door 1 m wide
    world.push_back({{x + 2, 2}, {x + 6, 2}});
    if (k > 0) world.push_back({{x, 2}, {x, 8}});
    // The same furniture in every room.
    for (const auto& [x0, y0, x1, y1] : {std::array<double, 4>{x + 4.8, 6.8, x + 5.6, 7.6},
                                         std::array<double, 4>{x + 0.3, 5.0, x + 0.9, 6.2},
                                         std::array<double, 4>{x + 3.0, 2.3, x + 3.5, 2.6}}) {
      world.push_back({{x0, y0}, {x1, y0}});
      world.push_back({{x1, y0}, {x1, y1}});
      world.push_back({{x1, y1}, {x0, y1}});
      world.push_back({{x0, y1}, {x0, y0}});
    }
  }
  return world;
}

// Drives the corridor eastwards and every room row by row (about 34 m of travel from one room
// to the next, more than min_loop_travel_meters), a node every 0.5 m; the poses are the truth
// (a filter without drift).
LoopRun TourLookAlikeRooms(int rooms) {
  const std::vector<Segment> world = LookAlikeRoomsWorld(rooms);
  std::vector<Eigen::Vector2d> waypoints = {{0.5, 1.0}};
  for (int k = 0; k < rooms; ++k) {
    const double x = 6.0 * k;
    waypoints.emplace_back(x + 1.5, 1.0);
    // Six rows across the room and back to its door: no part of the room is seen again after
    // 30 m of travel, so the room gives no loop closure of its own.
    for (int row = 0; row < 6; ++row) {
      const double y = 3.0 + 0.8 * row;
      waypoints.emplace_back(row % 2 == 0 ? x + 1.5 : x + 4.2, y);
      waypoints.emplace_back(row % 2 == 0 ? x + 4.2 : x + 1.5, y);
    }
    waypoints.emplace_back(x + 1.5, 1.0);
  }
  LoopRun run;
  for (std::size_t w = 0; w + 1 < waypoints.size(); ++w) {
    const Eigen::Vector2d a = waypoints[w];
    const Eigen::Vector2d b = waypoints[w + 1];
    const double heading = std::atan2(b.y() - a.y(), b.x() - a.x());
    const int steps = std::max(1, static_cast<int>((b - a).norm() / 0.5));
    for (int k = 0; k < steps; ++k) {
      const Eigen::Vector2d at = a + (b - a) * (static_cast<double>(k) / steps);
      run.truth.emplace_back(at.x(), at.y(), heading);
    }
  }
  Rng rng = MakeRng(4);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (const Pose2& pose : run.truth) {
    LaserScan scan = testing::SimulateScan(world, pose, 360, 2.0 * kPi * 359.0 / 360.0, 12.0);
    for (double& r : scan.ranges) r += noise(rng);
    run.scans.push_back(PrepareScan(scan, Pose2(), {}));
  }
  run.drifted = run.truth;
  return run;
}

// The look-alike room 6 m away must stay out of reach: the search window follows the
// uncertainty of the motion since the submap (a few decimetres over one room's tours), not a
// fixed growth with the distance travelled (which reached 6 m after about 100 m).
TEST(LoopClosureTest, ALookAlikeRoomNextDoorDoesNotBendTheMap) {
  const LoopRun run = TourLookAlikeRooms(5);
  const LoopClosureResult result = CloseLoops(Pointers(run.scans), run.drifted, {});
  const LoopClosureStatistics& stats = result.statistics;
  EXPECT_GT(stats.searches, 20);
  EXPECT_LT(testing::MaxPositionError(result.poses, run.truth), 0.1)
      << stats.found << " found, " << stats.accepted << " accepted, " << stats.gated
      << " held back, " << stats.rejected << " rejected";
}

double RmsPositionError(const std::vector<Pose2>& poses, const std::vector<Pose2>& truth) {
  double sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    sum += (poses[i].translation() - truth[i].translation()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(truth.size()));
}

// The line the filter finally keeps replaces the one it gave node by node: the motion edges are
// re-derived from it, the closures found are kept, and the optimum moves towards the better line
// — not onto it: the closures were matched against submaps built from the drifted line, whose
// 15 m turn by 0.75 degrees over their length.
TEST(LoopClosureTest, ReoptimizingOnABetterLineKeepsTheClosuresAndTakesTheLine) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  LoopCloser closer(SigmaClosures());
  for (std::size_t i = 0; i < run.scans.size(); ++i) closer.AddNode(run.scans[i], run.drifted[i]);
  const LoopClosureStatistics before = closer.statistics();
  ASSERT_GE(before.accepted, 5);
  const double on_drifted = RmsPositionError(closer.estimate(), run.truth);
  closer.Reoptimize(run.truth);
  EXPECT_EQ(closer.statistics().accepted, before.accepted);
  EXPECT_EQ(testing::MaxPositionError(closer.filter_poses(), run.truth), 0.0);
  // 0.174 m RMS on the drifted line, 0.141 m on the truth (seeded).
  EXPECT_LT(RmsPositionError(closer.estimate(), run.truth), on_drifted);
}

TEST(LoopClosureTest, RebaseMakesTheEstimateTheFiltersPoses) {
  const LoopRun run = DriveTwoLaps(DegToRad(0.05));
  LoopCloser closer(SigmaClosures());
  std::size_t i = 0;
  for (; i < run.scans.size() && closer.statistics().accepted == 0; ++i) {
    closer.AddNode(run.scans[i], run.drifted[i]);
  }
  ASSERT_LT(i, run.scans.size()) << "no closure";
  ASSERT_GT(testing::MaxPositionError(closer.estimate(), closer.filter_poses()), 0.1);
  closer.Rebase();
  EXPECT_EQ(testing::MaxPositionError(closer.estimate(), closer.filter_poses()), 0.0);
}

SlamOptions OnlineOptions() {
  SlamOptions options;
  options.laser_odometry.enabled = false;
  options.rbpf.particles = 5;
  options.rbpf.threads = 1;
  options.rbpf.seed = 3;
  options.every_scan.method = "interpolate";
  options.pose_graph = true;
  // With covariances from the matches (SigmaClosures) the particles follow later and seed 4
  // ends 0.79 m off.
  options.loop_closure = SigmaClosures();
  // Without the snap check: the laser odometry beside the filter slides 0.5 m along this loop's
  // bare corridors in one step (node 89; the filter's step is right), that edge is loosened,
  // and seed 1 ends 0.61 m off instead of 0.55 m (the particles follow 4 times instead of 5).
  // Snaps have their own test (AFilterThatSnappedOntoItsStartIsClosedAsIfItHadNot).
  options.loop_closure.snap_sigmas = 0.0;
  options.loop_closure.online = true;
  return options;
}

// Runs the online SLAM on 'run' (odometry: its drifted poses); with 'ask' the trajectory is
// asked for after every scan, as the live semantic mapper and the ROS node do.
SlamResult RunOnline(const LoopRun& run, const SlamOptions& options, bool ask) {
  IncrementalSlam slam(options);
  for (std::size_t i = 0; i < run.raw.size(); ++i) {
    slam.AddScan({run.raw[i], run.drifted[i], run.drifted[i]});
    if (ask) {
      EXPECT_EQ(slam.Trajectory().size(), i + 1);
    }
  }
  return std::move(slam).Finish();
}

std::vector<Pose2> Poses(const SlamResult& result) {
  std::vector<Pose2> poses;
  for (const StampedPose& p : result.trajectory) poses.push_back(p.pose);
  return poses;
}

// Online, on odometry whose heading drifts by 1 degree a metre (over 5 m off after a lap): the
// graph closes the first lap while the filter runs and the particles follow it. Checked over
// filter seeds, not on one: the filter alone (5 particles, scan matching from the drifting
// odometry) ends 0.17–0.75 m off at worst over seeds 1–6 and the online graph 0.21–0.55 m,
// better on some seeds and worse on others, so one seed's bound passes or fails by the seed.
// What holds on each seed is checked on each (closures accepted, the drift gone to within what
// the filter bends before it has a map); what the graph is for, on the seeds together.
TEST(LoopClosureTest, OnlineTheParticlesFollowTheClosedLoop) {
  const LoopRun run = DriveTwoLaps(DegToRad(1.0));
  ASSERT_GT(testing::MaxPositionError(run.drifted, run.truth), 5.0);
  double with_graph = 0.0;
  double without_graph = 0.0;
  int seeds_followed = 0;
  constexpr int kSeeds = 4;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    SlamOptions options = OnlineOptions();
    options.rbpf.seed = static_cast<std::uint64_t>(seed);
    const SlamResult result = RunOnline(run, options, false);
    const double error = testing::MaxPositionError(Poses(result), run.truth);
    EXPECT_GE(result.loop_closure.accepted, 5) << "seed " << seed;
    EXPECT_LT(error, 0.6) << "seed " << seed;
    if (result.loop_closure.follows >= 1) ++seeds_followed;
    with_graph += error;
    options.pose_graph = false;
    without_graph += testing::MaxPositionError(Poses(RunOnline(run, options, false)), run.truth);
  }
  EXPECT_GE(seeds_followed, kSeeds - 1);
  EXPECT_LT(with_graph, without_graph) << "mean worst error with the graph " << with_graph / kSeeds
                                       << " m, without " << without_graph / kSeeds << " m";
  // In the background the particles follow one node later; the same holds.
  SlamOptions options = OnlineOptions();
  options.rbpf.seed = 1;
  options.loop_closure.background = true;
  const SlamResult background = RunOnline(run, options, false);
  EXPECT_GE(background.loop_closure.follows, 1);
  EXPECT_GE(background.loop_closure.accepted, 5);
  EXPECT_LT(testing::MaxPositionError(Poses(background), run.truth), 0.6);
}

// In the background the graph works while the filter takes the next scans, and the filter waits
// for it at a fixed point: asking for the trajectory in between (which waits for the graph
// early) changes nothing, and neither does a second run.
TEST(LoopClosureTest, InTheBackgroundTheResultDoesNotDependOnTiming) {
  const LoopRun run = DriveTwoLaps(DegToRad(1.0));
  SlamOptions options = OnlineOptions();
  options.loop_closure.background = true;
  const std::vector<Pose2> first = Poses(RunOnline(run, options, false));
  const std::vector<Pose2> asked = Poses(RunOnline(run, options, true));
  ASSERT_EQ(first.size(), asked.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    ASSERT_EQ(first[i].x, asked[i].x) << i;
    ASSERT_EQ(first[i].y, asked[i].y) << i;
    ASSERT_EQ(first[i].theta, asked[i].theta) << i;
  }
}

}  // namespace
}  // namespace semchain::mapping
