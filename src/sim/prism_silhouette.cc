#include "sim/prism_silhouette.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/transforms.h"
#include "sim/scene.h"

namespace semchain::sim {
namespace {

constexpr double kNearPlane = 0.01;  // metres

double CrossAbout(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain; counter-clockwise in a y-up frame (clockwise on screen).
std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && CrossAbout(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && CrossAbout(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// Sutherland–Hodgman: keeps the part of 'polygon' where inside(p) >= 0 (inside is affine).
template <typename Inside>
std::vector<Eigen::Vector2d> ClipHalfPlane(const std::vector<Eigen::Vector2d>& polygon,
                                           Inside inside) {
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    const double da = inside(a), db = inside(b);
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

}  // namespace

std::vector<Eigen::Vector2d> FootprintOutline(const Footprint& footprint, int circle_sides) {
  if (footprint.shape == Footprint::Shape::kBox) return BoxCorners(footprint);
  std::vector<Eigen::Vector2d> outline;
  for (int i = 0; i < circle_sides; ++i) {
    const double angle = 2.0 * kPi * i / circle_sides;
    outline.push_back(footprint.center +
                      footprint.radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return outline;
}

std::vector<Eigen::Vector2d> ProjectPrism(const Solid& solid, const MountedCamera& camera,
                                          const Pose2& robot_pose) {
  const Eigen::Isometry3d camera_from_world =
      (WorldFromRobot(robot_pose) * camera.robot_from_camera).inverse();
  const std::vector<Eigen::Vector2d> outline = FootprintOutline(solid.footprint);
  const double bottom = solid.base_height, top = solid.base_height + solid.height;
  std::vector<Eigen::Vector3d> lower, upper;
  for (const Eigen::Vector2d& p : outline) {
    lower.push_back(camera_from_world * Eigen::Vector3d(p.x(), p.y(), bottom));
    upper.push_back(camera_from_world * Eigen::Vector3d(p.x(), p.y(), top));
  }
  // The prism's image is the hull of its vertices' images, once every edge that crosses the
  // near plane has been cut there.
  std::vector<Eigen::Vector2d> pixels;
  const auto add_edge = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    if (a.z() >= kNearPlane) pixels.push_back(camera.intrinsics.Project(a));
    if ((a.z() >= kNearPlane) != (b.z() >= kNearPlane)) {
      const Eigen::Vector3d cut = a + (b - a) * ((kNearPlane - a.z()) / (b.z() - a.z()));
      pixels.push_back(camera.intrinsics.Project(cut));
    }
  };
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const std::size_t next = (i + 1) % outline.size();
    add_edge(lower[i], lower[next]);
    add_edge(upper[i], upper[next]);
    add_edge(lower[i], upper[i]);  // adds lower[i] twice: harmless for the hull
  }
  return ConvexHull(std::move(pixels));
}

double AreaInsideImage(const std::vector<Eigen::Vector2d>& polygon, int width, int height) {
  std::vector<Eigen::Vector2d> clipped = polygon;
  const double right = width - 0.5, bottom = height - 0.5;
  clipped = ClipHalfPlane(clipped, [](const Eigen::Vector2d& p) { return p.x() + 0.5; });
  clipped = ClipHalfPlane(clipped, [&](const Eigen::Vector2d& p) { return right - p.x(); });
  clipped = ClipHalfPlane(clipped, [](const Eigen::Vector2d& p) { return p.y() + 0.5; });
  clipped = ClipHalfPlane(clipped, [&](const Eigen::Vector2d& p) { return bottom - p.y(); });
  double twice_area = 0.0;
  for (std::size_t i = 0; i < clipped.size(); ++i) {
    const Eigen::Vector2d& a = clipped[i];
    const Eigen::Vector2d& b = clipped[(i + 1) % clipped.size()];
    twice_area += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * std::abs(twice_area);
}

}  // namespace semchain::sim
