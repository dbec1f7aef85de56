#pragma once

#include "drawing/canvas.h"
#include "semantic/semantic_map.h"

namespace semchain::app {

// Draws the objects of a semantic map (footprints filled in their class colour, centres, ids)
// and its chains (arrows from each node to the next, clockwise) over whatever is on 'canvas'.
void DrawSemanticMap(const semantic::SemanticMap& map, drawing::TopDownCanvas& canvas);

}  // namespace semchain::app
