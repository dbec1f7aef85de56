#pragma once

#include "sim/world.h"

namespace semchain::sim {

// An 8 m × 6 m room with a door, a cabinet, a bucket, a chair, a stool, a white column and a
// low box, built in code so that renderer tests and benchmarks need no world file. The robot
// starts at (2, 3) facing +x; its camera and detection model are the defaults of world.h.
World FurnishedRoomWorld();

}  // namespace semchain::sim
