#include "semantic/map_folder.h"

#include <cstdio>

#include "semantic/semantic_map_io.h"

namespace semchain::semantic {
namespace {

Status CheckSemanticFitsMap(const SemanticMap& semantic, const mapping::MapImage& map,
                            const std::filesystem::path& semantic_path,
                            const std::filesystem::path& map_path) {
  const Eigen::Vector2d low = map.origin.head<2>();
  const Eigen::Vector2d high = low + map.resolution * Eigen::Vector2d(map.width, map.height);
  for (const SemanticObject& object : semantic.objects) {
    const Eigen::Vector2d& c = object.center;
    if ((c.array() < low.array()).any() || (c.array() > high.array()).any()) {
      char text[200];
      std::snprintf(text, sizeof(text), "object %d (%s) at (%.2f, %.2f) lies outside ", object.id,
                    object.class_name.c_str(), c.x(), c.y());
      return Status::Error(semantic_path.string() + ": " + text + map_path.string() +
                           ": map and semantic map do not belong together");
    }
  }
  return Status::Ok();
}

}  // namespace

Result<MapFolder> ReadMapFolder(const std::filesystem::path& dir) {
  MapFolder folder;
  Result<mapping::MapImage> map = mapping::ReadMap(dir / "map.yaml");
  if (!map.ok()) return map.status();
  folder.occupancy = std::move(*map);
  Result<SemanticMap> semantic = ReadSemanticJson(dir / "semantic.json");
  if (!semantic.ok()) return semantic.status();
  folder.semantic = std::move(*semantic);
  SEMCHAIN_RETURN_IF_ERROR(CheckSemanticFitsMap(folder.semantic, folder.occupancy,
                                                dir / "semantic.json", dir / "map.yaml"));
  folder.keyframes = dir / "keyframes.json";
  return folder;
}

}  // namespace semchain::semantic
