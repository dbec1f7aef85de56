#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <vector>

#include "core/pose2.h"
#include "sensors/camera.h"
#include "sim/scene.h"

// The geometry half of the RGB-D renderer: each pixel's viewing ray and the first surface it
// meets. Pixels that share a horizontal bearing share one Scene::CastAll; with an upright camera
// (no pitch) that is exactly one cast per image column.
namespace semchain::sim {

// The stretch of a horizontal ray inside one prism's footprint, from horizontal distance 's_in'
// (where it crosses 'entry') to 's_out' (metres). A wall has no thickness: s_in == s_out.
struct Span {
  double s_in = 0.0;
  double s_out = 0.0;
  RayHit entry;
};

// Which part of the world a pixel sees: a prism's vertical face, its top or bottom face (a
// camera above a low box sees its lid), the floor, the ceiling, or nothing (above the walls).
enum class Face { kSide, kTop, kBottom, kFloor, kCeiling, kNothing };

struct Contact {
  Face face = Face::kNothing;
  double t = std::numeric_limits<double>::infinity();  // depth along the optical axis, metres
  const Span* span = nullptr;                          // the prism, for kSide, kTop, kBottom
};

// The spans of the horizontal ray from 'origin' at 'bearing', nearest entry first.
std::vector<Span> BuildSpans(const Scene& scene, const Eigen::Vector2d& origin, double bearing,
                             double max_range);

class ColumnRays {
 public:
  // Casts the horizontal rays of a frame taken by 'camera' on a robot at 'robot_pose'; surfaces
  // farther than 'max_range' horizontally are ignored.
  ColumnRays(const Scene& scene, const MountedCamera& camera, const Pose2& robot_pose,
             double max_range);

  // The camera centre in the world frame.
  const Eigen::Vector3d& origin() const { return origin_; }

  // The viewing ray of pixel (u, v) in the world frame, scaled so that its optical-axis
  // component is 1: the point at depth z is origin() + z * ray.
  Eigen::Vector3d PixelRay(int u, int v) const {
    return rotation_ * Eigen::Vector3d(a_[u], b_[v], 1.0);
  }

  // The first surface met by 'ray', the viewing ray of pixel (u, v).
  Contact FirstContact(int u, int v, const Eigen::Vector3d& ray) const;

  // Calls visit(object index) for every part of a semantic object (World::objects) that the
  // ray of pixel (u, v) meets anywhere along its way, hidden or not (an object of several parts
  // may be visited more than once).
  template <typename Visit>
  void ForEachObjectMet(int u, int v, const Eigen::Vector3d& ray, Visit&& visit) const;

  // The depth of 'contact'. A pitched camera shares casts between pixels of nearly the same
  // bearing; the depth is still exact on flat faces because it is recomputed on the face's plane.
  double ContactDepth(const Eigen::Vector3d& ray, const Contact& contact) const;

 private:
  int SampleOf(int u, int v) const { return upright_ ? u : sample_of_pixel_[v * width_ + u]; }
  void CastPitched(const Scene& scene, double max_range);

  Eigen::Matrix3d rotation_;  // world from optical camera
  Eigen::Vector3d origin_;
  double ceiling_ = 0.0;
  int width_ = 0;
  int height_ = 0;
  bool upright_ = true;                   // the image columns are vertical in the world
  std::vector<double> a_;                 // (u - cx) / fx
  std::vector<double> b_;                 // (v - cy) / fy
  std::vector<std::vector<Span>> spans_;  // per bearing sample
  std::vector<int> sample_of_pixel_;      // pitched cameras only
};

template <typename Visit>
void ColumnRays::ForEachObjectMet(int u, int v, const Eigen::Vector3d& ray, Visit&& visit) const {
  const double z = origin_.z();
  const double horizontal = ray.head<2>().norm();
  if (horizontal < 1e-12) return;
  for (const Span& span : spans_[SampleOf(u, v)]) {
    const SurfaceRef& ref = span.entry.surface;
    if (ref.kind != SurfaceRef::Kind::kObject) continue;
    const double t_in = span.s_in / horizontal, t_out = span.s_out / horizontal;
    const double h_in = z + t_in * ray.z(), h_out = z + t_out * ray.z();
    // Through the prism between entry and exit the ray spans [min, max] of its two heights.
    const double low = std::min(h_in, h_out), high = std::max(h_in, h_out);
    if (high < span.entry.bottom || low > span.entry.top) continue;
    visit(ref.index);
  }
}

}  // namespace semchain::sim
