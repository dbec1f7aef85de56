#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "sim/object_shapes.h"
#include "sim/world.h"

// Randomized furnished rooms for the detector's training set (semchain dataset, DESIGN.md
// §5.6): a rectangular room, sometimes with a partition, holding every one of the ten classes
// at least once (doors and clocks on the walls, cabinets, sofas and beds against them, tables
// with chairs and computers, stools and buckets anywhere), distractor obstacles of random shape
// and colour, and random wall, floor and light looks. Everything follows from the seed.
namespace semchain::sim {

struct RandomRoomOptions {
  double min_size_meters = 4.5;  // each side of the room
  double max_size_meters = 8.0;
  int extra_objects_max = 5;  // beyond one of each class
  int distractors_max = 4;    // non-semantic obstacles
  // The share of furniture given the footprint range of another class of its size group
  // (FootprintDonors): rooms put a sofa where a bed would stand, or a cabinet where a table
  // would, so a detector trained only on each class's own sizes names objects by their size.
  // 0 keeps every class to its own range (and every earlier seed's rooms unchanged).
  double borrowed_footprint_fraction = 0.0;
  // The share of clocks that stand on a table as a desk clock (a disc on a block up to 0.2 m
  // deep, DeskClockSizeRange) rather than hang on a wall: a detector that has only seen clocks
  // 1.8 m up on walls takes one on a desk for the computer that usually stands there. A clock
  // goes on the wall when there is no table. 0 keeps every earlier seed's rooms unchanged.
  double desk_clock_fraction = 0.0;
};

// Sizes of a desk clock (width, depth, height; its base is the table's top).
ClassSizeRange DeskClockSizeRange();

// The classes whose footprint ranges an object of 'class_name' may take: small furniture
// (bucket, cabinet, chair, stool) trade among themselves, large furniture (cabinet, table, sofa,
// bed) too; a cabinet belongs to both. Empty for the other classes.
std::vector<std::string> FootprintDonors(const std::string& class_name);

World RandomRoom(std::uint64_t seed, const RandomRoomOptions& options = {});

// A camera placement in a room: where the robot stands and how its camera is mounted.
struct CameraView {
  Pose2 robot_pose;
  CameraSpec camera;
};

// A camera at robot height (0.3–1.3 m) in the free space of 'world', aimed at object
// 'target' (an index into world.objects) from 0.8–5 m with a random heading offset, pitch and
// roll, with the exposure, noise and blur varied. 'width' × 'height' pixels. Nothing when no
// free spot sees the target after a number of tries.
std::optional<CameraView> RandomCameraView(const World& world, int target, int width, int height,
                                           std::uint64_t seed);

}  // namespace semchain::sim
