#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sim/world.h"

// Ray casting against a world's vertical surfaces: walls, semantic objects and obstacles are
// prisms standing on the floor, so a horizontal ray meets a surface when it crosses the
// surface's footprint edge and its height lies within the surface's vertical extent.
namespace semchain::sim {

// What a ray hit.
struct SurfaceRef {
  enum class Kind { kWall, kObject, kObstacle };
  Kind kind = Kind::kWall;
  int index = 0;  // wall polyline, or index into World::objects / World::obstacles
  int part = -1;  // index into the solid's parts; -1 for a wall or a solid that is one prism
  bool operator==(const SurfaceRef&) const = default;
};

struct RayHit {
  double distance = 0.0;  // metres from the ray origin, in the plane
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();  // unit, facing the ray origin
  double surface_u = 0.0;  // metres along the surface outline (texture coordinate)
  double bottom = 0.0;     // vertical extent of the surface, metres above the floor
  double top = 0.0;
  SurfaceRef surface;
};

class Scene {
 public:
  explicit Scene(const World& world);

  // The nearest surface met by the ray from 'origin' at heading 'angle' within 'max_range'
  // whose vertical extent contains 'height' (a lidar's scan plane), or nothing.
  std::optional<RayHit> CastAtHeight(const Eigen::Vector2d& origin, double angle, double max_range,
                                     double height) const;

  // Every surface the ray meets within 'max_range', nearest first, whatever its height (the
  // 2.5D renderer looks over low surfaces at taller ones behind them).
  std::vector<RayHit> CastAll(const Eigen::Vector2d& origin, double angle, double max_range) const;

  // True when 'point' lies inside a solid's footprint or closer than 'clearance' to any
  // surface (walls included).
  bool IsOccupied(const Eigen::Vector2d& point, double clearance) const;

  const World& world() const { return world_; }

 private:
  // A vertical disc standing on an edge's line (a clock's face): at a point 'o' metres along
  // the line from its centre, the disc spans height ± sqrt(radius² - o²).
  struct Disc {
    double radius = 0.0;  // 0: the edge is an ordinary face of a prism
    Eigen::Vector2d center = Eigen::Vector2d::Zero();
    Eigen::Vector2d axis = Eigen::Vector2d::UnitX();  // unit, along the disc's face
    double height = 0.0;
  };
  struct Edge {
    Eigen::Vector2d a, b;
    double u0 = 0.0;  // texture coordinate at 'a'
    double bottom = 0.0, top = 0.0;
    SurfaceRef surface;
    Disc disc;
  };
  struct Circle {
    Eigen::Vector2d center;
    double radius = 0.0;
    double bottom = 0.0, top = 0.0;
    SurfaceRef surface;
  };
  void AddSolid(const Solid& solid, SurfaceRef ref);
  void AddPrism(const Footprint& footprint, double bottom, double top, SurfaceRef ref,
                const Disc& disc);
  template <typename Visit>
  void ForEachHit(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction, double max_range,
                  Visit&& visit) const;

  World world_;
  std::vector<Edge> edges_;
  std::vector<Circle> circles_;
};

// The corners of a box footprint, counter-clockwise.
std::vector<Eigen::Vector2d> BoxCorners(const Footprint& footprint);

// True when 'point' is inside 'footprint'.
bool FootprintContains(const Footprint& footprint, const Eigen::Vector2d& point);

// True when 'point' is inside the polygon (even-odd rule).
bool PolygonContains(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& point);

}  // namespace semchain::sim
