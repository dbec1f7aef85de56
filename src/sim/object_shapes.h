#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/world.h"

// The ten object classes of seed 000's data set (§2.1) as shapes built from parts, each part
// with its own height range, so that lidar, depth, colour and truth boxes all come from one
// geometry: a table is a top on four legs (the lidar at 0.19 m meets four legs, the camera sees
// the top and the floor between the legs), a chair a seat, a back and legs, a clock a disc on a
// wall. Proportions, secondary colours and details (drawers or doors, three or four legs, the
// clock's hands) vary per instance with the object's texture seed.
//
// Object frame: x along the footprint's yaw (its width), y across it (its depth). An object's
// front faces -y; its back (a chair's back, a sofa's back, a bed's headboard, the side of a
// cabinet or a clock that touches the wall) is at +y.
namespace semchain::sim {

// True when 'class_name' has a shape built from parts (one of DefaultClassNames(): door,
// cabinet, bucket, chair, stool, table, sofa, computer, bed, clock).
bool HasClassShape(const std::string& class_name);

// A class's typical look: a main colour drawn from its palette with a random shift, and a
// texture family that suits it (wood or paint for doors, fabric for sofas, ...).
struct ClassLook {
  std::array<std::uint8_t, 3> color = {200, 200, 200};
  TextureFamily texture = TextureFamily::kPaint;
};
ClassLook DrawClassLook(const std::string& class_name, std::uint32_t seed);

// The size range of a class (metres) the randomized rooms draw from. A disc's or cylinder's
// diameter is its width; 'base' is where it starts above the floor (a clock's lower edge; a
// computer stands on whatever is under it).
struct ClassSizeRange {
  double width_min, width_max;
  double depth_min, depth_max;
  double height_min, height_max;
  double base_min = 0.0, base_max = 0.0;
  bool round = false;  // a circular footprint (bucket; stools drawn round or square)
};
ClassSizeRange SizeRangeOf(const std::string& class_name);

// The parts of semantic object 'solid' of one of the ten classes, from its footprint, height,
// base height, colour (the main surfaces), texture family and texture seed. Every part lies
// inside the footprint and between base_height and base_height + height.
std::vector<Part> BuildClassParts(const Solid& solid);

// A part of 'solid' placed in its object frame: centre (x, y), a box w × d (or a circle of
// radius r when r > 0) between heights z0 and z1 above the object's base.
Part PlacePart(const Solid& solid, double x, double y, double w, double d, double r, double z0,
               double z1);

}  // namespace semchain::sim
