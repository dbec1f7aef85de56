#include "sim/texture.h"

#include <algorithm>
#include <cmath>

namespace semchain::sim {
namespace {

// SplitMix64's finaliser: a cheap, well-mixed 64-bit hash.
std::uint64_t Mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double Clamp01(double x) { return std::clamp(x, 0.0, 1.0); }

constexpr double kPiLocal = 3.14159265358979323846;

// How much of a pixel 'footprint' wide, centred 'distance' inside an edge, lies inside: a box
// filter of the step, so edges stay sharp up close and blend instead of flickering far away.
double Coverage(double distance, double footprint) { return Clamp01(distance / footprint + 0.5); }

// Value noise: hashed values on the integer lattice, blended with smoothstep weights.
double ValueNoise(std::uint64_t seed, double x, double y) {
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  const auto ix = static_cast<std::int64_t>(fx);
  const auto iy = static_cast<std::int64_t>(fy);
  const double tx = x - fx;
  const double ty = y - fy;
  const double sx = tx * tx * (3.0 - 2.0 * tx);
  const double sy = ty * ty * (3.0 - 2.0 * ty);
  const double a = HashToUnit(seed, ix, iy);
  const double b = HashToUnit(seed, ix + 1, iy);
  const double c = HashToUnit(seed, ix, iy + 1);
  const double d = HashToUnit(seed, ix + 1, iy + 1);
  return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

// Fades 'value' to 'mean' when the pattern's cells shrink below about two pixels.
double FadeFineDetail(double value, double mean, double cell, double footprint) {
  const double keep = Clamp01((cell / footprint - 2.0) / 2.0);
  return mean + keep * (value - mean);
}

float Channel(std::uint8_t value, double scale, double add) {
  return static_cast<float>(std::clamp(value * scale + add * (255.0 - value), 0.0, 255.0));
}

}  // namespace

double HashToUnit(std::uint64_t seed, std::int64_t a, std::int64_t b) {
  const std::uint64_t h = Mix(seed + static_cast<std::uint64_t>(a) * 0x632be59bd9b4e019ULL +
                              static_cast<std::uint64_t>(b) * 0x85157af5ULL);
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

SurfaceTexture::SurfaceTexture(std::uint32_t seed, const std::array<std::uint8_t, 3>& base)
    : seed_(Mix(seed)) {
  const auto r = [this](int k) { return HashToUnit(seed_, -1, k); };
  pattern_ = static_cast<TexturePattern>(std::min(3, static_cast<int>(4.0 * r(0))));
  switch (pattern_) {
    case TexturePattern::kBricks:
      cell_width_ = 0.20 + 0.10 * r(1);
      cell_height_ = 0.08 + 0.04 * r(2);
      joint_ = 0.012 + 0.008 * r(3);
      break;
    case TexturePattern::kTiles:
      cell_width_ = cell_height_ = 0.12 + 0.10 * r(1);
      joint_ = 0.008 + 0.004 * r(3);
      break;
    case TexturePattern::kBlobs:
      cell_width_ = cell_height_ = 0.12 + 0.08 * r(1);
      joint_ = 0.0;
      break;
    case TexturePattern::kPanels:
    default:  // the finishes are set by the other constructor
      cell_width_ = 0.22 + 0.16 * r(1);
      cell_height_ = 0.22 + 0.16 * r(2);
      joint_ = 0.0;
      break;
  }
  // Dark and light shades of the base colour; both far enough apart that a dark object still
  // shows its pattern to a corner detector.
  dark_ = {Channel(base[0], 0.3, 0.0), Channel(base[1], 0.3, 0.0), Channel(base[2], 0.3, 0.0)};
  light_ = {Channel(base[0], 1.0, 0.4), Channel(base[1], 1.0, 0.4), Channel(base[2], 1.0, 0.4)};
}

SurfaceTexture::SurfaceTexture(std::uint32_t seed, const std::array<std::uint8_t, 3>& base,
                               TextureFamily family)
    : SurfaceTexture(seed, base) {
  if (family == TextureFamily::kPattern) return;
  const auto r = [this](int k) { return HashToUnit(seed_, -2, k); };
  joint_ = 0.0;
  // Finishes vary less than the patterns: a narrower band around the base colour.
  double dark = 0.55, light = 0.25;
  switch (family) {
    case TextureFamily::kWood:
      pattern_ = TexturePattern::kWoodGrain;
      cell_width_ = 0.09 + 0.12 * r(1);  // plank width
      cell_height_ = 0.6 + 0.8 * r(2);   // plank length
      joint_ = 0.002 + 0.002 * r(3);
      break;
    case TextureFamily::kFabric:
      pattern_ = TexturePattern::kWeave;
      cell_width_ = cell_height_ = 0.004 + 0.004 * r(1);  // thread spacing
      dark = 0.65, light = 0.2;
      break;
    case TextureFamily::kMetal:
      pattern_ = TexturePattern::kBrushed;
      cell_width_ = cell_height_ = 0.3 + 0.4 * r(1);
      dark = 0.7, light = 0.35;
      break;
    case TextureFamily::kPlastic:
      pattern_ = TexturePattern::kSmooth;
      cell_width_ = cell_height_ = 0.25 + 0.3 * r(1);
      dark = 0.8, light = 0.15;
      break;
    case TextureFamily::kPaint:
    case TextureFamily::kPattern:
      pattern_ = TexturePattern::kPaint;
      cell_width_ = cell_height_ = 0.4 + 0.5 * r(1);
      dark = 0.8, light = 0.12;
      break;
  }
  dark_ = {Channel(base[0], dark, 0.0), Channel(base[1], dark, 0.0), Channel(base[2], dark, 0.0)};
  light_ = {Channel(base[0], 1.0, light), Channel(base[1], 1.0, light),
            Channel(base[2], 1.0, light)};
}

double SurfaceTexture::Intensity(double u, double v, double footprint) const {
  footprint = std::max(footprint, 1e-6);
  switch (pattern_) {
    case TexturePattern::kWoodGrain:
      return Clamp01(WoodGrain(u, v, footprint));
    case TexturePattern::kWeave:
      return Clamp01(Weave(u, v, footprint));
    case TexturePattern::kBrushed:
      return Clamp01(Brushed(u, v, footprint));
    case TexturePattern::kSmooth:
      return Clamp01(Smooth(u, v, footprint, 0.1));
    case TexturePattern::kPaint:
      return Clamp01(Smooth(u, v, footprint, 0.04));
    default:
      break;
  }
  double value = 0.0;
  switch (pattern_) {
    case TexturePattern::kBricks:
      value = Bricks(u, v, footprint, /*staggered=*/true);
      break;
    case TexturePattern::kTiles:
      value = Bricks(u, v, footprint, /*staggered=*/false);
      break;
    case TexturePattern::kBlobs:
      value = Blobs(u, v, footprint);
      break;
    case TexturePattern::kPanels:
      value = Panels(u, v, footprint);
      break;
    default:
      break;
  }
  // A slow brightness drift (0.9 m cells) so that repeats of a pattern still look different.
  const double drift = 0.85 + 0.3 * ValueNoise(seed_ + 7, u / 0.9, v / 0.9);
  return Clamp01(value * drift + Speckles(u, v, footprint));
}

Rgb SurfaceTexture::Sample(double u, double v, double footprint) const {
  const auto t = static_cast<float>(Intensity(u, v, footprint));
  return {dark_.r + t * (light_.r - dark_.r), dark_.g + t * (light_.g - dark_.g),
          dark_.b + t * (light_.b - dark_.b)};
}

double SurfaceTexture::Bricks(double u, double v, double footprint, bool staggered) const {
  const double row = std::floor(v / cell_height_);
  const double shift = staggered && std::fmod(std::abs(row), 2.0) == 1.0 ? 0.5 * cell_width_ : 0.0;
  const double col = std::floor((u + shift) / cell_width_);
  const double du = u + shift - col * cell_width_;
  const double dv = v - row * cell_height_;
  const double h =
      HashToUnit(seed_, static_cast<std::int64_t>(col), static_cast<std::int64_t>(row));
  // Tiles vary more than bricks: their joints are thinner, so the tiles must carry the corners.
  const double brick = staggered ? 0.4 + 0.6 * h : 0.1 + 0.9 * h;
  const double inside = std::min(std::min(du, cell_width_ - du), std::min(dv, cell_height_ - dv));
  const double cover = Coverage(inside - 0.5 * joint_, footprint);
  const double value = 0.08 + cover * (brick - 0.08);
  return FadeFineDetail(value, staggered ? 0.65 : 0.55, cell_height_, footprint);
}

double SurfaceTexture::Blobs(double u, double v, double footprint) const {
  const double s = cell_width_;
  const double n = 0.65 * ValueNoise(seed_ + 1, u / s, v / s) +
                   0.35 * ValueNoise(seed_ + 2, u / (0.45 * s), v / (0.45 * s));
  // The noise changes by about 1 per cell, so a pixel spans footprint / s of it.
  const double edge = std::max(footprint / (0.45 * s), 0.02);
  const double spot = Clamp01((n - 0.5) / edge + 0.5);
  return FadeFineDetail(0.12 + 0.83 * spot, 0.5, 0.45 * s, footprint);
}

double SurfaceTexture::Speckles(double u, double v, double footprint) const {
  // Sharp-edged spots a few centimetres across: the corners a camera finds up close, where
  // the main pattern's cells are larger than the view. They fade out with distance.
  constexpr double kSize = 0.035;
  if (footprint > 0.5 * kSize) return 0.0;
  const double n = ValueNoise(seed_ + 3, u / kSize, v / kSize);
  const double edge = std::max(footprint / kSize, 0.02);
  const double spot = Clamp01((n - 0.62) / edge + 0.5);
  return FadeFineDetail(-0.22 * spot, -0.22 * 0.25, kSize, footprint);
}

double SurfaceTexture::Panels(double u, double v, double footprint) const {
  const double cu = std::floor(u / cell_width_);
  const double cv = std::floor(v / cell_height_);
  const double x = u / cell_width_ - cu;  // position in the cell, in [0, 1)
  const double y = v / cell_height_ - cv;
  // Eight numbers per cell, 16 bits each, from two hashes (the pattern's hot path).
  const std::uint64_t cell =
      static_cast<std::uint64_t>(static_cast<std::int64_t>(cu)) * 0x632be59bd9b4e019ULL +
      static_cast<std::uint64_t>(static_cast<std::int64_t>(cv)) * 0x85157af5ULL;
  const std::uint64_t bits[2] = {Mix(seed_ + cell), Mix(seed_ + 0x9e37ULL + cell)};
  const auto h = [&](int k) {
    return static_cast<double>((bits[k / 4] >> (16 * (k % 4))) & 0xffffU) / 65536.0;
  };
  const double fu = footprint / cell_width_;
  const double fv = footprint / cell_height_;
  // The coverage of a rectangle [x0, x1] × [y0, y1] of the cell by the pixel.
  const auto rect = [&](double x0, double x1, double y0, double y1) {
    return Coverage(std::min(x - x0, x1 - x), fu) * Coverage(std::min(y - y0, y1 - y), fv);
  };
  const double x0 = 0.06 + 0.2 * h(0), x1 = 0.7 + 0.24 * h(1);
  const double y0 = 0.06 + 0.2 * h(2), y1 = 0.7 + 0.24 * h(3);
  const double outer = 0.05 + 0.9 * h(4);
  const double inner = h(5) < 0.5 ? outer + 0.45 : outer - 0.45;  // contrasts with the outer
  const double ix0 = x0 + (x1 - x0) * (0.15 + 0.3 * h(6)), ix1 = ix0 + 0.3 * (x1 - x0);
  const double iy0 = y0 + (y1 - y0) * (0.15 + 0.3 * h(7)), iy1 = iy0 + 0.35 * (y1 - y0);
  double value = 0.5 + rect(x0, x1, y0, y1) * (outer - 0.5);
  value += rect(ix0, ix1, iy0, iy1) * (Clamp01(inner) - value);
  return FadeFineDetail(value, 0.5, 0.3 * std::min(cell_width_, cell_height_), footprint);
}

double SurfaceTexture::WoodGrain(double u, double v, double footprint) const {
  // Planks run along v (upright parts) with staggered ends; grain lines wave along them.
  const double column = std::floor(u / cell_width_);
  const double offset = cell_height_ * HashToUnit(seed_, static_cast<std::int64_t>(column), 1);
  const double row = std::floor((v + offset) / cell_height_);
  const double plank =
      HashToUnit(seed_, static_cast<std::int64_t>(column), static_cast<std::int64_t>(row) + 7);
  const double du = u - column * cell_width_;
  const double dv = v + offset - row * cell_height_;
  const double wave =
      0.012 * std::sin(v * 9.0 + 6.0 * plank) + 0.02 * ValueNoise(seed_ + 11, u / 0.05, v / 0.4);
  const double grain_pitch = 0.006 + 0.006 * plank;
  const double grain = 0.5 + 0.5 * std::sin(2.0 * kPiLocal * (du + wave) / grain_pitch);
  const double base = 0.35 + 0.4 * plank;
  double value = base + FadeFineDetail(0.25 * (grain - 0.5), 0.0, grain_pitch, footprint);
  const double inside = std::min(std::min(du, cell_width_ - du), std::min(dv, cell_height_ - dv));
  value *= 0.55 + 0.45 * Coverage(inside - 0.5 * joint_, footprint);
  // A knot now and then: a dark spot a few centimetres across.
  const double knot = ValueNoise(seed_ + 12, u / 0.04, v / 0.04);
  value -= FadeFineDetail(0.3 * Clamp01((knot - 0.82) / 0.05), 0.0, 0.04, footprint);
  return value;
}

double SurfaceTexture::Weave(double u, double v, double footprint) const {
  const double s = cell_width_;
  const double thread =
      0.5 + 0.25 * (std::sin(2.0 * kPiLocal * u / s) * std::sin(2.0 * kPiLocal * v / s));
  const double mottle = ValueNoise(seed_ + 21, u / 0.07, v / 0.07);
  const double seams = ValueNoise(seed_ + 22, u / 0.25, v / 0.25);
  return 0.3 + 0.35 * mottle + 0.2 * seams + FadeFineDetail(thread - 0.5, 0.0, s, footprint);
}

double SurfaceTexture::Brushed(double u, double v, double footprint) const {
  // Streaks: noise stretched 40 times along u.
  const double streak = ValueNoise(seed_ + 31, u / 0.4, v / 0.004);
  const double sheen = ValueNoise(seed_ + 32, u / cell_width_, v / cell_height_);
  return 0.35 + 0.45 * sheen + FadeFineDetail(0.2 * (streak - 0.5), 0.0, 0.004, footprint) +
         0.5 * Speckles(u, v, footprint);
}

double SurfaceTexture::Smooth(double u, double v, double footprint, double marks) const {
  const double mottle = ValueNoise(seed_ + 41, u / cell_width_, v / cell_height_);
  const double scuff = ValueNoise(seed_ + 42, u / 0.03, v / 0.03);
  const double mark = FadeFineDetail(Clamp01((scuff - 0.8) / 0.06), 0.0, 0.03, footprint);
  return 0.45 + 0.35 * mottle - marks * 3.0 * mark;
}

std::uint32_t WallTextureSeed(std::uint32_t world_seed, int wall_index, int segment) {
  const std::uint64_t wall = Mix(0x57a11ULL + static_cast<std::uint64_t>(wall_index));
  return static_cast<std::uint32_t>(Mix((static_cast<std::uint64_t>(world_seed) << 32) ^
                                        Mix(wall + static_cast<std::uint64_t>(segment))));
}

std::uint32_t SolidTextureSeed(std::uint32_t world_seed, const Solid& solid,
                               const SurfaceRef& ref) {
  if (solid.texture_seed != 0) return solid.texture_seed;
  const std::uint64_t kind = ref.kind == SurfaceRef::Kind::kObject ? 0x0b1ecULL : 0x0b57ULL;
  return static_cast<std::uint32_t>(
      Mix((static_cast<std::uint64_t>(world_seed) << 32) ^
          Mix(kind * 1000003ULL + static_cast<std::uint64_t>(ref.index))));
}

std::array<std::uint8_t, 3> WallColor(std::uint32_t wall_seed) {
  const std::uint64_t seed = wall_seed;
  const auto channel = [&](int k, double lo) {
    return static_cast<std::uint8_t>(lo + (245.0 - lo) * HashToUnit(seed, 11, k));
  };
  return {channel(0, 190.0), channel(1, 180.0), channel(2, 160.0)};
}

}  // namespace semchain::sim
