#include "sim/detection_model.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "sim/prism_silhouette.h"

namespace semchain::sim {
namespace {

const std::vector<std::string>& ClassList(const World& world) {
  return world.classes.empty() ? DefaultClassNames() : world.classes;
}

int ClassIndex(const std::vector<std::string>& classes, const std::string& name) {
  const auto it = std::find(classes.begin(), classes.end(), name);
  return it == classes.end() ? -1 : static_cast<int>(it - classes.begin());
}

double MedianMillimetres(std::vector<std::uint16_t> depths) {
  const auto middle = depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2);
  std::nth_element(depths.begin(), middle, depths.end());
  return *middle;
}

// The same number of draws for every candidate, whatever happens to it, so one object's fate
// does not shift the random numbers of the objects after it.
struct Draws {
  double miss = 0.0;
  double confusion = 0.0;
  double other_class = 0.0;
  double box[4] = {0.0, 0.0, 0.0, 0.0};
  double depth = 0.0;
  double score = 0.0;
};

Draws Draw(Rng& rng) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  Draws d;
  d.miss = uniform(rng);
  d.confusion = uniform(rng);
  d.other_class = uniform(rng);
  for (double& edge : d.box) edge = normal(rng);
  d.depth = normal(rng);
  d.score = normal(rng);
  return d;
}

// A class other than 'true_id', uniformly ('true_id' == -1: any class).
int OtherClass(int true_id, int class_count, double unit) {
  const int choices = true_id >= 0 ? class_count - 1 : class_count;
  if (choices <= 0) return true_id;
  const int pick = std::min(choices - 1, static_cast<int>(unit * choices));
  return true_id >= 0 && pick >= true_id ? pick + 1 : pick;
}

std::optional<Detection> DetectObject(const World& world, const Solid& solid,
                                      const ObjectVisibility& view, const PinholeCamera& k,
                                      const Draws& draw) {
  const DetectionModelSpec& spec = world.detection;
  const int box_width = view.u_max - view.u_min + 1, box_height = view.v_max - view.v_min + 1;
  if (view.pixels == 0 || view.VisibleFraction() < spec.min_visible_fraction) return {};
  if (std::min(box_width, box_height) < spec.min_box_pixels) return {};
  // Beyond the depth camera's range there is no depth to report: no detection.
  if (2 * view.measured < view.pixels) return {};
  if (draw.miss < spec.miss_probability) return {};
  const std::vector<std::string>& classes = ClassList(world);
  Detection detection;
  detection.class_id = ClassIndex(classes, solid.class_name);
  if (draw.confusion < spec.confusion_probability) {
    detection.class_id =
        OtherClass(detection.class_id, static_cast<int>(classes.size()), draw.other_class);
  }
  detection.class_name = detection.class_id >= 0 ? classes[detection.class_id] : solid.class_name;
  const double edges[4] = {double(view.u_min), double(view.v_min), view.u_max + 1.0,
                           view.v_max + 1.0};
  const double limits[4] = {double(k.width), double(k.height), double(k.width), double(k.height)};
  for (int i = 0; i < 4; ++i) {
    detection.box[i] = std::clamp(edges[i] + spec.box_noise_px * draw.box[i], 0.0, limits[i]);
  }
  detection.box[2] = std::max(detection.box[2], detection.box[0] + 1.0);
  detection.box[3] = std::max(detection.box[3], detection.box[1] + 1.0);
  detection.depth_m =
      std::max(0.001 * MedianMillimetres(view.depths_mm) + spec.depth_noise_std * draw.depth, 0.0);
  // Confident on well-seen objects, less so on partly hidden ones.
  const double seen = std::min(1.0, view.VisibleFraction());
  detection.score = std::clamp(0.6 + 0.35 * seen + 0.03 * draw.score, 0.5, 0.99);
  return detection;
}

// A spurious box of a random class on the background (no object pixel at its centre), with the
// depth measured there; nothing when 'tries' random boxes all land on objects or unmeasured
// pixels.
std::optional<Detection> FalsePositive(const World& world, const RgbdImage& image, Rng& rng) {
  const DetectionModelSpec& spec = world.detection;
  const std::vector<std::string>& classes = ClassList(world);
  const int width = image.rgb.cols, height = image.rgb.rows;
  const double smallest = std::max(1, spec.min_box_pixels);
  if (classes.empty() || width < smallest || height < smallest) return {};
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int tries = 0; tries < 20; ++tries) {
    const double w = smallest + unit(rng) * std::max(0.0, 0.3 * width - smallest);
    const double h = smallest + unit(rng) * std::max(0.0, 0.4 * height - smallest);
    const double x1 = unit(rng) * (width - w), y1 = unit(rng) * (height - h);
    const int cu = std::min(width - 1, static_cast<int>(x1 + 0.5 * w));
    const int cv = std::min(height - 1, static_cast<int>(y1 + 0.5 * h));
    const std::uint16_t depth_mm = image.depth.at<std::uint16_t>(cv, cu);
    const double class_draw = unit(rng), score_draw = unit(rng);
    if (image.object_ids.at<std::int32_t>(cv, cu) >= 0 || depth_mm == 0) continue;
    Detection detection;
    detection.class_id =
        std::min(static_cast<int>(classes.size()) - 1,
                 static_cast<int>(class_draw * static_cast<double>(classes.size())));
    detection.class_name = classes[detection.class_id];
    detection.box[0] = x1, detection.box[1] = y1, detection.box[2] = x1 + w,
    detection.box[3] = y1 + h;
    detection.depth_m = 0.001 * depth_mm;
    detection.score = 0.25 + 0.3 * score_draw;  // below most true detections
    return detection;
  }
  return {};
}

}  // namespace

std::vector<ObjectVisibility> MeasureVisibility(const RgbdImage& image, const World& world) {
  std::vector<ObjectVisibility> views(world.objects.size());
  for (int v = 0; v < image.object_ids.rows; ++v) {
    const auto* ids = image.object_ids.ptr<std::int32_t>(v);
    const auto* depth = image.depth.ptr<std::uint16_t>(v);
    for (int u = 0; u < image.object_ids.cols; ++u) {
      if (ids[u] < 0 || ids[u] >= static_cast<int>(views.size())) continue;
      ObjectVisibility& view = views[ids[u]];
      if (view.pixels++ == 0) view.u_min = view.u_max = u, view.v_min = view.v_max = v;
      view.u_min = std::min(view.u_min, u);
      view.u_max = std::max(view.u_max, u);
      view.v_min = std::min(view.v_min, v);
      view.v_max = std::max(view.v_max, v);
      if (depth[u] > 0) view.depths_mm.push_back(depth[u]);
    }
  }
  for (std::size_t i = 0; i < views.size(); ++i) {
    views[i].measured = static_cast<int>(views[i].depths_mm.size());
    if (i < image.unoccluded_pixels.size()) views[i].silhouette = image.unoccluded_pixels[i];
  }
  return views;
}

std::vector<ObjectVisibility> MeasureVisibility(const Scene& scene, const MountedCamera& camera,
                                                const Pose2& robot_pose, const RgbdImage& image) {
  const World& world = scene.world();
  std::vector<ObjectVisibility> views = MeasureVisibility(image, world);
  for (std::size_t i = 0; i < views.size(); ++i) {
    ObjectVisibility& view = views[i];
    if (view.pixels == 0) continue;
    // An object of parts has holes (between a table's legs) no convex outline knows of: its
    // silhouette is the pixels the renderer found it in when ignoring everything else.
    const bool parts = world.objects[i].shape == ObjectShape::kParts;
    if (parts && i < image.unoccluded_pixels.size()) continue;
    view.silhouette = AreaInsideImage(ProjectPrism(world.objects[i], camera, robot_pose),
                                      camera.intrinsics.width, camera.intrinsics.height);
  }
  return views;
}

std::vector<Detection> DetectObjects(const Scene& scene, const MountedCamera& camera,
                                     const Pose2& robot_pose, const RgbdImage& image, Rng& rng) {
  const World& world = scene.world();
  const std::vector<ObjectVisibility> views = MeasureVisibility(scene, camera, robot_pose, image);
  std::vector<Detection> detections;
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (views[i].pixels == 0) continue;  // no draws for objects out of sight
    const Draws draw = Draw(rng);
    std::optional<Detection> detection =
        DetectObject(world, world.objects[i], views[i], camera.intrinsics, draw);
    if (detection) detections.push_back(std::move(*detection));
  }
  if (world.detection.false_positives_per_frame > 0.0) {
    std::poisson_distribution<int> count(world.detection.false_positives_per_frame);
    for (int n = count(rng); n > 0; --n) {
      std::optional<Detection> detection = FalsePositive(world, image, rng);
      if (detection) detections.push_back(std::move(*detection));
    }
  }
  return detections;
}

}  // namespace semchain::sim
