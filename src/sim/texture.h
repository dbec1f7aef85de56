#pragma once

#include <array>
#include <cstdint>

#include "sim/scene.h"

// Seeded procedural textures for the renderer's walls and solids (DESIGN.md §3.1). A texture is
// a function of surface coordinates in metres (u along the outline, v the height; x and y on
// horizontal faces), so a point of a surface has the same colour from every viewpoint and ORB
// finds the same corners in every frame that sees it.
namespace semchain::sim {

// An RGB colour with channels in [0, 255].
struct Rgb {
  float r = 0.0f;
  float g = 0.0f;
  float b = 0.0f;
};

enum class TexturePattern {
  kBricks,  // staggered rows of bricks with mortar joints
  kTiles,   // a square grid of tiles of strongly varying brightness
  kBlobs,   // two-tone spots from thresholded value noise
  kPanels,  // posters: a rectangle (with an inset) in each cell of a coarse grid
  // The finishes of TextureFamily (world.h) other than kPattern:
  kWoodGrain,  // planks with wavy grain lines and knots
  kWeave,      // fabric: a fine weave over a mottled dye
  kBrushed,    // metal: fine streaks along u, a soft sheen
  kSmooth,     // plastic: nearly uniform, faint mottling and scuffs
  kPaint,      // painted plaster: uniform with a slow roller mottle and rare marks
};

class SurfaceTexture {
 public:
  // The pattern, its scale and its details all follow from 'seed'; 'base_color' tints it.
  SurfaceTexture(std::uint32_t seed, const std::array<std::uint8_t, 3>& base_color);
  // A texture of 'family': kPattern is the constructor above, the others their finish.
  SurfaceTexture(std::uint32_t seed, const std::array<std::uint8_t, 3>& base_color,
                 TextureFamily family);

  // The colour at surface coordinates (u, v) in metres. 'footprint' is the size in metres of
  // one pixel there: detail finer than about two pixels fades to its mean instead of aliasing.
  Rgb Sample(double u, double v, double footprint) const;

  // Brightness in [0, 1] before tinting; Sample() maps it between a dark and a light shade.
  double Intensity(double u, double v, double footprint) const;

  TexturePattern pattern() const { return pattern_; }

 private:
  double Bricks(double u, double v, double footprint, bool staggered) const;
  double Blobs(double u, double v, double footprint) const;
  double Panels(double u, double v, double footprint) const;
  double Speckles(double u, double v, double footprint) const;
  double WoodGrain(double u, double v, double footprint) const;
  double Weave(double u, double v, double footprint) const;
  double Brushed(double u, double v, double footprint) const;
  double Smooth(double u, double v, double footprint, double marks) const;

  std::uint64_t seed_;
  TexturePattern pattern_;
  double cell_width_;   // metres: brick / tile / blob / panel size along u
  double cell_height_;  // metres: along v
  double joint_;        // metres: mortar or grout width
  Rgb dark_;
  Rgb light_;
};

// The texture seed of segment 'segment' of wall polyline 'wall_index' in a world seeded
// 'world_seed' (walls carry no seed of their own). Each straight stretch of wall gets its own
// pattern, as the walls of a real room differ (and a place recogniser can tell them apart).
std::uint32_t WallTextureSeed(std::uint32_t world_seed, int wall_index, int segment);

// The texture seed of a solid: its own 'texture_seed' when set (LoadWorld always sets one),
// otherwise one derived from the world seed, what it is (object or obstacle) and its index.
std::uint32_t SolidTextureSeed(std::uint32_t world_seed, const Solid& solid, const SurfaceRef& ref);

// The base colour of a wall seeded 'wall_seed' (WallTextureSeed): a light, varied paint.
std::array<std::uint8_t, 3> WallColor(std::uint32_t wall_seed);

// A uniform number in [0, 1) that depends only on its arguments (a hash, not a generator).
double HashToUnit(std::uint64_t seed, std::int64_t a, std::int64_t b = 0);

}  // namespace semchain::sim
