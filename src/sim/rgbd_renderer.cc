#include "sim/rgbd_renderer.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "core/angles.h"
#include "core/transforms.h"
#include "sim/render_rays.h"
#include "sim/texture.h"

namespace semchain::sim {
namespace {

constexpr float kFloorGrey = 118.0f;
constexpr float kCeilingGrey = 196.0f;
constexpr std::int64_t kDepthNoiseStream = 0x64657074;
constexpr std::int64_t kColorNoiseStream = 0x72676221;

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
                        int wall_index, TextureFamily family) {
  WallLooks looks;
  double u = 0.0;
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    const std::uint32_t seed = WallTextureSeed(world_seed, wall_index, static_cast<int>(i));
    looks.starts.push_back(u);
    looks.segments.push_back({SurfaceTexture(seed, WallColor(seed), family), WallColor(seed)});
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

  // Brightness of a face with unit 'normal' seen along 'ray'.
  double Lighting(const Eigen::Vector3d& normal, const Eigen::Vector3d& ray) const;
  void CountUnoccluded(RgbdImage& image) const;
  void ApplyCameraColor(cv::Mat& rgb) const;

  const MountedCamera& camera_;
  const RenderOptions& options_;
  const World& world_;
  ColumnRays rays_;
  std::vector<WallLooks> walls_;
  std::vector<Look> objects_, obstacles_;
  std::vector<std::vector<Look>> object_parts_;      // per object built of parts, per part
  std::optional<Look> floor_;                        // a textured floor
  Eigen::Vector3d light_ = Eigen::Vector3d::Zero();  // unit, the way the light travels
};

FrameRenderer::FrameRenderer(const Scene& scene, const MountedCamera& camera,
                             const Pose2& robot_pose, const RenderOptions& options)
    : camera_(camera),
      options_(options),
      world_(scene.world()),
      rays_(scene, camera, robot_pose, options.far_clip_meters) {
  const World& world = scene.world();
  for (std::size_t i = 0; i < world.walls.size(); ++i) {
    walls_.push_back(
        MakeWallLooks(world.walls[i], world.seed, static_cast<int>(i), world.shell.wall_texture));
  }
  object_parts_.resize(world.objects.size());
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const Solid& solid = world.objects[i];
    const SurfaceRef ref{SurfaceRef::Kind::kObject, static_cast<int>(i)};
    objects_.push_back(
        {SurfaceTexture(SolidTextureSeed(world.seed, solid, ref), solid.color, solid.texture),
         solid.color, solid.plain});
    if (solid.shape != ObjectShape::kParts) continue;
    for (const Part& part : solid.parts) {
      object_parts_[i].push_back(
          {SurfaceTexture(part.texture_seed, part.color, part.texture), part.color, solid.plain});
    }
  }
  for (std::size_t i = 0; i < world.obstacles.size(); ++i) {
    const Solid& solid = world.obstacles[i];
    const SurfaceRef ref{SurfaceRef::Kind::kObstacle, static_cast<int>(i)};
    obstacles_.push_back(
        {SurfaceTexture(SolidTextureSeed(world.seed, solid, ref), solid.color, solid.texture),
         solid.color, solid.plain});
  }
  if (world.shell.textured_floor) {
    const std::uint32_t seed = WallTextureSeed(world.seed, -1, 0);
    floor_ = Look{SurfaceTexture(seed, world.shell.floor_color, world.shell.floor_texture),
                  world.shell.floor_color, false};
  }
  if (world.lighting.enabled && world.lighting.direction.norm() > 0.0) {
    light_ = world.lighting.direction.normalized();
  }
}

const Look& FrameRenderer::LookOf(const RayHit& hit) const {
  const SurfaceRef& ref = hit.surface;
  if (ref.kind == SurfaceRef::Kind::kObject) {
    return ref.part >= 0 ? object_parts_[ref.index][ref.part] : objects_[ref.index];
  }
  if (ref.kind == SurfaceRef::Kind::kObstacle) return obstacles_[ref.index];
  const WallLooks& wall = walls_[ref.index];
  const auto next = std::upper_bound(wall.starts.begin(), wall.starts.end(), hit.surface_u);
  const std::ptrdiff_t segment = std::max<std::ptrdiff_t>(0, next - wall.starts.begin() - 1);
  return wall.segments[segment];
}

double FrameRenderer::Lighting(const Eigen::Vector3d& normal, const Eigen::Vector3d& ray) const {
  if (light_.isZero()) {
    // Lambert-like: faces seen head-on are brighter than faces seen at a grazing angle.
    return 0.55 + 0.45 * std::abs(normal.dot(ray)) / ray.norm();
  }
  // Faces turned away from the camera are never drawn, so orient the normal towards it.
  const Eigen::Vector3d towards_camera = normal.dot(ray) > 0.0 ? -normal : normal;
  const double diffuse = std::max(0.0, -towards_camera.dot(light_));
  return world_.lighting.ambient + world_.lighting.directional * diffuse;
}

Rgb FrameRenderer::Shade(const Eigen::Vector3d& ray, const Contact& contact, double t) const {
  if (contact.face == Face::kFloor) {
    if (!floor_ && light_.isZero()) return {kFloorGrey, kFloorGrey, kFloorGrey};
    const Eigen::Vector3d point = rays_.origin() + t * ray;
    const auto shade = static_cast<float>(Lighting(Eigen::Vector3d::UnitZ(), ray));
    Rgb color{kFloorGrey, kFloorGrey, kFloorGrey};
    if (floor_ && options_.textured) {
      const double footprint =
          t / camera_.intrinsics.fx / std::max(std::abs(ray.z()) / ray.norm(), 0.25);
      color = floor_->texture.Sample(point.x(), point.y(), footprint);
    }
    return {color.r * shade, color.g * shade, color.b * shade};
  }
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
  const double facing = std::abs(normal.dot(ray)) / ray.norm();
  const auto shade = static_cast<float>(Lighting(normal, ray));
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
  if (options_.count_unoccluded) CountUnoccluded(image);
  ApplyCameraColor(image.rgb);
  return image;
}

void FrameRenderer::CountUnoccluded(RgbdImage& image) const {
  const int width = camera_.intrinsics.width;
  image.unoccluded_pixels.assign(world_.objects.size(), 0);
  // The pixel each object was last counted for: parts of one object count once per pixel.
  std::vector<std::int64_t> counted_at(world_.objects.size(), -1);
  for (int v = 0; v < camera_.intrinsics.height; ++v) {
    for (int u = 0; u < width; ++u) {
      const std::int64_t pixel = static_cast<std::int64_t>(v) * width + u;
      rays_.ForEachObjectMet(u, v, rays_.PixelRay(u, v), [&](int object) {
        if (counted_at[object] == pixel) return;
        counted_at[object] = pixel;
        ++image.unoccluded_pixels[object];
      });
    }
  }
}

void FrameRenderer::ApplyCameraColor(cv::Mat& rgb) const {
  if (options_.exposure != 1.0) rgb.convertTo(rgb, CV_8UC3, options_.exposure);
  if (options_.blur_sigma_px > 0.0) {
    cv::GaussianBlur(rgb, rgb, cv::Size(), options_.blur_sigma_px, options_.blur_sigma_px,
                     cv::BORDER_REFLECT);
  }
  if (options_.rgb_noise_std <= 0.0) return;
  SEMCHAIN_CHECK(rgb.isContinuous());
  std::uint8_t* channel = rgb.ptr<std::uint8_t>();
  const auto count = static_cast<std::int64_t>(rgb.total() * rgb.channels());
  for (std::int64_t i = 0; i < count; ++i) {
    // Box–Muller on hashed uniforms, one channel value per draw.
    const double u1 = 1.0 - HashToUnit(options_.noise_seed, i, kColorNoiseStream);
    const double u2 = HashToUnit(options_.noise_seed, i, kColorNoiseStream + 1);
    const double noise =
        options_.rgb_noise_std * std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
    channel[i] = cv::saturate_cast<std::uint8_t>(channel[i] + noise);
  }
}

}  // namespace

MountedCamera MakeMountedCamera(const CameraSpec& spec) {
  MountedCamera camera;
  camera.intrinsics = PinholeCamera::FromFov(spec.width, spec.height_px, DegToRad(spec.fov_deg));
  camera.robot_from_camera =
      RobotFromOpticalCamera(spec.forward_offset, 0.0, spec.height, 0.0, DegToRad(spec.pitch_deg),
                             DegToRad(spec.roll_deg));
  camera.max_range = spec.max_range;
  return camera;
}

RenderOptions MakeRenderOptions(const CameraSpec& spec, std::uint64_t noise_seed) {
  RenderOptions options;
  options.depth_noise_std_meters = spec.depth_noise_std;
  options.noise_seed = noise_seed;
  options.exposure = spec.exposure;
  options.rgb_noise_std = spec.rgb_noise_std;
  options.blur_sigma_px = spec.blur_sigma_px;
  return options;
}

RgbdImage RenderRgbd(const Scene& scene, const MountedCamera& camera, const Pose2& robot_pose,
                     const RenderOptions& options) {
  return FrameRenderer(scene, camera, robot_pose, options).Render();
}

}  // namespace semchain::sim
