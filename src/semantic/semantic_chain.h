#pragma once

#include <Eigen/Core>
#include <map>
#include <opencv2/core.hpp>
#include <vector>

#include "mapping/map_io.h"
#include "semantic/grid_geometry.h"
#include "semantic/semantic_map.h"
#include "semantic/semantic_options.h"

// The semantic chain list (seed 000 Fig. 8, seed 001 Table 1) and the neighbour graph
// (DESIGN.md §3.5). The papers' rooms are single loops; a building has several rooms and
// corridors, so the free space is first cut into regions at its doorways and each region gets
// its own chain.
namespace semchain::semantic {

GridGeometry GeometryOf(const mapping::MapImage& map);

// Regions of the free space: the cores (cells farther than doorway_half_width from anything
// not free) are the seeds, and every free cell joins the core nearest to it through free space.
struct RegionMap {
  cv::Mat labels;                        // CV_32SC1, row = cell y; -1 outside every region
  std::vector<Eigen::Vector2d> centers;  // centroid of each region's free cells (map frame)
  int count() const { return static_cast<int>(centers.size()); }
};

RegionMap SegmentRegions(const mapping::MapImage& map, const ChainOptions& options);

// The region of an object: that of the nearest region cell in sight of its centre (a line
// that crosses no occupied cell outside the object), so that an object against a wall joins
// the room it stands in, not the one behind the wall. -1 when the map has no region.
int RegionOf(const RegionMap& regions, const mapping::MapImage& map, const SemanticObject& object);

// The order of 'objects' around 'center': clockwise, starting from the first door met going
// clockwise from north (from the first object after north when there is no door).
std::vector<int> ClockwiseOrder(const std::vector<SemanticObject>& objects,
                                const Eigen::Vector2d& center);

// The chain of the objects (ids in order): links between consecutive nodes and from the last
// back to the first.
SemanticChain MakeChain(int region, const std::vector<int>& order,
                        const std::vector<SemanticObject>& objects);

// True when the straight line between the two objects' centres crosses no occupied cell of
// 'map' outside the objects themselves.
bool MutuallyVisible(const mapping::MapImage& map, const SemanticObject& a,
                     const SemanticObject& b);

// Where the robot stood when it saw each object (by object id); may be empty.
using Viewpoints = std::map<int, std::vector<Eigen::Vector2d>>;

// The region most of the viewpoints lie in (the room the robot saw the object from); RegionOf
// when no viewpoint lies in a region.
int RegionOfViewed(const RegionMap& regions, const mapping::MapImage& map,
                   const SemanticObject& object, const std::vector<Eigen::Vector2d>& viewpoints);

// Fills map->chains (one per region holding objects) and map->neighbours.
void BuildChainsAndNeighbours(const mapping::MapImage& occupancy, const ChainOptions& options,
                              const Viewpoints& viewpoints, SemanticMap* map);

}  // namespace semchain::semantic
