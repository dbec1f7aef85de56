#include "eval/reloc_scoring.h"

#include <gtest/gtest.h>

#include <vector>

namespace semchain::eval {
namespace {

// Eleven scans one second apart at the origin; the method's CPU grows by 10 ms a scan and its
// search CPU by 4 ms.
struct Fixture {
  std::vector<StampedPose> truth;
  localization::RelocTrace trace;
  RelocBenchmarkOptions options;

  Fixture() {
    options.time_limit = 5.0;
    for (int i = 0; i <= 10; ++i) {
      truth.push_back({100.0 + i, Pose2(0.0, 0.0, 0.0)});
      trace.estimates.push_back(Pose2(3.0, 0.0, 0.0));  // 3 m off
      trace.cpu_seconds.push_back(0.010 * (i + 1));
      trace.search_cpu_seconds.push_back(0.004 * (i + 1));
      trace.iterations.push_back(i + 1);
    }
  }
  void ConvergeFrom(int scan) {
    for (std::size_t i = static_cast<std::size_t>(scan); i < trace.estimates.size(); ++i) {
      trace.estimates[i] = Pose2(0.1, 0.0, 0.05);
    }
  }
};

TEST(ScoreRelocTraceTest, ASuccessIsChargedUntilConvergence) {
  Fixture f;
  f.ConvergeFrom(3);
  const RelocTrialOutcome outcome = ScoreRelocTrace(f.trace, f.truth, f.options);
  EXPECT_TRUE(outcome.success);
  EXPECT_DOUBLE_EQ(outcome.time, 3.0);
  EXPECT_DOUBLE_EQ(outcome.cpu, 0.040);
  EXPECT_DOUBLE_EQ(outcome.search_cpu, 0.016);
  EXPECT_EQ(outcome.iterations, 4);
  EXPECT_NEAR(outcome.error_m, 0.1, 1e-12);
}

TEST(ScoreRelocTraceTest, AFailureIsChargedForTheWholeTimeItHad) {
  Fixture f;
  const RelocTrialOutcome never = ScoreRelocTrace(f.trace, f.truth, f.options);
  EXPECT_FALSE(never.success);
  EXPECT_TRUE(never.localized);
  EXPECT_NEAR(never.final_error_m, 3.0, 1e-12);
  // Up to the time limit (5 s: scan 5), not to the end of the trial and not zero.
  EXPECT_DOUBLE_EQ(never.time, 5.0);
  EXPECT_DOUBLE_EQ(never.cpu, 0.060);
  EXPECT_DOUBLE_EQ(never.search_cpu, 0.024);

  // Converging after the limit is a failure charged the same way.
  f.ConvergeFrom(7);
  const RelocTrialOutcome late = ScoreRelocTrace(f.trace, f.truth, f.options);
  EXPECT_FALSE(late.success);
  EXPECT_DOUBLE_EQ(late.time, 5.0);
  EXPECT_DOUBLE_EQ(late.cpu, 0.060);

  // A trial shorter than the limit is charged to its end.
  f.options.time_limit = 30.0;
  f.trace.estimates.back() = Pose2(3.0, 0.0, 0.0);  // lost again at the last scan
  const RelocTrialOutcome lost = ScoreRelocTrace(f.trace, f.truth, f.options);
  EXPECT_FALSE(lost.success);
  EXPECT_DOUBLE_EQ(lost.time, 10.0);
  EXPECT_DOUBLE_EQ(lost.cpu, 0.110);
}

TEST(ScoreRelocTraceTest, OnlyTheFinalStreakCounts) {
  Fixture f;
  f.trace.estimates[1] = Pose2(0.0, 0.0, 0.0);  // right once, then lost
  f.ConvergeFrom(4);
  const RelocTrialOutcome outcome = ScoreRelocTrace(f.trace, f.truth, f.options);
  EXPECT_TRUE(outcome.success);
  EXPECT_DOUBLE_EQ(outcome.time, 4.0);
  // A heading off by more than the tolerance is not within it.
  f.trace.estimates[6] = Pose2(0.0, 0.0, 0.2);
  const RelocTrialOutcome heading = ScoreRelocTrace(f.trace, f.truth, f.options);
  EXPECT_FALSE(heading.success);
  EXPECT_DOUBLE_EQ(heading.time, 5.0);
}

// A pre-localization that puts the robot where a map 0.08 m off shows it: 0.08 m off the truth,
// exact in the map's frame.
TEST(ScoreRelocTraceTest, ThePreLocalizationIsAlsoScoredInTheMapsFrame) {
  Fixture f;
  const Pose2 map_offset(0.08, -0.03, 0.0);
  std::vector<StampedPose> mapping_truth;
  std::vector<StampedPose> mapping_estimate;
  for (int i = 0; i < 10; ++i) {
    mapping_truth.push_back({0.1 * i, Pose2(0.5 * i, 0.0, 0.0)});
    mapping_estimate.push_back({0.1 * i, map_offset * mapping_truth.back().pose});
  }
  const Result<MapFrame> frame = MapFrame::FromTrajectories(mapping_estimate, mapping_truth);
  ASSERT_TRUE(frame.ok());
  f.trace.prelocalization = map_offset * f.truth[2].pose;
  f.trace.prelocalization_scan = 2;
  const RelocTrialOutcome outcome = ScoreRelocTrace(f.trace, f.truth, f.options, &*frame);
  ASSERT_TRUE(outcome.prelocalized);
  EXPECT_NEAR(outcome.prelocalization_error.x(), 0.08, 1e-12);
  EXPECT_NEAR(outcome.prelocalization_error.y(), 0.03, 1e-12);
  EXPECT_NEAR(outcome.prelocalization_error_map.norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace semchain::eval
