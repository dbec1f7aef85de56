#include "sim/object_shapes.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "sim/texture.h"

namespace semchain::sim {
namespace {

using Color = std::array<std::uint8_t, 3>;

// Draws for one object's details: each call to Next() is a new uniform number in [0, 1) that
// depends only on the object's seed and how many came before.
class Draws {
 public:
  explicit Draws(std::uint32_t seed) : seed_(seed) {}
  double Next() { return HashToUnit(seed_, 0x5a4e, count_++); }
  double Between(double lo, double hi) { return lo + (hi - lo) * Next(); }
  bool Chance(double p) { return Next() < p; }
  template <typename T>
  const T& Pick(const std::vector<T>& items) {
    const auto i = static_cast<std::size_t>(Next() * static_cast<double>(items.size()));
    return items[std::min(i, items.size() - 1)];
  }

 private:
  std::uint64_t seed_;
  std::int64_t count_ = 0;
};

std::uint8_t Clamp255(double value) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L));
}

// 'color' scaled by 'brightness' and moved by up to 'jitter' of full scale per channel.
Color Shift(const Color& color, double brightness, double jitter, Draws& draws) {
  Color out;
  for (int c = 0; c < 3; ++c) {
    out[c] = Clamp255(color[c] * brightness + 255.0 * jitter * (2.0 * draws.Next() - 1.0));
  }
  return out;
}

struct Palette {
  std::vector<Color> colors;
  std::vector<TextureFamily> textures;
};

const Palette& PaletteOf(const std::string& class_name) {
  using T = TextureFamily;
  static const std::map<std::string, Palette> kPalettes = {
      {"door",
       {{{150, 100, 60}, {120, 80, 50}, {235, 232, 225}, {180, 170, 150}, {90, 100, 110}},
        {T::kWood, T::kWood, T::kPaint}}},
      {"cabinet",
       {{{165, 120, 75}, {225, 225, 220}, {130, 135, 140}, {95, 110, 135}, {60, 60, 65}},
        {T::kWood, T::kPaint, T::kMetal}}},
      {"bucket",
       {{{200, 40, 40}, {40, 90, 190}, {230, 190, 40}, {50, 150, 70}, {160, 165, 170}},
        {T::kPlastic, T::kPlastic, T::kMetal}}},
      {"chair",
       {{{60, 60, 65}, {140, 95, 60}, {40, 70, 140}, {150, 40, 40}, {90, 130, 90}},
        {T::kFabric, T::kWood, T::kPlastic}}},
      {"stool",
       {{{170, 130, 80}, {60, 60, 60}, {200, 60, 50}, {210, 210, 205}, {120, 90, 60}},
        {T::kWood, T::kPlastic, T::kMetal}}},
      {"table",
       {{{175, 130, 85}, {235, 235, 230}, {110, 80, 55}, {150, 150, 150}, {60, 55, 50}},
        {T::kWood, T::kWood, T::kPaint, T::kPlastic}}},
      {"sofa",
       {{{110, 110, 115}, {60, 80, 130}, {130, 90, 60}, {80, 110, 80}, {200, 185, 160}},
        {T::kFabric, T::kFabric, T::kPlastic}}},
      {"computer",
       {{{30, 30, 35}, {70, 70, 75}, {215, 215, 215}, {150, 150, 155}},
        {T::kPlastic, T::kPlastic, T::kMetal}}},
      {"bed",
       {{{170, 130, 85}, {235, 235, 235}, {100, 70, 50}, {70, 80, 100}, {180, 175, 165}},
        {T::kWood, T::kPaint, T::kFabric}}},
      {"clock",
       {{{30, 30, 30}, {160, 110, 60}, {200, 200, 205}, {170, 40, 40}, {235, 235, 230}},
        {T::kPlastic, T::kWood, T::kMetal}}},
  };
  static const Palette kGeneric = {{{150, 150, 150}}, {T::kPaint}};
  const auto it = kPalettes.find(class_name);
  return it == kPalettes.end() ? kGeneric : it->second;
}

// The parts of one object, in its frame; the builders below append to it.
class Builder {
 public:
  explicit Builder(const Solid& solid)
      : solid_(solid), draws_(solid.texture_seed ^ 0x9a37u), main_(solid.color) {
    const Footprint& f = solid.footprint;
    round_ = f.shape == Footprint::Shape::kCircle;
    width_ = round_ ? 2.0 * f.radius : f.width;
    depth_ = round_ ? 2.0 * f.radius : f.depth;
    height_ = solid.height;
  }

  double W() const { return width_; }
  double D() const { return depth_; }
  double H() const { return height_; }
  bool round() const { return round_; }
  Draws& draws() { return draws_; }
  const Color& main() const { return main_; }
  TextureFamily main_texture() const {
    return solid_.texture == TextureFamily::kPattern ? TextureFamily::kPaint : solid_.texture;
  }
  Color Shade(double brightness, double jitter = 0.03) {
    return Shift(main_, brightness, jitter, draws_);
  }

  // A box part (w × d) centred at (x, y), from z0 to z1 above the base.
  Part& Box(double x, double y, double w, double d, double z0, double z1, const Color& color,
            TextureFamily texture) {
    return Add(PlacePart(solid_, x, y, w, d, 0.0, z0, z1), color, texture);
  }
  Part& Cylinder(double x, double y, double r, double z0, double z1, const Color& color,
                 TextureFamily texture) {
    return Add(PlacePart(solid_, x, y, 0.0, 0.0, r, z0, z1), color, texture);
  }
  // A vertical disc of 'diameter' in a slab of thickness d centred at (x, y), its centre 'zc'
  // above the base.
  Part& Disc(double x, double y, double diameter, double d, double zc, const Color& color,
             TextureFamily texture) {
    Part& part = Box(x, y, diameter, d, zc - 0.5 * diameter, zc + 0.5 * diameter, color, texture);
    part.profile = Part::Profile::kDisc;
    return part;
  }

  std::vector<Part> Take() { return std::move(parts_); }

 private:
  Part& Add(Part part, const Color& color, TextureFamily texture) {
    // A detail that does not fit an unusually small object is left out.
    const Footprint& f = part.footprint;
    const bool empty =
        f.shape == Footprint::Shape::kCircle ? f.radius <= 0.0 : f.width <= 0.0 || f.depth <= 0.0;
    if (empty || part.top <= part.bottom) return discarded_ = part;
    part.color = color;
    part.texture = texture;
    part.texture_seed = solid_.texture_seed * 31u + static_cast<std::uint32_t>(parts_.size()) + 1u;
    parts_.push_back(part);
    return parts_.back();
  }

  const Solid& solid_;
  Draws draws_;
  Color main_;
  bool round_ = false;
  double width_ = 0.0, depth_ = 0.0, height_ = 0.0;
  std::vector<Part> parts_;
  Part discarded_;
};

// std::clamp without its precondition: an object too small for a detail's usual range gets
// the upper bound.
double Fit(double value, double lo, double hi) { return std::min(std::max(value, lo), hi); }

const Color kMetalGrey = {150, 152, 158};
const Color kBlack = {25, 25, 28};

// Metal or wood legs, in a colour that contrasts with the main one.
std::pair<Color, TextureFamily> LegLook(Builder& b) {
  if (b.draws().Chance(0.5))
    return {Shift(kMetalGrey, 1.0, 0.08, b.draws()), TextureFamily::kMetal};
  if (b.draws().Chance(0.3)) return {Shift(kBlack, 1.0, 0.03, b.draws()), TextureFamily::kPaint};
  return {Shift({140, 100, 65}, 1.0, 0.08, b.draws()), TextureFamily::kWood};
}

// Four legs of size 'leg' inset 'inset' from the corners of a w × d rectangle centred at
// (0, y), from z0 to z1; round legs when 'round'.
void FourLegs(Builder& b, double w, double d, double y, double leg, double inset, double z0,
              double z1, const std::pair<Color, TextureFamily>& look, bool round) {
  const double x = 0.5 * w - inset - 0.5 * leg;
  const double yy = 0.5 * d - inset - 0.5 * leg;
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      if (round) {
        b.Cylinder(sx * x, y + sy * yy, 0.5 * leg, z0, z1, look.first, look.second);
      } else {
        b.Box(sx * x, y + sy * yy, leg, leg, z0, z1, look.first, look.second);
      }
    }
  }
}

void BuildDoor(Builder& b) {
  const double W = b.W(), D = b.D(), H = b.H();
  const double jamb = std::min(0.07, 0.1 * W);
  const Color frame =
      b.draws().Chance(0.5) ? b.Shade(0.8) : Shift({235, 235, 230}, 1.0, 0.03, b.draws());
  b.Box(-0.5 * W + 0.5 * jamb, 0.0, jamb, D, 0.0, H, frame, TextureFamily::kPaint);
  b.Box(0.5 * W - 0.5 * jamb, 0.0, jamb, D, 0.0, H, frame, TextureFamily::kPaint);
  b.Box(0.0, 0.0, W - 2.0 * jamb, D, H - jamb, H, frame, TextureFamily::kPaint);
  const double leaf_w = W - 2.0 * jamb, leaf_top = H - jamb;
  b.Box(0.0, 0.0, leaf_w, 0.45 * D, 0.01, leaf_top, b.main(), b.main_texture());
  // Raised panels on both faces: two or four, a lighter or darker shade of the leaf.
  const Color panel = b.Shade(b.draws().Chance(0.5) ? 0.85 : 1.12);
  const int columns = b.draws().Chance(0.4) ? 2 : 1;
  const double margin = 0.12 * leaf_w, gap = 0.08 * leaf_w;
  const double panel_w = (leaf_w - 2.0 * margin - (columns - 1) * gap) / columns;
  for (int c = 0; c < columns; ++c) {
    const double x = -0.5 * leaf_w + margin + 0.5 * panel_w + c * (panel_w + gap);
    b.Box(x, 0.0, panel_w, 0.65 * D, 0.10 * leaf_top, 0.42 * leaf_top, panel, b.main_texture());
    b.Box(x, 0.0, panel_w, 0.65 * D, 0.52 * leaf_top, 0.90 * leaf_top, panel, b.main_texture());
  }
  // The handle stands out on both faces, near the edge away from the hinges.
  const double side = b.draws().Chance(0.5) ? 1.0 : -1.0;
  const double handle_z = std::min(0.98, 0.45 * H);
  b.Box(side * (0.5 * leaf_w - 0.09), 0.0, 0.13, 0.95 * D, handle_z, handle_z + 0.05,
        Shift(kMetalGrey, 1.05, 0.05, b.draws()), TextureFamily::kMetal);
}

void BuildCabinet(Builder& b) {
  const double W = b.W(), D = b.D(), H = b.H();
  const double plinth = std::min(0.08, 0.1 * H);
  const double body_d = D - 0.04;
  b.Box(0.0, 0.5 * D - 0.5 * body_d, W, body_d, plinth, H, b.main(), b.main_texture());
  b.Box(0.0, 0.5 * D - 0.5 * body_d, W - 0.04, body_d - 0.04, 0.0, plinth, b.Shade(0.5),
        TextureFamily::kPaint);
  const Color front = b.Shade(b.draws().Chance(0.5) ? 0.88 : 1.1);
  const auto handle_look =
      std::make_pair(Shift(kMetalGrey, 1.0, 0.06, b.draws()), TextureFamily::kMetal);
  const double front_y = -0.5 * D + 0.03, handle_y = -0.5 * D + 0.01;
  const double inner_h = H - plinth - 0.04;
  if (b.draws().Chance(0.35) && inner_h > 0.3) {  // drawers
    const int rows = std::clamp(static_cast<int>(inner_h / 0.25), 2, 6);
    const double row_h = inner_h / rows;
    for (int r = 0; r < rows; ++r) {
      const double z0 = plinth + 0.02 + r * row_h;
      b.Box(0.0, front_y, W - 0.03, 0.02, z0 + 0.01, z0 + row_h - 0.01, front, b.main_texture());
      b.Box(0.0, handle_y, std::min(0.25, 0.4 * W), 0.02, z0 + 0.6 * row_h, z0 + 0.6 * row_h + 0.02,
            handle_look.first, handle_look.second);
    }
    return;
  }
  const int doors = W > 0.6 ? 2 : 1;
  const double door_w = (W - 0.02) / doors;
  for (int d = 0; d < doors; ++d) {
    const double x = -0.5 * W + 0.01 + (d + 0.5) * door_w;
    b.Box(x, front_y, door_w - 0.01, 0.02, plinth + 0.02, H - 0.02, front, b.main_texture());
    // Vertical handles beside the doors' meeting edge (or the free edge of a single door).
    const double edge = doors == 2 ? (d == 0 ? 1.0 : -1.0) : 1.0;
    const double hx = x + edge * (0.5 * door_w - 0.05);
    const double hz = plinth + 0.5 * inner_h + std::min(0.3, 0.2 * inner_h);
    b.Box(hx, handle_y, 0.02, 0.02, hz - std::min(0.12, 0.15 * inner_h), hz, handle_look.first,
          handle_look.second);
  }
}

void BuildBucket(Builder& b) {
  const double r = 0.5 * b.W(), H = b.H();
  b.Cylinder(0.0, 0.0, r - 0.012, 0.0, H - 0.03, b.main(), b.main_texture());
  b.Cylinder(0.0, 0.0, r, H - 0.03, H, b.Shade(0.8), b.main_texture());        // the rim
  b.Cylinder(0.0, 0.0, r - 0.008, 0.0, 0.02, b.Shade(0.7), b.main_texture());  // the foot ring
}

void BuildChair(Builder& b) {
  const double W = b.W(), D = b.D(), H = b.H();
  const double seat_top = Fit(b.draws().Between(0.42, 0.48), 0.3 * H, H - 0.25);
  const double seat_t = b.draws().Between(0.03, 0.06);
  const double back_d = b.draws().Between(0.03, 0.05);
  const double leg = b.draws().Between(0.025, 0.04);
  const auto legs = LegLook(b);
  const bool round_legs = b.draws().Chance(0.4);
  FourLegs(b, W, D, 0.0, leg, 0.02, 0.0, seat_top - seat_t, legs, round_legs);
  b.Box(0.0, 0.0, W, D, seat_top - seat_t, seat_top, b.main(), b.main_texture());
  const double back_y = 0.5 * D - 0.5 * back_d;
  if (b.draws().Chance(0.5)) {  // a solid back
    b.Box(0.0, back_y, W, back_d, seat_top, H, b.Shade(0.95), b.main_texture());
  } else {  // two posts and a backrest board
    const double post = 0.03;
    for (const double sx : {-1.0, 1.0}) {
      b.Box(sx * (0.5 * W - 0.5 * post), back_y, post, back_d, seat_top, H, legs.first,
            legs.second);
    }
    const double board_h = std::min(0.25, 0.6 * (H - seat_top));
    b.Box(0.0, back_y, W - 2.0 * post, back_d, H - board_h, H - 0.01, b.Shade(0.95),
          b.main_texture());
  }
}

void BuildStool(Builder& b) {
  const double W = b.W(), D = b.D(), H = b.H();
  const double seat_t = b.draws().Between(0.03, 0.05);
  const auto legs = LegLook(b);
  if (b.round()) {
    b.Cylinder(0.0, 0.0, 0.5 * W, H - seat_t, H, b.main(), b.main_texture());
    const int count = b.draws().Chance(0.5) ? 3 : 4;
    const double leg_r = b.draws().Between(0.012, 0.02);
    const double at = 0.5 * W - leg_r - 0.025;
    const double turn = b.draws().Between(0.0, 2.0 * M_PI);
    for (int i = 0; i < count; ++i) {
      const double a = turn + 2.0 * M_PI * i / count;
      b.Cylinder(at * std::cos(a), at * std::sin(a), leg_r, 0.0, H - seat_t, legs.first,
                 legs.second);
    }
    return;
  }
  b.Box(0.0, 0.0, W, D, H - seat_t, H, b.main(), b.main_texture());
  FourLegs(b, W, D, 0.0, b.draws().Between(0.025, 0.04), 0.015, 0.0, H - seat_t, legs,
           b.draws().Chance(0.5));
  // Rungs between the legs, above the lidar's plane.
  const double rung_z = std::min(0.3, 0.5 * (H - seat_t));
  b.Box(0.0, 0.0, W - 0.06, 0.02, rung_z, rung_z + 0.02, legs.first, legs.second);
}

void BuildTable(Builder& b) {
  const double W = b.W(), D = b.D(), H = b.H();
  const double top_t = b.draws().Between(0.025, 0.05);
  const double leg = b.draws().Between(0.04, 0.07);
  const auto legs =
      b.draws().Chance(0.5) ? std::make_pair(b.Shade(0.8), b.main_texture()) : LegLook(b);
  b.Box(0.0, 0.0, W, D, H - top_t, H, b.main(), b.main_texture());
  const double inset = b.draws().Between(0.02, 0.08);
  FourLegs(b, W, D, 0.0, leg, inset, 0.0, H - top_t, legs, b.draws().Chance(0.4));
  if (b.draws().Chance(0.5)) {  // an apron under the top's long edges
    const double apron = 0.08;
    for (const double sy : {-1.0, 1.0}) {
      b.Box(0.0, sy * (0.5 * D - inset - 0.5 * leg), W - 2.0 * (inset + leg), 0.02,
            H - top_t - apron, H - top_t, legs.first, legs.second);
    }
  }
}

void BuildSofa(Builder& b) {
  const double W = b.W(), D = b.D(), H = b.H();
  const double foot = 0.08, seat_top = std::min(0.45, 0.55 * H);
  const double back_d = std::min(0.22, 0.25 * D),
               arm_w = std::min(b.draws().Between(0.12, 0.22), 0.2 * W);
  const double arm_top = std::min(seat_top + b.draws().Between(0.12, 0.22), H - 0.05);
  const Color feet = Shift(kBlack, 1.0, 0.03, b.draws());
  FourLegs(b, W, D, 0.0, 0.05, 0.03, 0.0, foot, {feet, TextureFamily::kWood}, false);
  const double seat_d = D - back_d;
  const double seat_y = -0.5 * D + 0.5 * seat_d;
  b.Box(0.0, seat_y, W - 2.0 * arm_w, seat_d, foot, seat_top - 0.1, b.Shade(0.85),
        b.main_texture());
  b.Box(0.0, 0.5 * D - 0.5 * back_d, W, back_d, foot, H, b.main(), b.main_texture());
  for (const double sx : {-1.0, 1.0}) {
    b.Box(sx * (0.5 * W - 0.5 * arm_w), seat_y, arm_w, seat_d, foot, arm_top, b.Shade(0.95),
          b.main_texture());
  }
  // Seat cushions with gaps between them, a lighter shade.
  const int cushions = std::clamp(static_cast<int>((W - 2.0 * arm_w) / 0.6), 1, 4);
  const double cushion_w = (W - 2.0 * arm_w) / cushions;
  const Color cushion = b.Shade(1.1);
  for (int c = 0; c < cushions; ++c) {
    const double x = -0.5 * W + arm_w + (c + 0.5) * cushion_w;
    b.Box(x, seat_y, cushion_w - 0.02, seat_d - 0.02, seat_top - 0.1, seat_top, cushion,
          b.main_texture());
  }
}

void BuildComputer(Builder& b) {
  const double W = b.W(), D = b.D(), H = b.H();
  const double bezel_d = std::min(0.04, 0.3 * D);
  const double stand_h = Fit(b.draws().Between(0.08, 0.14), 0.05, 0.4 * H);
  const double screen_y = 0.5 * D - 0.05 - bezel_d;  // near the back edge of the footprint
  const double base_d = std::min(0.18, D - 0.01);
  b.Box(0.0, 0.5 * D - 0.5 * base_d - 0.005, std::min(0.24, 0.6 * W), base_d, 0.0, 0.015,
        b.Shade(0.9), b.main_texture());
  b.Box(0.0, screen_y + 0.5 * bezel_d + 0.02, 0.05, 0.03, 0.015, stand_h + 0.05, b.Shade(0.9),
        b.main_texture());
  b.Box(0.0, screen_y, W, bezel_d, stand_h, H, b.main(), b.main_texture());
  // The screen, slightly in front of the bezel: dark, or showing a bright picture.
  const bool on = b.draws().Chance(0.5);
  const Color screen =
      on ? Shift({90, 130, 190}, 1.0, 0.15, b.draws()) : Shift({20, 25, 35}, 1.0, 0.02, b.draws());
  b.Box(0.0, screen_y - 0.5 * bezel_d - 0.003, W - 0.04, 0.006, stand_h + 0.02, H - 0.02, screen,
        on ? TextureFamily::kPattern : TextureFamily::kPlastic);
}

void BuildBed(Builder& b) {
  const double W = b.W(), D = b.D(), H = b.H();
  const double head_d = 0.06, frame_top = std::min(0.3, 0.4 * H);
  const double mattress_top = std::min(frame_top + b.draws().Between(0.15, 0.25), H - 0.05);
  const double body_d = D - head_d, body_y = -0.5 * D + 0.5 * body_d;
  FourLegs(b, W, body_d, body_y, 0.06, 0.0, 0.0, 0.1, {b.Shade(0.7), b.main_texture()}, false);
  b.Box(0.0, body_y, W, body_d, 0.1, frame_top, b.main(), b.main_texture());
  b.Box(0.0, 0.5 * D - 0.5 * head_d, W, head_d, 0.0, H, b.Shade(0.9), b.main_texture());
  const Color duvet_palette[] = {
      {235, 235, 235}, {120, 150, 200}, {200, 170, 150}, {150, 180, 140}, {190, 80, 80}};
  const Color duvet = Shift(duvet_palette[std::min(4, static_cast<int>(5.0 * b.draws().Next()))],
                            1.0, 0.05, b.draws());
  b.Box(0.0, body_y, W - 0.04, body_d - 0.02, frame_top, mattress_top, duvet,
        TextureFamily::kFabric);
  const int pillows = W > 1.2 ? 2 : 1;
  const double pillow_w = (W - 0.1) / pillows - 0.05;
  for (int p = 0; p < pillows; ++p) {
    const double x = -0.5 * (W - 0.1) + (p + 0.5) * (W - 0.1) / pillows;
    b.Box(x, 0.5 * D - head_d - 0.2, pillow_w, 0.35, mattress_top, std::min(mattress_top + 0.1, H),
          Shift({240, 240, 238}, 1.0, 0.02, b.draws()), TextureFamily::kFabric);
  }
}

void BuildClock(Builder& b) {
  const double W = b.W(), D = b.D();
  const double zc = 0.5 * b.H();
  const double diameter = std::min(W, b.H());
  const double rim = std::clamp(0.08 * diameter, 0.01, 0.03);
  const double hands_d = 0.004, face_d = 0.006;
  const double back_d = D - hands_d - face_d;
  b.Disc(0.0, 0.5 * D - 0.5 * back_d, diameter, back_d, zc, b.main(), b.main_texture());
  const Color face = Shift({238, 236, 228}, 1.0, 0.03, b.draws());
  b.Disc(0.0, -0.5 * D + hands_d + 0.5 * face_d, diameter - 2.0 * rim, face_d, zc, face,
         TextureFamily::kPaint);
  // Two hands at right angles (the parts are upright prisms: each hand is vertical or level).
  const Color hand = Shift(kBlack, 1.0, 0.02, b.draws());
  const double r = 0.5 * diameter - rim;
  const double hour = b.draws().Chance(0.5) ? 1.0 : -1.0,
               minute = b.draws().Chance(0.5) ? 1.0 : -1.0;
  const double y = -0.5 * D + 0.5 * hands_d;
  b.Box(0.0, y, 0.012, hands_d, hour > 0 ? zc : zc - 0.55 * r, hour > 0 ? zc + 0.55 * r : zc, hand,
        TextureFamily::kPaint);
  b.Box(minute * 0.4 * r, y, 0.8 * r, hands_d, zc - 0.005, zc + 0.005, hand, TextureFamily::kPaint);
}

using ShapeBuilder = std::function<void(Builder&)>;

const std::map<std::string, ShapeBuilder>& Builders() {
  static const std::map<std::string, ShapeBuilder> kBuilders = {
      {"door", BuildDoor},   {"cabinet", BuildCabinet},   {"bucket", BuildBucket},
      {"chair", BuildChair}, {"stool", BuildStool},       {"table", BuildTable},
      {"sofa", BuildSofa},   {"computer", BuildComputer}, {"bed", BuildBed},
      {"clock", BuildClock}};
  return kBuilders;
}

}  // namespace

bool HasClassShape(const std::string& class_name) { return Builders().count(class_name) > 0; }

ClassLook DrawClassLook(const std::string& class_name, std::uint32_t seed) {
  Draws draws(seed ^ 0x10c4u);
  const Palette& palette = PaletteOf(class_name);
  ClassLook look;
  look.color = Shift(draws.Pick(palette.colors), draws.Between(0.85, 1.15), 0.06, draws);
  look.texture = draws.Pick(palette.textures);
  return look;
}

ClassSizeRange SizeRangeOf(const std::string& class_name) {
  static const std::map<std::string, ClassSizeRange> kRanges = {
      {"door", {0.8, 1.0, 0.08, 0.12, 1.95, 2.15}},
      {"cabinet", {0.4, 1.2, 0.35, 0.6, 0.7, 2.0}},
      {"bucket", {0.24, 0.4, 0.24, 0.4, 0.25, 0.45, 0.0, 0.0, true}},
      {"chair", {0.42, 0.55, 0.42, 0.52, 0.8, 1.0}},
      {"stool", {0.3, 0.42, 0.3, 0.42, 0.45, 0.75}},
      {"table", {0.8, 1.6, 0.6, 0.9, 0.7, 0.78}},
      {"sofa", {1.4, 2.2, 0.8, 0.95, 0.75, 0.9}},
      {"computer", {0.4, 0.6, 0.18, 0.25, 0.35, 0.5}},
      {"bed", {0.9, 1.8, 1.95, 2.1, 0.8, 1.1}},
      {"clock", {0.25, 0.4, 0.04, 0.06, 0.25, 0.4, 1.8, 2.0}},
  };
  const auto it = kRanges.find(class_name);
  return it == kRanges.end() ? ClassSizeRange{0.3, 1.0, 0.3, 1.0, 0.3, 1.0} : it->second;
}

Part PlacePart(const Solid& solid, double x, double y, double w, double d, double r, double z0,
               double z1) {
  const Footprint& f = solid.footprint;
  const double c = std::cos(f.yaw), s = std::sin(f.yaw);
  Part part;
  part.footprint.center = f.center + Eigen::Vector2d(c * x - s * y, s * x + c * y);
  part.footprint.yaw = f.yaw;
  if (r > 0.0) {
    part.footprint.shape = Footprint::Shape::kCircle;
    part.footprint.radius = r;
  } else {
    part.footprint.width = w;
    part.footprint.depth = d;
  }
  part.bottom = solid.base_height + z0;
  part.top = solid.base_height + z1;
  return part;
}

std::vector<Part> BuildClassParts(const Solid& solid) {
  const auto it = Builders().find(solid.class_name);
  if (it == Builders().end()) return {};
  Builder builder(solid);
  it->second(builder);
  return builder.Take();
}

}  // namespace semchain::sim
