#include "sim/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/cross2.h"

namespace semchain::sim {
namespace {

double DistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length_sq = ab.squaredNorm();
  const double t = length_sq > 0.0 ? std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

std::vector<Eigen::Vector2d> BoxCorners(const Footprint& f) {
  const Eigen::Vector2d along(std::cos(f.yaw), std::sin(f.yaw));
  const Eigen::Vector2d across(-along.y(), along.x());
  const Eigen::Vector2d half_w = 0.5 * f.width * along;
  const Eigen::Vector2d half_d = 0.5 * f.depth * across;
  return {f.center - half_w - half_d, f.center + half_w - half_d, f.center + half_w + half_d,
          f.center - half_w + half_d};
}

bool FootprintContains(const Footprint& f, const Eigen::Vector2d& point) {
  const Eigen::Vector2d d = point - f.center;
  if (f.shape == Footprint::Shape::kCircle) return d.norm() <= f.radius;
  const double along = d.x() * std::cos(f.yaw) + d.y() * std::sin(f.yaw);
  const double across = -d.x() * std::sin(f.yaw) + d.y() * std::cos(f.yaw);
  return std::abs(along) <= 0.5 * f.width && std::abs(across) <= 0.5 * f.depth;
}

bool PolygonContains(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

Scene::Scene(const World& world) : world_(world) {
  for (std::size_t w = 0; w < world_.walls.size(); ++w) {
    const auto& line = world_.walls[w];
    double u = 0.0;
    const SurfaceRef ref{SurfaceRef::Kind::kWall, static_cast<int>(w)};
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const double length = (line[i + 1] - line[i]).norm();
      if (world_.wall_thickness <= 0.0 || length <= 0.0) {
        edges_.push_back({line[i], line[i + 1], u, 0.0, world_.wall_height, ref, Disc{}});
      } else {
        // A thick wall is the outline of a slab around the segment, lengthened by half the
        // thickness at both ends so that slabs meeting at a corner overlap (no gap).
        const Eigen::Vector2d along = (line[i + 1] - line[i]) / length;
        const Eigen::Vector2d half_along = 0.5 * world_.wall_thickness * along;
        const Eigen::Vector2d half_across(-half_along.y(), half_along.x());
        const Eigen::Vector2d a = line[i] - half_along;
        const Eigen::Vector2d b = line[i + 1] + half_along;
        const Eigen::Vector2d corners[4] = {a - half_across, b - half_across, b + half_across,
                                            a + half_across};
        for (int k = 0; k < 4; ++k) {
          edges_.push_back(
              {corners[k], corners[(k + 1) % 4], u, 0.0, world_.wall_height, ref, Disc{}});
        }
      }
      u += length;
    }
  }
  for (std::size_t i = 0; i < world_.objects.size(); ++i) {
    AddSolid(world_.objects[i], {SurfaceRef::Kind::kObject, static_cast<int>(i)});
  }
  for (std::size_t i = 0; i < world_.obstacles.size(); ++i) {
    AddSolid(world_.obstacles[i], {SurfaceRef::Kind::kObstacle, static_cast<int>(i)});
  }
}

void Scene::AddSolid(const Solid& solid, SurfaceRef ref) {
  if (solid.shape == ObjectShape::kPrism || solid.parts.empty()) {
    AddPrism(solid.footprint, solid.base_height, solid.base_height + solid.height, ref, Disc{});
    return;
  }
  for (std::size_t i = 0; i < solid.parts.size(); ++i) {
    const Part& part = solid.parts[i];
    ref.part = static_cast<int>(i);
    Disc disc;
    if (part.profile == Part::Profile::kDisc) {
      disc.radius = 0.5 * std::min(part.footprint.width, part.top - part.bottom);
      disc.center = part.footprint.center;
      disc.axis = Eigen::Vector2d(std::cos(part.footprint.yaw), std::sin(part.footprint.yaw));
      disc.height = 0.5 * (part.bottom + part.top);
    }
    AddPrism(part.footprint, part.bottom, part.top, ref, disc);
  }
}

void Scene::AddPrism(const Footprint& footprint, double bottom, double top, SurfaceRef ref,
                     const Disc& disc) {
  if (footprint.shape == Footprint::Shape::kCircle) {
    circles_.push_back({footprint.center, footprint.radius, bottom, top, ref});
    return;
  }
  const std::vector<Eigen::Vector2d> corners = BoxCorners(footprint);
  double u = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector2d& a = corners[i];
    const Eigen::Vector2d& b = corners[(i + 1) % corners.size()];
    edges_.push_back({a, b, u, bottom, top, ref, disc});
    u += (b - a).norm();
  }
}

template <typename Visit>
void Scene::ForEachHit(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                       double max_range, Visit&& visit) const {
  for (const Edge& edge : edges_) {
    const Eigen::Vector2d e = edge.b - edge.a;
    const double denominator = Cross(direction, e);
    if (std::abs(denominator) < 1e-12) continue;  // parallel: grazing rays see nothing
    const Eigen::Vector2d w = edge.a - origin;
    const double t = Cross(w, e) / denominator;
    const double s = Cross(w, direction) / denominator;
    if (t <= 1e-9 || t > max_range || s < 0.0 || s > 1.0) continue;
    const Eigen::Vector2d point = origin + t * direction;
    double bottom = edge.bottom, top = edge.top;
    if (edge.disc.radius > 0.0) {
      const double along = (point - edge.disc.center).dot(edge.disc.axis);
      const double half_sq = edge.disc.radius * edge.disc.radius - along * along;
      if (half_sq <= 0.0) continue;  // beside the disc
      bottom = edge.disc.height - std::sqrt(half_sq);
      top = edge.disc.height + std::sqrt(half_sq);
    }
    Eigen::Vector2d normal = Eigen::Vector2d(-e.y(), e.x()).normalized();
    if (normal.dot(direction) > 0.0) normal = -normal;
    visit(RayHit{t, point, normal, edge.u0 + s * e.norm(), bottom, top, edge.surface});
  }
  for (const Circle& circle : circles_) {
    // |origin + t d - c|² = r² with |d| = 1; only the entry point of the circle is visible.
    const Eigen::Vector2d m = origin - circle.center;
    const double b = m.dot(direction);
    const double c = m.squaredNorm() - circle.radius * circle.radius;
    const double discriminant = b * b - c;
    if (c <= 0.0 || discriminant < 0.0) continue;  // origin inside, or a miss
    const double t = -b - std::sqrt(discriminant);
    if (t <= 1e-9 || t > max_range) continue;
    const Eigen::Vector2d point = origin + t * direction;
    const Eigen::Vector2d normal = (point - circle.center) / circle.radius;
    const double u = circle.radius * (std::atan2(normal.y(), normal.x()) + M_PI);
    visit(RayHit{t, point, normal, u, circle.bottom, circle.top, circle.surface});
  }
}

std::optional<RayHit> Scene::CastAtHeight(const Eigen::Vector2d& origin, double angle,
                                          double max_range, double height) const {
  std::optional<RayHit> nearest;
  const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
  ForEachHit(origin, direction, max_range, [&](const RayHit& hit) {
    if (height < hit.bottom || height > hit.top) return;
    if (!nearest || hit.distance < nearest->distance) nearest = hit;
  });
  return nearest;
}

std::vector<RayHit> Scene::CastAll(const Eigen::Vector2d& origin, double angle,
                                   double max_range) const {
  std::vector<RayHit> hits;
  const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
  ForEachHit(origin, direction, max_range, [&](const RayHit& hit) { hits.push_back(hit); });
  std::sort(hits.begin(), hits.end(),
            [](const RayHit& a, const RayHit& b) { return a.distance < b.distance; });
  return hits;
}

bool Scene::IsOccupied(const Eigen::Vector2d& point, double clearance) const {
  for (const Solid& solid : world_.objects) {
    if (FootprintContains(solid.footprint, point)) return true;
  }
  for (const Solid& solid : world_.obstacles) {
    if (FootprintContains(solid.footprint, point)) return true;
  }
  for (const Edge& edge : edges_) {
    if (DistanceToSegment(point, edge.a, edge.b) < clearance) return true;
  }
  for (const Circle& circle : circles_) {
    if ((point - circle.center).norm() < circle.radius + clearance) return true;
  }
  return false;
}

}  // namespace semchain::sim
