#include "localization/laser_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace semchain::localization {
namespace {

// 6 m × 4 m at 0.05 m, free, with a wall along x = 2.0 (the column of cells centred there).
mapping::MapImage WallMap() {
  mapping::MapImage map;
  map.width = 120;
  map.height = 80;
  map.resolution = 0.05;
  map.origin = Eigen::Vector3d(-3.025, -2.025, 0.0);
  map.cells.assign(120 * 80, 0);
  for (int y = 0; y < 80; ++y) map.cells[static_cast<std::size_t>(y * 120 + 100)] = 100;
  return map;
}

// One beam straight ahead reading 'range'.
LaserScan OneBeam(double range, double max_range = 20.0) {
  LaserScan scan;
  scan.max_range = max_range;
  scan.ranges = {range};
  return scan;
}

TEST(LikelihoodFieldModelTest, BeamLikelihoodIsTheGaussianOfTheDistance) {
  const LocalizationMap map(WallMap(), 2.0);
  AmclOptions options;
  options.laser_max_range = -1.0;  // the scan's 20 m
  const LikelihoodFieldModel model(map, options);
  for (const double d : {0.0, 0.1, 0.2, 0.45}) {
    // The robot at x = 0 facing the wall; the reading ends d short of it.
    const LaserBeams beams = SelectBeams(OneBeam(2.0 - d), Pose2(), options);
    double mean_beam = 0.0;
    const double weight = model.Weight(beams, Pose2(0.0, 0.3, 0.0), &mean_beam);
    const double pz = 0.5 * std::exp(-d * d / (2 * 0.2 * 0.2)) + 0.5 / 20.0;
    EXPECT_NEAR(mean_beam, pz, 1e-6) << d;
    EXPECT_NEAR(weight, 1.0 + pz * pz * pz, 1e-6) << d;  // nav2: 1 + Σ pz³
  }
}

TEST(LikelihoodFieldModelTest, FarEndpointsAndMaxRangeReadings) {
  const LocalizationMap map(WallMap(), 2.0);
  AmclOptions options;
  options.laser_max_range = -1.0;
  const LikelihoodFieldModel model(map, options);
  double mean_beam = 0.0;
  // An endpoint beyond the cap (and one off the map) scores the capped distance.
  const double capped = 0.5 * std::exp(-4.0 / (2 * 0.04)) + 0.5 / 20.0;
  model.Weight(SelectBeams(OneBeam(10.0), Pose2(), options), Pose2(), &mean_beam);
  EXPECT_NEAR(mean_beam, capped, 1e-9);
  // A max-range reading is skipped.
  EXPECT_DOUBLE_EQ(model.Weight(SelectBeams(OneBeam(20.0), Pose2(), options), Pose2(), &mean_beam),
                   1.0);
}

TEST(BeamModelTest, RayCastAndMixture) {
  const LocalizationMap map(WallMap(), 2.0);
  // The wall's cell starts at x = 1.975: the ray from x = 0 stops there.
  EXPECT_NEAR(map.CalcRange({0.0, 0.3}, 0.0, 20.0), 1.975, 1e-9);
  EXPECT_NEAR(map.CalcRange({0.0, 0.3}, -kPi / 4, 20.0), 1.975 * std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(map.CalcRange({0.0, 0.3}, kPi, 20.0), 3.025, 1e-9);  // off the map
  AmclOptions options;
  options.laser_model_type = LaserModelType::kBeam;
  const BeamModel model(map, options);
  const double expected = 1.975;
  // Short reading: hit + short + rand; exact reading: hit + rand; max reading: hit tail + max.
  const double short_pz =
      0.5 * std::exp(-1.0 / (2 * 0.04)) + 0.05 * 0.1 * std::exp(-0.1 * 0.975) + 0.5 / 20.0;
  EXPECT_NEAR(model.BeamLikelihood(0.975, expected, 20.0), short_pz, 1e-12);
  EXPECT_NEAR(model.BeamLikelihood(expected, expected, 20.0), 0.5 + 0.5 / 20.0, 1e-12);
  EXPECT_NEAR(model.BeamLikelihood(20.0, 20.0, 20.0), 0.5 + 0.05, 1e-12);
  options.laser_max_range = -1.0;
  const BeamModel beam(map, options);
  double mean_beam = 0.0;
  const double weight =
      beam.Weight(SelectBeams(OneBeam(expected), Pose2(), options), Pose2(0, 0.3, 0), &mean_beam);
  EXPECT_NEAR(weight, 1.0 + std::pow(0.5 + 0.5 / 20.0, 3), 1e-9);
}

// nav2 adds z_max only to a reading of exactly range_max and z_rand only below it, so a reading
// beyond range_max (CARMEN's 81.91 m "no return" above an 80.99 m maximum) keeps only the tail of
// the hit Gaussian; the likelihood field skips both.
TEST(BeamModelTest, ReadingsBeyondRangeMaxGetNeitherZMaxNorZRand) {
  const LocalizationMap map(WallMap(), 2.0);
  AmclOptions options;
  options.laser_model_type = LaserModelType::kBeam;
  const BeamModel model(map, options);
  EXPECT_NEAR(model.BeamLikelihood(20.0, 20.0, 20.0), 0.5 + 0.05, 1e-12);
  EXPECT_NEAR(model.BeamLikelihood(20.1, 20.0, 20.0), 0.5 * std::exp(-0.01 / 0.08), 1e-12);
  EXPECT_NEAR(model.BeamLikelihood(20.1, 1.975, 20.0), 0.0, 1e-12);
  options.laser_max_range = -1.0;  // the scan's 20 m
  const BeamModel beam(map, options);
  double mean_beam = 0.0;
  // Facing the wall (expected 1.975 m): the over-range reading scores 0, so p = 1 + 0³.
  EXPECT_DOUBLE_EQ(
      beam.Weight(SelectBeams(OneBeam(20.5), Pose2(), options), Pose2(0, 0.3, 0), &mean_beam), 1.0);
  EXPECT_NEAR(mean_beam, 0.0, 1e-12);
  const LikelihoodFieldModel field(map, options);
  EXPECT_DOUBLE_EQ(
      field.Weight(SelectBeams(OneBeam(20.5), Pose2(), options), Pose2(0, 0.3, 0), &mean_beam),
      1.0);
}

TEST(SelectBeamsTest, EvenlySpacedAsNav2) {
  LaserScan scan;
  scan.max_range = 30.0;
  scan.angle_min = -kPi / 2;
  scan.angle_increment = kPi / 359;
  scan.ranges.assign(360, 5.0);
  scan.ranges[6] = 0.0;  // no reading: counts as max range
  AmclOptions options;
  const LaserBeams beams = SelectBeams(scan, Pose2(), options);
  ASSERT_EQ(beams.ranges.size(), 60u);  // step ⌊359 / 59⌋ = 6
  EXPECT_DOUBLE_EQ(beams.bearings[1], scan.BeamAngle(6));
  EXPECT_DOUBLE_EQ(beams.ranges[1], 30.0);
  EXPECT_DOUBLE_EQ(beams.range_max, 30.0);
}

// A Neato-like scan: 361 beams, only every third with a return. Evenly spaced beams keep the
// empty ones (the likelihood field skips them: a third of max_beams is used); selecting among
// the returns reads max_beams beams, all returns, spread over the whole scan.
TEST(SelectBeamsTest, AmongReturnsKeepsMaxBeamsReturns) {
  LaserScan scan;
  scan.max_range = 5.0;
  scan.angle_min = -kPi;
  scan.angle_increment = 2.0 * kPi / 360;
  scan.ranges.assign(361, 0.0);
  for (std::size_t i = 0; i < scan.ranges.size(); i += 3)
    scan.ranges[i] = 1.0 + 0.001 * static_cast<double>(i);
  AmclOptions options;
  const LaserBeams evenly = SelectBeams(scan, Pose2(), options);
  EXPECT_EQ(evenly.ranges.size(), 61u);  // step ⌊360 / 59⌋ = 6: beams 0, 6, ..., 360
  EXPECT_EQ(evenly.hits, 61);            // 6 is a multiple of 3: by chance all returns here
  scan.ranges.assign(361, 0.0);
  for (std::size_t i = 1; i < scan.ranges.size(); i += 3)
    scan.ranges[i] = 1.0 + 0.001 * static_cast<double>(i);
  EXPECT_EQ(SelectBeams(scan, Pose2(), options).hits, 0);  // the same beams, now all empty

  options.beam_selection = BeamSelection::kReturns;
  const LaserBeams returns = SelectBeams(scan, Pose2(), options);
  // 120 returns (beams 1, 4, ..., 358): every ⌊119 / 59⌋ = 2nd of them.
  ASSERT_EQ(returns.ranges.size(), 60u);
  EXPECT_EQ(returns.hits, 60);
  EXPECT_DOUBLE_EQ(returns.bearings[0], scan.BeamAngle(1));
  EXPECT_DOUBLE_EQ(returns.bearings[1], scan.BeamAngle(7));
  EXPECT_DOUBLE_EQ(returns.ranges[1], 1.007);
  EXPECT_DOUBLE_EQ(returns.bearings[59], scan.BeamAngle(355));
  for (const double r : returns.ranges) EXPECT_LT(r, returns.range_max);
}

}  // namespace
}  // namespace semchain::localization
