#pragma once

#include "drawing/canvas.h"
#include "sim/world.h"

// A world drawn top-down on a drawing::TopDownCanvas (`semchain render`).
namespace semchain::sim {

// The region covered by the world's walls, solids, route and trial region.
drawing::Bounds WorldBounds(const World& world);

// The colour of class 'class_id' (a fixed palette; -1 and unknown classes are grey).
drawing::Color ClassColor(int class_id);

// Draws walls (black), semantic objects (filled with their class colour, legend by class),
// obstacles (grey), the mapping route (dashed) and the trial region (outline).
void DrawWorld(const World& world, drawing::TopDownCanvas& canvas);

}  // namespace semchain::sim
