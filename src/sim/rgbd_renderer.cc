#include "sim/rgbd_renderer.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/transforms.h"
#include "sim/render_rays.h"
#include "sim/texture.h"

namespace semchain::sim {
namespace {

constexpr float kFloorGrey = 118.0f;
constexpr float kCeilingGrey = 196.0f;
constexpr std::int64_t kDepthNoiseStream = 0x64657074;

// A surface's texture and flat colour.
struct Look {
  SurfaceTexture texture;
  std::array<std::uint8_t, 3> color;
  bool plain = false;  // flat colour, no texture
};

// The looks of a wall polyline's segments; segment i starts at texture coordinate starts[i].
struct WallLooks {
  std::vector<double> starts;
  std::vector<Look> segments;
};

WallLooks MakeWallLooks(const std::vector<Eigen::Vector2d>& polyline, std::uint32_t world_seed,
                        int wall_index) {
  WallLooks looks;
  double u = 0.0;
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    const std::uint32_t seed = WallTextureSeed(world_seed, wall_index, static_cast<int>(i));
    looks.starts.push_back(u);
    looks.segments.push_back({SurfaceTexture(seed, WallColor(seed)), WallColor(seed)});
    u += (polyline[i + 1] - polyline[i]).norm();
  }
  return looks;
}

class FrameRenderer {
 public:
  FrameRenderer(const Scene& scene, const MountedCamera& camera, const Pose2& robot_pose,
                const RenderOptions& options);
  RgbdImage Render() const;

 private:
  const Look& LookOf(const RayHit& hit) const;
  // Colour of what 'contact' found along 'ray'; the point there is origin + t * ray.
  Rgb Shade(const Eigen::Vector3d& ray, const Contact& contact, double t) const;
  void AddDepthNoise(cv::Mat& depth_meters) const;

  const MountedCamera& camera_;
  const RenderOptions& options_;
  ColumnRays rays_;
  std::vector<WallLooks> walls_;
  std::vector<Look> objects_, obstacles_;
};

FrameRenderer::FrameRenderer(const Scene& scene, const MountedCamera& camera,
                             const Pose2& robot_pose, const RenderOptions& options)
    : camera_(camera),
      options_(options),
      rays_(scene, camera, robot_pose, options.far_clip_meters) {
  const World& world = scene.world();
  for (std::size_t i = 0; i < world.walls.size(); ++i) {
    walls_.push_back(MakeWallLooks(world.walls[i], world.seed, static_cast<int>(i)));
  }
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const Solid& solid = world.objects[i];
    const SurfaceRef ref{SurfaceRef::Kind::kObject, static_cast<int>(i)};
    objects_.push_back({SurfaceTexture(SolidTextureSeed(world.seed, solid, ref), solid.color),
                        solid.color, solid.plain});
  }
  for (std::size_t i = 0; i < world.obstacles.size(); ++i) {
    const Solid& solid = world.obstacles[i];
    const SurfaceRef ref{SurfaceRef::Kind::kObstacle, static_cast<int>(i)};
    obstacles_.push_back({SurfaceTexture(SolidTextureSeed(world.seed, solid, ref), solid.color),
                          solid.color, solid.plain});
  }
}

const Look& FrameRenderer::LookOf(const RayHit& hit) const {
  const SurfaceRef& ref = hit.surface;
  if (ref.kind == SurfaceRef::Kind::kObject) return objects_[ref.index];
  if (ref.kind == SurfaceRef::Kind::kObstacle) return obstacles_[ref.index];
  const WallLooks& wall = walls_[ref.index];
  const auto next = std::upper_bound(wall.starts.begin(), wall.starts.end(), hit.surface_u);
  const std::ptrdiff_t segment = std::max<std::ptrdiff_t>(0, next - wall.starts.begin() - 1);
  return wall.segments[segment];
}

Rgb FrameRenderer::Shade(const Eigen::Vector3d& ray, const Contact& contact, double t) const {
  if (contact.face == Face::kFloor) return {kFloorGrey, kFloorGrey, kFloorGrey};
  if (contact.face == Face::kCeiling) return {kCeilingGrey, kCeilingGrey, kCeilingGrey};
  if (contact.face == Face::kNothing) return {0.0f, 0.0f, 0.0f};
  const RayHit& hit = contact.span->entry;
  const Eigen::Vector3d point = rays_.origin() + t * ray;
  Eigen::Vector3d normal(hit.normal.x(), hit.normal.y(), 0.0);
  double u = hit.surface_u;
  double v = point.z();
  if (contact.face != Face::kSide) {  // a horizontal face: textured by world x and y
    normal = Eigen::Vector3d(0.0, 0.0, contact.face == Face::kTop ? 1.0 : -1.0);
    u = point.x();
    v = point.y();
  }
  // Lambert-like: faces seen head-on are brighter than faces seen at a grazing angle.
  const double facing = std::abs(normal.dot(ray)) / ray.norm();
  const auto shade = static_cast<float>(0.55 + 0.45 * facing);
  const Look& look = LookOf(hit);
  Rgb color{static_cast<float>(look.color[0]), static_cast<float>(look.color[1]),
            static_cast<float>(look.color[2])};
  if (options_.textured && !look.plain) {
    // One pixel covers t / fx metres across the ray, more on a face seen at an angle.
    const double footprint = t / camera_.intrinsics.fx / std::max(facing, 0.25);
    color = look.texture.Sample(u, v, footprint);
  }
  return {color.r * shade, color.g * shade, color.b * shade};
}

void FrameRenderer::AddDepthNoise(cv::Mat& depth_meters) const {
  if (options_.depth_noise_std_meters <= 0.0) return;
  // Box–Muller on hashed uniforms: each pixel's noise depends only on the seed and the pixel,
  // and costs a fraction of a generator's draw.
  const auto sigma = static_cast<float>(options_.depth_noise_std_meters);
  const auto apply = [](float& depth, float noise) {
    // Only measured pixels get noise; a noisy reading never turns into "no measurement".
    if (depth > 0.0f) depth = std::max(depth + noise, 0.001f);
  };
  SEMCHAIN_CHECK(depth_meters.isContinuous());
  float* depth = depth_meters.ptr<float>();
  const auto count = static_cast<std::int64_t>(depth_meters.total());
  for (std::int64_t i = 0; i < count; i += 2) {
    const auto u1 = static_cast<float>(1.0 - HashToUnit(options_.noise_seed, i, kDepthNoiseStream));
    const auto u2 = static_cast<float>(HashToUnit(options_.noise_seed, i + 1, kDepthNoiseStream));
    const float radius = sigma * std::sqrt(-2.0f * std::log(u1));
    const float angle = 6.2831853f * u2;
    apply(depth[i], radius * std::cos(angle));
    if (i + 1 < count) apply(depth[i + 1], radius * std::sin(angle));
  }
}

RgbdImage FrameRenderer::Render() const {
  const PinholeCamera& k = camera_.intrinsics;
  RgbdImage image;
  image.rgb.create(k.height, k.width, CV_8UC3);
  image.object_ids.create(k.height, k.width, CV_32SC1);
  cv::Mat depth_meters(k.height, k.width, CV_32FC1);
  for (int v = 0; v < k.height; ++v) {
    auto* rgb = image.rgb.ptr<cv::Vec3b>(v);
    auto* ids = image.object_ids.ptr<std::int32_t>(v);
    auto* depth = depth_meters.ptr<float>(v);
    for (int u = 0; u < k.width; ++u) {
      const Eigen::Vector3d ray = rays_.PixelRay(u, v);
      const Contact contact = rays_.FirstContact(u, v, ray);
      const double t = rays_.ContactDepth(ray, contact);
      const Rgb color = Shade(ray, contact, t);
      rgb[u] = cv::Vec3b(cv::saturate_cast<std::uint8_t>(color.r),
                         cv::saturate_cast<std::uint8_t>(color.g),
                         cv::saturate_cast<std::uint8_t>(color.b));
      const bool object =
          contact.span != nullptr && contact.span->entry.surface.kind == SurfaceRef::Kind::kObject;
      ids[u] = object ? contact.span->entry.surface.index : -1;
      const bool measured = contact.face != Face::kCeiling && contact.face != Face::kNothing &&
                            t <= camera_.max_range;
      depth[u] = measured ? static_cast<float>(t) : 0.0f;
    }
  }
  AddDepthNoise(depth_meters);
  depth_meters.convertTo(image.depth, CV_16UC1, 1000.0);  // rounds to the nearest millimetre
  return image;
}

}  // namespace

MountedCamera MakeMountedCamera(const CameraSpec& spec) {
  MountedCamera camera;
  camera.intrinsics = PinholeCamera::FromFov(spec.width, spec.height_px, DegToRad(spec.fov_deg));
  camera.robot_from_camera =
      RobotFromOpticalCamera(spec.forward_offset, 0.0, spec.height, 0.0, DegToRad(spec.pitch_deg));
  camera.max_range = spec.max_range;
  return camera;
}

RenderOptions MakeRenderOptions(const CameraSpec& spec, std::uint64_t noise_seed) {
  RenderOptions options;
  options.depth_noise_std_meters = spec.depth_noise_std;
  options.noise_seed = noise_seed;
  return options;
}

RgbdImage RenderRgbd(const Scene& scene, const MountedCamera& camera, const Pose2& robot_pose,
                     const RenderOptions& options) {
  return FrameRenderer(scene, camera, robot_pose, options).Render();
}

}  // namespace semchain::sim
