#pragma once

#include "mapping/map_io.h"
#include "semantic/semantic_map.h"
#include "sim/world.h"

// Test fixtures made from a simulated world's truth (so that end-to-end tests do not spend their
// time on SLAM and semantic mapping).
namespace semchain::e2e {

// The maps a perfect SLAM and semantic mapping would make of 'world' (so that tests do
// not spend their time building them): cells within half a cell of a surface occupied, the rest
// of the walls' extent free, a margin unknown; the objects' true footprints, chained.
struct TruthMaps {
  mapping::MapImage occupancy;
  semantic::SemanticMap semantic;
};

TruthMaps MapsFromTruth(const sim::World& world);

}  // namespace semchain::e2e
