#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

// The semantic map of DESIGN.md §3.4–3.5 and §5.4: objects on the occupancy map, one chain per
// region (seed 000 Fig. 8, seed 001 Table 1) and a neighbour graph.
namespace semchain::semantic {

struct SemanticObject {
  int id = 0;
  std::string class_name;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // map frame, metres
  std::vector<Eigen::Vector2d> footprint;            // polygon, counter-clockwise
  int observations = 0;                              // frames in which it was detected
  double confidence = 0.0;                           // mean cell probability, 0..1
};

struct ChainLink {
  int from = 0;  // object ids
  int to = 0;
  double distance = 0.0;  // between the centres, metres
};

// The objects of one region in chain order (a door first when the region has one, then
// clockwise around the region's centre); links join consecutive objects and the last to the
// first, so that every node has an upstream and a downstream neighbour.
struct SemanticChain {
  int region = 0;
  std::vector<int> order;
  std::vector<ChainLink> links;
};

struct SemanticMap {
  std::vector<std::string> classes;
  std::vector<SemanticObject> objects;
  std::vector<SemanticChain> chains;
  std::vector<ChainLink> neighbours;  // the k nearest mutually visible objects of each object

  // The object with 'id', or nullptr.
  const SemanticObject* Find(int id) const;
};

// A node's neighbours in its chain (upstream = previous, downstream = next).
struct ChainNeighbours {
  int upstream = -1;  // object ids; -1 when the chain has a single node
  int downstream = -1;
  double upstream_distance = 0.0;
  double downstream_distance = 0.0;
};

// The chain neighbours of object 'id', when it is in a chain of at least two nodes.
bool FindChainNeighbours(const SemanticMap& map, int id, ChainNeighbours* neighbours);

}  // namespace semchain::semantic
