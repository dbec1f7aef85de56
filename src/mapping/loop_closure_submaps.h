#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/pose2.h"
#include "mapping/branch_and_bound_matcher.h"
#include "mapping/loop_closure_options.h"
#include "mapping/map_io.h"
#include "mapping/match_grid.h"
#include "mapping/occupancy_grid.h"

// The loop closer's submaps (loop_closure.cc) and what its searches need of them: finishing a
// submap, keeping its match grid built within the memory cap, the query a node matches against
// it and how a match agrees with the cells it observed. Apart from the closer's bookkeeping of
// nodes, edges and verification, which never looks inside a submap; not part of the API.
namespace semchain::mapping::internal {

// A rigid local map in the frame of its first node.
struct Submap {
  int first = 0;
  int last = 0;
  // While open: the grid scans go into. Once finished it keeps only its frame (an empty grid
  // with the same origin and resolution, for CellOf): what the searches need of it is kept as
  // an image at a byte a cell, where the grid takes 16 (a campus run has a hundred submaps).
  OccupancyGrid grid;
  bool finished = false;
  // Once finished: the grid's image (the match grid is built from it) and, cell by cell over its
  // extent, whether the grid observed the cell (the image's unknown also covers observed cells
  // of middling probability; a bit a cell: MIT Killian's masks took 50 MB as bytes);
  // image_min is its first cell in the grid's indices.
  MapImage image;
  std::vector<bool> observed;
  Eigen::Vector2i image_min = Eigen::Vector2i::Zero();
  // Once finished: the match grid's centre and the radius of its extent around it (metres)...
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
  // ...and, while built, the match grid and its matcher (which refers to the grid).
  std::unique_ptr<MatchGrid> match_grid;
  std::unique_ptr<BranchAndBoundMatcher> matcher;
  std::uint64_t last_used = 0;  // search counter when it was last needed built
};

// Finishes the open submap: keeps its grid's image and which cells it observed, empties the grid
// and builds the match grid and matcher.
void Finish(Submap* submap, const LoopClosureOptions& options);

// Builds 'wanted' if needed and marks it used at 'tick'; then, while more than
// options.max_built_submaps finished submaps are built, or they hold more than
// options.max_built_submaps_megabytes, frees the least recently used one other than 'wanted' and
// 'keep' (may be null). Returns the most the built submaps held (once 'wanted' was built).
double Acquire(Submap* wanted, const Submap* keep, std::uint64_t tick, std::vector<Submap>* submaps,
               const LoopClosureOptions& options);

// The match points of node i's scan and, with query_travel_meters > 0, of the scans of the nodes
// before it within that much travel, in node i's frame (placed by the graph's estimate), at most
// one per query_cell_meters cell. Down a corridor one scan sees few of the features that tell
// places apart (a 180° laser mostly sees the walls beside it); a short stretch of the local map
// sees each several times.
std::vector<Eigen::Vector2d> QueryPoints(
    const std::vector<std::vector<Eigen::Vector2d>>& node_points,
    const std::vector<Pose2>& estimate, const std::vector<double>& travel, std::size_t i,
    const LoopClosureOptions& options);

// How a query placed at 'pose' agrees with what the submap observed: the share of its points on
// observed cells and their mean M.
struct KnownAgreement {
  double fraction = 0.0;
  double score = 0.0;
};

KnownAgreement AgreementOnKnownCells(const Submap& submap,
                                     const std::vector<Eigen::Vector2d>& points, const Pose2& pose);

}  // namespace semchain::mapping::internal
