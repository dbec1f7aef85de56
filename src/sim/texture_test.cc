#include "sim/texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace semchain::sim {
namespace {

constexpr std::array<std::uint8_t, 3> kGrey = {200, 200, 200};

// Mean and spread of a texture's brightness over a 2 m × 1 m patch, sampled every 7 mm.
std::pair<double, double> Statistics(const SurfaceTexture& texture, double footprint) {
  double sum = 0.0, sum_sq = 0.0;
  int n = 0;
  for (double u = 0.0; u < 2.0; u += 0.007) {
    for (double v = 0.0; v < 1.0; v += 0.007) {
      const double value = texture.Intensity(u, v, footprint);
      sum += value;
      sum_sq += value * value;
      ++n;
    }
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum_sq / n - mean * mean))};
}

TEST(TextureTest, SameSeedSameColoursDifferentSeedsDiffer) {
  const SurfaceTexture a(17, kGrey), b(17, kGrey), c(18, kGrey);
  double difference = 0.0;
  for (double u = 0.0; u < 2.0; u += 0.013) {
    EXPECT_EQ(a.Intensity(u, 0.37, 0.005), b.Intensity(u, 0.37, 0.005));
    difference += std::abs(a.Intensity(u, 0.37, 0.005) - c.Intensity(u, 0.37, 0.005));
  }
  EXPECT_GT(difference / (2.0 / 0.013), 0.05);
}

TEST(TextureTest, EveryPatternOccursAndHasContrastUpClose) {
  std::set<TexturePattern> seen;
  for (std::uint32_t seed = 1; seed <= 64; ++seed) {
    const SurfaceTexture texture(seed, kGrey);
    seen.insert(texture.pattern());
    const auto [mean, spread] = Statistics(texture, 0.005);
    EXPECT_GT(spread, 0.12) << "seed " << seed;  // enough for a corner detector
    EXPECT_GT(mean, 0.15);
    EXPECT_LT(mean, 0.9);
  }
  EXPECT_EQ(seen.size(), 4u);
}

TEST(TextureTest, DetailFadesWhenPixelsGrowLarge) {
  for (std::uint32_t seed = 1; seed <= 16; ++seed) {
    const SurfaceTexture texture(seed, kGrey);
    // At 0.5 m per pixel nothing of a 0.1–0.5 m pattern survives but the slow drift.
    EXPECT_LT(Statistics(texture, 0.5).second, 0.6 * Statistics(texture, 0.005).second)
        << "seed " << seed;
  }
}

TEST(TextureTest, TintFollowsTheBaseColour) {
  const SurfaceTexture red(5, {220, 40, 40});
  double r = 0.0, g = 0.0;
  for (double u = 0.0; u < 1.0; u += 0.01) {
    const Rgb color = red.Sample(u, 0.5, 0.005);
    r += color.r;
    g += color.g;
    EXPECT_GE(color.r, 0.0f);
    EXPECT_LE(color.r, 255.0f);
  }
  EXPECT_GT(r, 1.5 * g);
}

TEST(TextureTest, SeedsDependOnWorldWallAndSegment) {
  EXPECT_NE(WallTextureSeed(0, 0, 0), WallTextureSeed(0, 0, 1));
  EXPECT_NE(WallTextureSeed(0, 0, 0), WallTextureSeed(0, 1, 0));
  EXPECT_NE(WallTextureSeed(0, 0, 0), WallTextureSeed(1, 0, 0));
  Solid solid;
  solid.texture_seed = 99;
  EXPECT_EQ(SolidTextureSeed(3, solid, {SurfaceRef::Kind::kObject, 2}), 99u);
  solid.texture_seed = 0;
  EXPECT_NE(SolidTextureSeed(3, solid, {SurfaceRef::Kind::kObject, 2}),
            SolidTextureSeed(3, solid, {SurfaceRef::Kind::kObstacle, 2}));
}

}  // namespace
}  // namespace semchain::sim
