// The filter's output for a fixed seed, pinned: poses and weights of particles, the estimate and
// the recovery averages after each update of two seeded runs, compared with the values the
// filter produced before its speed-ups (testdata/amcl_regression_*.inc, written by the
// pre-change code). A speed-up must not change what the filter computes.
//
// To rewrite the fixture (only when a change of the filter's results is intended and
// explained), run from the repository root:
//   SEMCHAIN_AMCL_FIXTURE_OUT=src/localization/testdata
//     build/src/localization/localization_test --gtest_filter='AmclRegression*'
// (one command line).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "localization/amcl.h"
#include "mapping/testing/synthetic_map.h"

namespace semchain::localization {
namespace {

constexpr double kExpectedGlobal[] = {
#include "localization/testdata/amcl_regression_global.inc"
};
constexpr double kExpectedTracking[] = {
#include "localization/testdata/amcl_regression_tracking.inc"
};

// Appends what the filter computed after one update: counts, estimate, recovery averages, sums
// over all particles and every 499th particle's pose and weight.
void Record(const Amcl& amcl, std::vector<double>* trace) {
  const AmclEstimate e = amcl.Estimate();
  const std::vector<Particle>& particles = amcl.particles();
  trace->insert(trace->end(),
                {static_cast<double>(particles.size()), static_cast<double>(e.clusters), e.pose.x,
                 e.pose.y, e.pose.theta, e.cluster_weight, e.covariance(0, 0), e.covariance(1, 1),
                 e.covariance(2, 2), amcl.w_slow(), amcl.w_fast(), amcl.mean_beam_likelihood(),
                 static_cast<double>(amcl.counters().random_particles)});
  double x = 0.0, y = 0.0, theta = 0.0, weight = 0.0;
  for (const Particle& p : particles) {
    x += p.pose.x;
    y += p.pose.y;
    theta += p.pose.theta;
    weight += p.weight;
  }
  trace->insert(trace->end(), {x, y, theta, weight});
  for (std::size_t i = 0; i < particles.size(); i += 499) {
    const Particle& p = particles[i];
    trace->insert(trace->end(), {p.pose.x, p.pose.y, p.pose.theta, p.weight});
  }
}

// Feeds the first 'scans' scans of the simulated room run; records every filter update.
std::vector<double> Trace(Amcl& amcl, int scans) {
  const mapping::testing::SimulatedRun run = mapping::testing::SimulateRoomRun(0.1, 0.01, 3);
  std::vector<double> trace;
  for (int i = 0; i < scans && i < static_cast<int>(run.scans.size()); ++i) {
    const StampedScan& s = run.scans[static_cast<std::size_t>(i)];
    if (amcl.ProcessScan(s.scan, s.odometry, s.LaserOffset())) Record(amcl, &trace);
  }
  return trace;
}

// Writes 'trace' as the body of a C array when SEMCHAIN_AMCL_FIXTURE_OUT names a folder;
// returns whether it did.
bool WriteFixture(const std::vector<double>& trace, const std::string& name) {
  const char* folder = std::getenv("SEMCHAIN_AMCL_FIXTURE_OUT");
  if (folder == nullptr) return false;
  const std::string path = std::string(folder) + "/amcl_regression_" + name + ".inc";
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return false;
  std::fprintf(file, "// Written by amcl_regression_test from the filter before its speed-ups.\n");
  for (const double v : trace) std::fprintf(file, "%.17g,\n", v);
  std::fclose(file);
  return true;
}

template <std::size_t N>
void ExpectSameTrace(const std::vector<double>& trace, const double (&expected)[N]) {
  ASSERT_EQ(trace.size(), N);
  for (std::size_t i = 0; i < N; ++i) {
    // Relative 1e-12: room for a different (but exact-in-intent) rounding, not for any change
    // in which particles were drawn.
    ASSERT_NEAR(trace[i], expected[i], 1e-12 * std::max(1.0, std::abs(expected[i])))
        << "trace value " << i;
  }
}

class AmclRegression : public ::testing::Test {
 protected:
  AmclRegression() : map_(mapping::testing::RoomMap(), AmclOptions().laser_likelihood_max_dist) {}
  LocalizationMap map_;
};

// Global localization with KLD resampling and random-particle recovery at work.
TEST_F(AmclRegression, GlobalLocalizationMatchesThePreChangeFilter) {
  AmclOptions options;
  options.max_particles = 4000;
  options.min_particles = 300;
  options.recovery_alpha_slow = 0.001;
  options.recovery_alpha_fast = 0.1;
  Amcl amcl(map_, options, MakeRng(11, 2));
  amcl.InitializeGlobal();
  const std::vector<double> trace = Trace(amcl, 60);
  if (WriteFixture(trace, "global")) GTEST_SKIP() << "fixture written";
  ExpectSameTrace(trace, kExpectedGlobal);
}

// Tracking from an initial pose with nav2's defaults.
TEST_F(AmclRegression, TrackingMatchesThePreChangeFilter) {
  AmclOptions options;
  Amcl amcl(map_, options, MakeRng(12, 5));
  amcl.InitializePose(Pose2(-3.7, -3.1, 0.05), Eigen::Vector3d(0.04, 0.04, 0.01).asDiagonal());
  const std::vector<double> trace = Trace(amcl, 80);
  if (WriteFixture(trace, "tracking")) GTEST_SKIP() << "fixture written";
  ExpectSameTrace(trace, kExpectedTracking);
}

}  // namespace
}  // namespace semchain::localization
