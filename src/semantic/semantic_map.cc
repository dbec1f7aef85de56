#include "semantic/semantic_map.h"

#include <cstddef>

namespace semchain::semantic {

const SemanticObject* SemanticMap::Find(int id) const {
  for (const SemanticObject& object : objects) {
    if (object.id == id) return &object;
  }
  return nullptr;
}

bool FindChainNeighbours(const SemanticMap& map, int id, ChainNeighbours* neighbours) {
  for (const SemanticChain& chain : map.chains) {
    const std::size_t n = chain.order.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (chain.order[i] != id) continue;
      if (n < 2 || chain.links.size() != n) return false;
      const ChainLink& down = chain.links[i];
      const ChainLink& up = chain.links[(i + n - 1) % n];
      *neighbours = {up.from, down.to, up.distance, down.distance};
      return true;
    }
  }
  return false;
}

}  // namespace semchain::semantic
