// Geometric sanity checks of a parsed world (see ValidateWorld in world_io.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/angles.h"
#include "core/cross2.h"
#include "sim/scene.h"
#include "sim/world_io.h"

namespace semchain::sim {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

// True when segments ab and cd cross at a point interior to both (touching does not count).
bool SegmentsCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double d1 = Cross(b - a, c - a), d2 = Cross(b - a, d - a);
  const double d3 = Cross(d - c, a - c), d4 = Cross(d - c, b - c);
  constexpr double kEps = 1e-9;
  return ((d1 > kEps && d2 < -kEps) || (d1 < -kEps && d2 > kEps)) &&
         ((d3 > kEps && d4 < -kEps) || (d3 < -kEps && d4 > kEps));
}

// The footprint's outline; a circle becomes a 32-gon (inscribed, 0.5% smaller at worst).
Polygon Outline(const Footprint& footprint) {
  if (footprint.shape == Footprint::Shape::kBox) return BoxCorners(footprint);
  Polygon polygon;
  for (int i = 0; i < 32; ++i) {
    const double angle = 2.0 * kPi * i / 32.0;
    polygon.push_back(footprint.center +
                      footprint.radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return polygon;
}

bool OutlineCrossesSegment(const Polygon& outline, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  for (std::size_t i = 0; i < outline.size(); ++i) {
    if (SegmentsCross(outline[i], outline[(i + 1) % outline.size()], a, b)) return true;
  }
  return PolygonContains(outline, a) || PolygonContains(outline, b);
}

bool OutlinesOverlap(const Polygon& p, const Polygon& q) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (OutlineCrossesSegment(q, p[i], p[(i + 1) % p.size()])) return true;
  }
  return PolygonContains(p, q.front()) || PolygonContains(q, p.front());
}

std::string Point(const Eigen::Vector2d& p) {
  char text[64];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f)", p.x(), p.y());
  return text;
}

struct NamedSolid {
  std::string path;  // "objects[3]"
  const Solid* solid;
};

Status CheckSolids(const World& world, const std::vector<NamedSolid>& solids) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e18), high = -low;
  for (const auto& line : world.walls) {
    for (const auto& p : line) low = low.cwiseMin(p), high = high.cwiseMax(p);
  }
  for (std::size_t i = 0; i < solids.size(); ++i) {
    const Solid& solid = *solids[i].solid;
    const Eigen::Vector2d& c = solid.footprint.center;
    const std::string what = solids[i].path + " at " + Point(c);
    if ((c.array() < low.array()).any() || (c.array() > high.array()).any()) {
      return Status::Error(what + " lies outside the walls");
    }
    const Polygon outline = Outline(solid.footprint);
    for (std::size_t w = 0; w < world.walls.size() && solid.class_name != "door"; ++w) {
      for (std::size_t k = 0; k + 1 < world.walls[w].size(); ++k) {
        if (OutlineCrossesSegment(outline, world.walls[w][k], world.walls[w][k + 1])) {
          return Status::Error(what + " crosses walls[" + std::to_string(w) + "]");
        }
      }
    }
    for (std::size_t j = 0; j < i; ++j) {
      // One may stand on the other (a computer on a table): their heights must not overlap.
      const Solid& other = *solids[j].solid;
      const bool stacked = solid.base_height >= other.base_height + other.height - 1e-9 ||
                           other.base_height >= solid.base_height + solid.height - 1e-9;
      if (!stacked && OutlinesOverlap(outline, Outline(other.footprint))) {
        return Status::Error(what + " overlaps " + solids[j].path);
      }
    }
  }
  return Status::Ok();
}

// 'labels[i]' names path[i] in the error.
Status CheckPath(const Scene& scene, const std::vector<Eigen::Vector2d>& path,
                 const std::vector<std::string>& labels, double clearance) {
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const double length = (path[i + 1] - path[i]).norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(length / 0.02)));
    for (int s = 0; s <= steps; ++s) {
      const Eigen::Vector2d p = path[i] + (path[i + 1] - path[i]) * (double(s) / steps);
      if (scene.IsOccupied(p, clearance)) {
        return Status::Error("the route from " + labels[i] + " to " + labels[i + 1] +
                             " passes within " + std::to_string(clearance).substr(0, 4) +
                             " m of a surface at " + Point(p));
      }
    }
  }
  return Status::Ok();
}

}  // namespace

Status ValidateWorld(const World& world, const std::string& source_name, double clearance) {
  if (clearance < 0.0) clearance = world.robot.radius;
  std::vector<NamedSolid> solids;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    solids.push_back({"objects[" + std::to_string(i) + "]", &world.objects[i]});
  }
  for (std::size_t i = 0; i < world.obstacles.size(); ++i) {
    solids.push_back({"obstacles[" + std::to_string(i) + "]", &world.obstacles[i]});
  }
  SEMCHAIN_RETURN_IF_ERROR(CheckSolids(world, solids).WithContext(source_name));
  const Scene scene(world);
  const Eigen::Vector2d start = world.robot.start.translation();
  if (scene.IsOccupied(start, clearance)) {
    return Status::Error(source_name + ": robot.start " + Point(start) + " is within " +
                         std::to_string(clearance).substr(0, 4) + " m of a surface");
  }
  if (!world.mapping_route.empty()) {
    std::vector<Eigen::Vector2d> route = {start};
    std::vector<std::string> labels = {"robot.start"};
    for (std::size_t i = 0; i < world.mapping_route.size(); ++i) {
      route.push_back(world.mapping_route[i]);
      labels.push_back("mapping_route[" + std::to_string(i) + "]");
    }
    SEMCHAIN_RETURN_IF_ERROR(CheckPath(scene, route, labels, clearance).WithContext(source_name));
  }
  return Status::Ok();
}

}  // namespace semchain::sim
