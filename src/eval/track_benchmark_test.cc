#include "eval/track_benchmark.h"

#include <gtest/gtest.h>

#include "eval/reference_check.h"
#include "mapping/testing/synthetic_map.h"

namespace semchain::eval {
namespace {

using localization::LocalizationMethod;

TEST(SummarizeTrackTest, ErrorsOfEstimatedScansAndCpuPerUpdate) {
  std::vector<TrackedScan> track(4);
  track[0] = {0.0, true, {}, 0.10, 1.0, 0.9, 1, true, 3.0};
  track[1] = {0.2, true, {}, 0.30, 4.0, 0.9, 0, true, 1.0};
  track[2] = {0.4, false, {}, 0.0, 0.0, 0.0, 0, false, 1.0};  // no pose: not scored
  track[3] = {0.6, true, {}, 0.20, 2.0, 0.9, 2, false, 5.0};
  const TrackSummary s = SummarizeTrack(track);
  EXPECT_EQ(s.scans, 4);
  EXPECT_EQ(s.estimated, 3);
  EXPECT_EQ(s.updates, 3);
  EXPECT_EQ(s.scan_matched, 2);
  EXPECT_DOUBLE_EQ(s.median_m, 0.20);
  EXPECT_DOUBLE_EQ(s.max_m, 0.30);
  EXPECT_DOUBLE_EQ(s.median_deg, 2.0);
  EXPECT_DOUBLE_EQ(s.max_deg, 4.0);
  EXPECT_DOUBLE_EQ(s.cpu_ms_per_update, (3.0 + 5.0) / 3.0);
  EXPECT_DOUBLE_EQ(s.cpu_ms_per_scan, 10.0 / 4.0);
}

struct Room {
  mapping::testing::SimulatedRun run = mapping::testing::SimulateRoomRun(0.1, 0.01, 1);
  mapping::MapImage image = mapping::testing::RoomMap();
  localization::LocalizerMap map{image, semantic::SemanticMap(), localization::AmclOptions(),
                                 localization::PreLocalizationOptions(),
                                 localization::ScanMatchRelocalizerOptions()};
};

// The room driven with odometry 3 % long and 2 % short in turns: started at the true pose, every
// method tracks the truth (the map is exact) within two decimetres and 10° with AMCL alone (its
// heading trails the odometry's in turns), and to a few centimetres and a degree with each scan
// matched against the map.
TEST(TrackScansTest, EveryMethodFollowsTheTruthFromTheInitialPose) {
  const Room room;
  for (const LocalizationMethod method :
       {LocalizationMethod::kAmcl, LocalizationMethod::kSemanticAmcl,
        LocalizationMethod::kSemanticScanMatch, LocalizationMethod::kScanMatchGlobal}) {
    TrackOptions options;
    const TrackSummary s =
        SummarizeTrack(TrackScans(room.map, method, room.run.scans, room.run.truth, options));
    options.localizer.scan_tracking.enabled = false;
    const TrackSummary alone =
        SummarizeTrack(TrackScans(room.map, method, room.run.scans, room.run.truth, options));
    const std::string name = LocalizationMethodName(method);
    EXPECT_EQ(s.scans, static_cast<int>(room.run.scans.size()));
    EXPECT_EQ(s.estimated, s.scans) << name;  // from the first scan on
    EXPECT_EQ(s.scan_matched, s.scans) << name;
    EXPECT_EQ(alone.scan_matched, 0) << name;
    EXPECT_LT(alone.max_m, 0.2) << name;
    EXPECT_LT(alone.max_deg, 10.0) << name;
    EXPECT_LT(s.median_m, 0.01) << name;
    EXPECT_LT(s.max_m, 0.03) << name;
    EXPECT_LT(s.max_deg, 1.0) << name;
    EXPECT_LT(s.median_m, 0.5 * alone.median_m) << name;
  }
}

// A reference off the odometry by 3 % (the run's odometry error) shows a few millimetres a scan;
// one pose moved 8 cm sideways shows there, in its motion against the odometry and in its
// distance to where the scan fits the map.
TEST(CheckReferenceTest, NamesTheScanWhoseReferencePoseIsOff) {
  const Room room;
  std::vector<Pose2> reference = room.run.truth;
  const std::size_t k = 20;
  reference[k] = reference[k] * Pose2(0.0, 0.08, 0.0);
  const std::vector<ReferenceCheck> checks =
      CheckReference(room.map.matcher, room.run.scans, reference, 0.05);
  ASSERT_EQ(checks.size(), reference.size());
  EXPECT_DOUBLE_EQ(checks[0].motion_m, 0.0);
  for (std::size_t i = 1; i < checks.size(); ++i) {
    if (i == k || i == k + 1) continue;
    EXPECT_LT(checks[i].fit_m, 0.02) << i;
  }
  EXPECT_NEAR(checks[k].motion_m, 0.08, 0.01);
  EXPECT_NEAR(checks[k + 1].motion_m, 0.08, 0.01);
  EXPECT_NEAR(checks[k].fit_m, 0.08, 0.02);
  EXPECT_GT(checks[k].points, 100);
  EXPECT_LT(checks[k].score, checks[k - 1].score);
}

}  // namespace
}  // namespace semchain::eval
