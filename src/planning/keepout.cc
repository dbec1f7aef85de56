#include "planning/keepout.h"

#include "io/yaml_reader.h"

namespace semchain::planning {

Result<std::vector<Polygon>> ReadKeepoutZones(const std::filesystem::path& path) {
  Result<yaml::Node> root = yaml::Node::LoadFile(path);
  if (!root.ok()) return root.status();
  if (!root->IsMap()) return root->Error("expected a map with the key 'keepout'");
  SEMCHAIN_RETURN_IF_ERROR(root->CheckKeys({"keepout"}));
  const Result<yaml::Node> zones = root->Get("keepout");
  if (!zones.ok()) return zones.status();
  if (!zones->IsSequence()) return zones->Error("expected a list of polygons");
  std::vector<Polygon> polygons;
  for (std::size_t i = 0; i < zones->size(); ++i) {
    const yaml::Node zone = zones->At(i);
    if (!zone.IsSequence() || zone.size() < 3) {
      return zone.Error("expected a polygon of at least 3 [x, y] points");
    }
    Polygon polygon;
    for (std::size_t k = 0; k < zone.size(); ++k) {
      const Result<std::vector<double>> point = zone.At(k).AsDoubleList(2);
      if (!point.ok()) return point.status();
      polygon.emplace_back((*point)[0], (*point)[1]);
    }
    polygons.push_back(std::move(polygon));
  }
  return polygons;
}

}  // namespace semchain::planning
