#include "sim/render_rays.h"

#include <algorithm>
#include <cmath>

#include "core/transforms.h"

namespace semchain::sim {
namespace {

const Solid& SolidOf(const World& world, const SurfaceRef& ref) {
  return ref.kind == SurfaceRef::Kind::kObject ? world.objects[ref.index]
                                               : world.obstacles[ref.index];
}

// Where the ray leaves a circular footprint it entered at 's_in': the chord's far end.
double CircleExit(const Solid& solid, const Eigen::Vector2d& origin,
                  const Eigen::Vector2d& direction, double s_in) {
  return 2.0 * (solid.footprint.center - origin).dot(direction) - s_in;
}

}  // namespace

std::vector<Span> BuildSpans(const Scene& scene, const Eigen::Vector2d& origin, double bearing,
                             double max_range) {
  const std::vector<RayHit> hits = scene.CastAll(origin, bearing, max_range);
  const Eigen::Vector2d direction(std::cos(bearing), std::sin(bearing));
  std::vector<Span> spans;
  spans.reserve(hits.size());
  for (const RayHit& hit : hits) {
    if (hit.surface.kind == SurfaceRef::Kind::kWall) {
      spans.push_back({hit.distance, hit.distance, hit});
      continue;
    }
    // A convex footprint is crossed twice, entry then exit (a ray through a corner meets two
    // edges at once): the first hit opens the span, later ones extend it.
    const auto open = std::find_if(spans.begin(), spans.end(), [&](const Span& span) {
      return span.entry.surface == hit.surface;
    });
    if (open != spans.end()) {
      open->s_out = std::max(open->s_out, hit.distance);
      continue;
    }
    Span span{hit.distance, hit.distance, hit};
    const Solid& solid = SolidOf(scene.world(), hit.surface);
    if (solid.footprint.shape == Footprint::Shape::kCircle) {
      span.s_out = CircleExit(solid, origin, direction, hit.distance);
    }
    spans.push_back(span);
  }
  return spans;
}

ColumnRays::ColumnRays(const Scene& scene, const MountedCamera& camera, const Pose2& robot_pose,
                       double max_range) {
  const Eigen::Isometry3d world_from_camera = WorldFromRobot(robot_pose) * camera.robot_from_camera;
  rotation_ = world_from_camera.linear();
  origin_ = world_from_camera.translation();
  ceiling_ = scene.world().wall_height;
  const PinholeCamera& k = camera.intrinsics;
  width_ = k.width;
  height_ = k.height;
  for (int u = 0; u < width_; ++u) a_.push_back((u - k.cx) / k.fx);
  for (int v = 0; v < height_; ++v) b_.push_back((v - k.cy) / k.fy);
  // When the image's down axis is vertical, every pixel of a column has the column's bearing.
  upright_ = rotation_.col(1).head<2>().norm() < 1e-9;
  if (!upright_) {
    CastPitched(scene, max_range);
    return;
  }
  for (int u = 0; u < width_; ++u) {
    const Eigen::Vector3d ray = PixelRay(u, 0);
    spans_.push_back(BuildSpans(scene, origin_.head<2>(), std::atan2(ray.y(), ray.x()), max_range));
  }
}

void ColumnRays::CastPitched(const Scene& scene, double max_range) {
  // Bearings relative to the camera's heading (the image x axis stays horizontal without roll).
  const Eigen::Vector2d right = rotation_.col(0).head<2>().normalized();
  const Eigen::Vector2d forward(-right.y(), right.x());
  const double heading = std::atan2(forward.y(), forward.x());
  std::vector<double> relative(static_cast<std::size_t>(width_) * height_);
  double lo = 0.0, hi = 0.0, finest = 1.0;
  for (int v = 0; v < height_; ++v) {
    for (int u = 0; u < width_; ++u) {
      const Eigen::Vector3d ray = PixelRay(u, v);
      const double r = std::atan2(-ray.head<2>().dot(right), ray.head<2>().dot(forward));
      relative[v * width_ + u] = r;
      lo = std::min(lo, r);
      hi = std::max(hi, r);
      if (u > 0) {
        const double gap = std::abs(r - relative[v * width_ + u - 1]);
        if (gap > 1e-12) finest = std::min(finest, gap);
      }
    }
  }
  // Samples half the finest pixel spacing apart: a pixel's bearing is within a quarter pixel
  // of its sample's, and ContactDepth() removes the depth error on flat faces.
  const int count =
      std::clamp(static_cast<int>(std::ceil((hi - lo) / (0.5 * finest))) + 1, 2, 16 * width_);
  const double step = (hi - lo) / (count - 1);
  for (int i = 0; i < count; ++i) {
    spans_.push_back(BuildSpans(scene, origin_.head<2>(), heading + lo + i * step, max_range));
  }
  sample_of_pixel_.resize(relative.size());
  for (std::size_t i = 0; i < relative.size(); ++i) {
    sample_of_pixel_[i] = step > 0.0 ? static_cast<int>(std::lround((relative[i] - lo) / step)) : 0;
  }
}

Contact ColumnRays::FirstContact(int u, int v, const Eigen::Vector3d& ray) const {
  const double z = origin_.z();
  Contact best;
  if (ray.z() < 0.0) {
    best = {Face::kFloor, -z / ray.z(), nullptr};
  } else if (ray.z() > 0.0 && z < ceiling_) {
    best = {Face::kCeiling, (ceiling_ - z) / ray.z(), nullptr};
  }
  const double horizontal = ray.head<2>().norm();  // metres travelled in the plane per unit t
  if (horizontal < 1e-12) return best;
  for (const Span& span : spans_[SampleOf(u, v)]) {
    const double t_in = span.s_in / horizontal;
    if (t_in >= best.t) break;  // spans are sorted by entry: nothing later can be nearer
    const double h_in = z + t_in * ray.z();
    const double bottom = span.entry.bottom, top = span.entry.top;
    if (h_in >= bottom && h_in <= top) return {Face::kSide, t_in, &span};
    // Above a prism and descending, the ray may land on its top face before leaving the
    // footprint; below a raised one and rising, on its bottom face.
    const bool onto_top = h_in > top && ray.z() < 0.0;
    const bool onto_bottom = h_in < bottom && ray.z() > 0.0;
    if (span.s_out <= span.s_in || !(onto_top || onto_bottom)) continue;
    const double t = ((onto_top ? top : bottom) - z) / ray.z();
    if (t <= span.s_out / horizontal && t < best.t) {
      best = {onto_top ? Face::kTop : Face::kBottom, t, &span};
    }
  }
  return best;
}

double ColumnRays::ContactDepth(const Eigen::Vector3d& ray, const Contact& contact) const {
  if (upright_ || contact.face != Face::kSide) return contact.t;
  // Intersect the pixel's own ray with the plane of the face its bearing sample hit.
  const Eigen::Vector2d& normal = contact.span->entry.normal;
  const double along = normal.dot(ray.head<2>());
  if (std::abs(along) < 1e-12) return contact.t;
  const double t = normal.dot(contact.span->entry.point - origin_.head<2>()) / along;
  return t > 0.0 ? t : contact.t;
}

}  // namespace semchain::sim
