#include "localization/prelocalization.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "core/angles.h"
#include "core/transforms.h"
#include "mapping/distance_field.h"
#include "semantic/semantic_chain.h"

namespace semchain::localization {
namespace {

// Mapped pairs farther apart than this are never seen together by a camera of a few metres'
// range; not indexing them keeps the index small on large maps.
constexpr double kMaxPairDistance = 15.0;
// Fixed-point iterations of the centre-behind-surface correction, at most, and the move of the
// position below which it has settled (the depth changes little with the direction seen from).
constexpr int kRefinements = 4;
constexpr double kSettledMeters = 1e-3;

Eigen::Vector2d Unit(const Eigen::Vector2d& v) {
  const double n = v.norm();
  return n > 1e-12 ? Eigen::Vector2d(v / n) : Eigen::Vector2d(1.0, 0.0);
}

// The mean distance from the centre to the outline: the centre's depth behind a surface seen
// from an unknown side.
double MeanCenterBehindSurface(const semantic::SemanticObject& object) {
  double sum = 0.0;
  constexpr int kDirections = 8;
  for (int k = 0; k < kDirections; ++k) {
    const double a = 2.0 * M_PI * k / kDirections;
    sum += CenterBehindSurface(object, Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return sum / kDirections;
}

// The robot heading, as (cos, sin), that turns the direction 'seen' (robot frame) into the
// direction from 'at' to 'centre' (world): the complex product of the one by the conjugate of
// the other. Headings compared and averaged this way need no arc tangent.
Eigen::Vector2d HeadingFrom(const Eigen::Vector2d& at, const Eigen::Vector2d& centre,
                            const Eigen::Vector2d& seen) {
  const Eigen::Vector2d world = Unit(centre - at);
  const Eigen::Vector2d robot = Unit(seen);
  return {world.dot(robot), robot.x() * world.y() - robot.y() * world.x()};
}

}  // namespace

bool PreLocalizationOptions::Validate(std::string* error) const {
  if (!(distance_tolerance > 0.0 && distance_tolerance < 1.0)) {
    *error = "distance_tolerance (alpha) must be in (0, 1)";
    return false;
  }
  if (!(distance_slack >= 0.0)) {
    *error = "distance_slack must be >= 0";
    return false;
  }
  if (!(unknown_reach >= 0.0)) {
    *error = "unknown_reach must be >= 0";
    return false;
  }
  if (!(heading_agreement > 0.0) || !(agreement_radius > 0.0) || max_hypotheses < 1 ||
      !(position_std_base > 0.0) || !(heading_std > 0.0) || clearance < 0.0 ||
      !(centre_std_base > 0.0)) {
    *error = "tolerances, standard deviations and max_hypotheses must be positive";
    return false;
  }
  if (!(laser_refine_max_shift >= 0.0) || !(laser_refine_max_turn >= 0.0)) {
    *error = "laser_refine_max_shift and laser_refine_max_turn must be >= 0";
    return false;
  }
  if (!(look_alike_laser_margin >= 0.0) || !(distinct_place_distance > 0.0) ||
      !(distinct_place_heading > 0.0)) {
    *error =
        "look_alike_laser_margin must be >= 0, distinct_place_distance and "
        "distinct_place_heading > 0";
    return false;
  }
  return true;
}

std::vector<ObservedObject> ObserveObjects(const std::vector<Detection>& detections,
                                           const MountedCamera& camera,
                                           const PreLocalizationOptions& options) {
  std::vector<ObservedObject> observed;
  const double right = camera.intrinsics.width - options.border_margin_px;
  for (std::size_t i = 0; i < detections.size(); ++i) {
    const Detection& d = detections[i];
    if (d.score < options.min_score || !(d.depth_m > 0.0)) continue;
    if (options.border_margin_px >= 0.0 &&
        (d.box[0] <= options.border_margin_px || d.box[2] >= right)) {
      continue;
    }
    // Box edges are pixel boundaries; pixel u covers [u − 0.5, u + 0.5).
    const double u = 0.5 * (d.box[0] + d.box[2]) - 0.5;
    const double v = 0.5 * (d.box[1] + d.box[3]) - 0.5;
    const Eigen::Vector3d robot =
        CameraToRobot(camera.robot_from_camera, camera.intrinsics.Backproject(u, v, d.depth_m));
    ObservedObject object;
    object.class_name = d.class_name;
    object.surface = robot.head<2>();
    object.range = object.surface.norm();
    object.bearing = std::atan2(object.surface.y(), object.surface.x());
    object.detection = static_cast<int>(i);
    observed.push_back(object);
  }
  return observed;
}

int IntersectCircles(const Eigen::Vector2d& c0, double r0, const Eigen::Vector2d& c1, double r1,
                     double slack, Eigen::Vector2d out[2]) {
  const Eigen::Vector2d delta = c1 - c0;
  const double d = delta.norm();
  if (d < 1e-9) return 0;  // concentric: no point, or a whole circle
  const Eigen::Vector2d u = delta / d;
  if (d > r0 + r1) {  // apart
    if (d - (r0 + r1) > slack) return 0;
    out[0] = c0 + u * (r0 + 0.5 * (d - r0 - r1));
    return 1;
  }
  if (d < std::abs(r0 - r1)) {  // one inside the other
    if (std::abs(r0 - r1) - d > slack) return 0;
    const double sign = r0 >= r1 ? 1.0 : -1.0;
    out[0] = c0 + sign * u * (r0 - 0.5 * (std::abs(r0 - r1) - d));
    return 1;
  }
  const double a = (r0 * r0 - r1 * r1 + d * d) / (2.0 * d);
  const double h2 = r0 * r0 - a * a;
  const Eigen::Vector2d base = c0 + a * u;
  if (h2 <= 1e-12) {
    out[0] = base;
    return 1;
  }
  const double h = std::sqrt(h2);
  const Eigen::Vector2d normal(-u.y(), u.x());
  out[0] = base + h * normal;
  out[1] = base - h * normal;
  return 2;
}

double CenterBehindSurface(const semantic::SemanticObject& object,
                           const Eigen::Vector2d& direction) {
  const std::vector<Eigen::Vector2d>& polygon = object.footprint;
  if (polygon.size() < 3) return 0.0;
  double best = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d a = polygon[k] - object.center;
    const Eigen::Vector2d e = polygon[(k + 1) % polygon.size()] - polygon[k];
    // Solve t·direction = a + s·e by Cramer's rule, t = t_num / det and s = s_num / det; the
    // tests are made on the numerators (det made positive), and only a farther hit divides: this
    // runs for every edge of every object on every hypothesis.
    double det = direction.y() * e.x() - direction.x() * e.y();
    if (std::abs(det) < 1e-12) continue;
    double t_num = a.y() * e.x() - a.x() * e.y();
    double s_num = direction.x() * a.y() - direction.y() * a.x();
    if (det < 0.0) {
      det = -det;
      t_num = -t_num;
      s_num = -s_num;
    }
    if (t_num > best * det && s_num >= -1e-9 * det && s_num <= (1.0 + 1e-9) * det) {
      best = t_num / det;
    }
  }
  return best;
}

PreLocalizer::PreLocalizer(const semantic::SemanticMap& map, const mapping::MapImage& occupancy,
                           const PreLocalizationOptions& options)
    : objects_(map.objects), occupancy_(occupancy), options_(options) {
  for (const semantic::SemanticObject& object : objects_) class_id_.emplace(object.class_name, 0);
  int next_id = 0;
  for (auto& [name, id] : class_id_) id = next_id++;  // name order
  const std::size_t classes = class_id_.size();
  objects_of_class_.resize(classes);
  pairs_.resize(classes * classes);
  std::vector<int> class_of;
  for (std::size_t o = 0; o < objects_.size(); ++o) {
    const semantic::SemanticObject& object = objects_[o];
    class_of.push_back(class_id_.at(object.class_name));
    objects_of_class_[static_cast<std::size_t>(class_of.back())].push_back(static_cast<int>(o));
    double radius = 0.0;
    for (const Eigen::Vector2d& corner : object.footprint) {
      radius = std::max(radius, (corner - object.center).norm());
    }
    outline_radius_.push_back(radius);
    mean_behind_.push_back(MeanCenterBehindSurface(object));
    std::vector<cv::Point2f>& outline = outlines_.emplace_back();
    for (const Eigen::Vector2d& corner : object.footprint) {
      outline.emplace_back(static_cast<float>(corner.x()), static_cast<float>(corner.y()));
    }
  }
  for (std::size_t a = 0; a < objects_.size(); ++a) {
    for (std::size_t b = 0; b < objects_.size(); ++b) {
      if (a == b) continue;
      const int ca = class_of[a];
      const int cb = class_of[b];
      // Each unordered pair once, under its classes in id order (a first when equal).
      if (ca > cb || (ca == cb && a > b)) continue;
      const double distance = (objects_[a].center - objects_[b].center).norm();
      if (distance > kMaxPairDistance) continue;
      pairs_[static_cast<std::size_t>(ca) * classes + static_cast<std::size_t>(cb)].push_back(
          {distance, static_cast<int>(a), static_cast<int>(b)});
    }
  }
  for (std::vector<IndexedPair>& list : pairs_) {
    std::sort(list.begin(), list.end(),
              [](const IndexedPair& x, const IndexedPair& y) { return x.distance < y.distance; });
  }
  if (occupancy.width > 0 && occupancy.height > 0) {
    const cv::Mat free = mapping::MapCellMask(occupancy, mapping::CellState::kFree);
    cv::distanceTransform(free, clearance_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    clearance_ *= occupancy.resolution;
    if (options_.unknown_reach > 0.0) {  // only Standable reads it, and only then
      cv::Mat not_free;
      cv::bitwise_not(free, not_free);
      cv::distanceTransform(not_free, to_free_, cv::DIST_L2, cv::DIST_MASK_PRECISE);
      to_free_ *= occupancy.resolution;
    }
  }
}

std::vector<int> PreLocalizer::ClassesOf(const std::vector<ObservedObject>& observed) const {
  std::vector<int> classes;
  classes.reserve(observed.size());
  for (const ObservedObject& s : observed) {
    const auto it = class_id_.find(s.class_name);
    classes.push_back(it == class_id_.end() ? -1 : it->second);
  }
  return classes;
}

template <typename Visit>
void PreLocalizer::ForEachPair(int class_a, int class_b, double d, double slack,
                               Visit&& visit) const {
  if (class_a < 0 || class_b < 0) return;
  const bool swapped = class_a > class_b;
  const std::vector<IndexedPair>& list =
      pairs_[static_cast<std::size_t>(std::min(class_a, class_b)) * class_id_.size() +
             static_cast<std::size_t>(std::max(class_a, class_b))];
  const double low = std::max(0.0, d - slack) / (1.0 + options_.distance_tolerance);
  const double high = (d + slack) / (1.0 - options_.distance_tolerance);
  auto first =
      std::upper_bound(list.begin(), list.end(), low,
                       [](double value, const IndexedPair& p) { return value < p.distance; });
  for (; first != list.end() && first->distance < high; ++first) {
    if (swapped) {
      visit(first->b, first->a, first->distance);
    } else {
      visit(first->a, first->b, first->distance);
    }
    // Same classes: either object may be the first one seen.
    if (class_a == class_b) visit(first->b, first->a, first->distance);
  }
}

std::vector<std::tuple<int, int, double>> PreLocalizer::RetrievePairs(const std::string& class_a,
                                                                      const std::string& class_b,
                                                                      double d,
                                                                      double slack) const {
  std::vector<std::tuple<int, int, double>> found;
  const auto a = class_id_.find(class_a);
  const auto b = class_id_.find(class_b);
  if (a == class_id_.end() || b == class_id_.end()) return found;
  ForEachPair(a->second, b->second, d, slack, [&](int oa, int ob, double distance) {
    found.emplace_back(objects_[static_cast<std::size_t>(oa)].id,
                       objects_[static_cast<std::size_t>(ob)].id, distance);
  });
  return found;
}

std::optional<Eigen::Vector2i> PreLocalizer::MapCell(const Eigen::Vector2d& point) const {
  const semantic::GridGeometry geometry = semantic::GeometryOf(occupancy_);
  const Eigen::Vector2i cell = geometry.CellOf(point);
  if (!geometry.Contains(cell)) return std::nullopt;
  return cell;
}

bool PreLocalizer::InFreeSpace(const Eigen::Vector2d& point) const {
  if (clearance_.empty()) return false;
  const std::optional<Eigen::Vector2i> cell = MapCell(point);
  if (!cell) return false;
  // The distance to the nearest non-free cell is 0 exactly on the cells that are not free.
  const float clearance = clearance_.at<float>(cell->y(), cell->x());
  return clearance > 0.0f && clearance >= options_.clearance;
}

bool PreLocalizer::OffObstacles(const Eigen::Vector2d& point) const {
  const std::optional<Eigen::Vector2i> cell = MapCell(point);
  return cell && mapping::ClassifyMapCell(occupancy_, cell->x(), cell->y()) !=
                     mapping::CellState::kOccupied;
}

bool PreLocalizer::Standable(const Eigen::Vector2d& point) const {
  if (InFreeSpace(point)) return true;
  if (options_.unknown_reach <= 0.0 || to_free_.empty()) return false;
  const std::optional<Eigen::Vector2i> cell = MapCell(point);
  return cell &&
         mapping::ClassifyMapCell(occupancy_, cell->x(), cell->y()) ==
             mapping::CellState::kUnknown &&
         to_free_.at<float>(cell->y(), cell->x()) <= options_.unknown_reach;
}

void PreLocalizer::AddPairHypotheses(const std::vector<ObservedObject>& observed, int i, int j,
                                     int a, int b, std::vector<PoseCandidate>* out) const {
  const semantic::SemanticObject& oa = objects_[a];
  const semantic::SemanticObject& ob = objects_[b];
  const ObservedObject& si = observed[i];
  const ObservedObject& sj = observed[j];
  // Where the objects' centres are in the robot frame, the camera having seen their surfaces:
  // behind the surface by the centre's depth in the direction seen (refined below).
  const auto centre_in_robot = [](const ObservedObject& s, double behind) {
    return Eigen::Vector2d(s.surface + behind * Unit(s.surface));
  };
  Eigen::Vector2d points[2];
  // Range errors grow with range: far circles may miss each other by more.
  const double slack =
      options_.circle_slack + options_.circle_slack_per_metre * (si.range + sj.range);
  const int count = IntersectCircles(
      oa.center, centre_in_robot(si, mean_behind_[static_cast<std::size_t>(a)]).norm(), ob.center,
      centre_in_robot(sj, mean_behind_[static_cast<std::size_t>(b)]).norm(), slack, points);
  const double sigma =
      options_.position_std_base + options_.position_std_per_metre * 0.5 * (si.range + sj.range);
  // A position off by sigma turns the bearing of an object at range r by up to sigma / r: the
  // headings the two bearings give may differ by that much more (a door half a metre away
  // moves by a third of a radian for 0.15 m). |h_i − h_j| ≤ tolerance is
  // cos(h_i − h_j) ≥ cos(tolerance).
  const double heading_tolerance =
      options_.heading_agreement +
      (options_.heading_agreement_by_range
           ? sigma * (1.0 / std::max(si.range, sigma) + 1.0 / std::max(sj.range, sigma))
           : 0.0);
  const double min_heading_cosine = heading_tolerance >= kPi ? -2.0 : std::cos(heading_tolerance);
  for (int k = 0; k < count; ++k) {
    // Refine with the depth behind the surface seen from this position (a fixed point: the
    // depth depends on the direction, the direction on the position).
    Eigen::Vector2d x = points[k];
    Eigen::Vector2d pi, pj;
    bool lost = false;
    for (int iteration = 0; iteration < kRefinements; ++iteration) {
      pi = centre_in_robot(si, CenterBehindSurface(oa, Unit(x - oa.center)));
      pj = centre_in_robot(sj, CenterBehindSurface(ob, Unit(x - ob.center)));
      Eigen::Vector2d refined[2];
      const int n = IntersectCircles(oa.center, pi.norm(), ob.center, pj.norm(), slack, refined);
      if (n == 0) {
        lost = true;
        break;
      }
      const Eigen::Vector2d next =
          n == 2 && (refined[1] - x).norm() < (refined[0] - x).norm() ? refined[1] : refined[0];
      const bool settled = (next - x).norm() < kSettledMeters;
      x = next;
      if (settled) break;
    }
    if (lost) continue;
    // The heading each bearing gives at a position; the mirror solution disagrees.
    const auto headings_agree = [&](const Eigen::Vector2d& at) {
      return HeadingFrom(at, oa.center, pi).dot(HeadingFrom(at, ob.center, pj)) >=
             min_heading_cosine;
    };
    PoseCandidate candidate;
    // The circular mean of the two headings: the angle of the sum of their unit vectors.
    const Eigen::Vector2d mean = HeadingFrom(x, oa.center, pi) + HeadingFrom(x, ob.center, pj);
    candidate.pose = Pose2(x.x(), x.y(), std::atan2(mean.y(), mean.x()));
    if (options_.refine) {
      // Ranges and bearings together; the bearings must then agree at the refined pose.
      const std::array<Match, 2> pair = {Match{i, a}, Match{j, b}};
      Refine(observed, pair, &candidate.pose);
    }
    // Where a robot can stand first: a cell read or two.
    if (!Standable(candidate.pose.translation())) continue;
    if (!headings_agree(candidate.pose.translation())) continue;
    candidate.covariance =
        Eigen::Vector3d(sigma * sigma, sigma * sigma, options_.heading_std * options_.heading_std)
            .asDiagonal();
    out->push_back(candidate);
  }
}

void PreLocalizer::MatchAgreeing(const std::vector<ObservedObject>& observed,
                                 const std::vector<int>& classes, const Pose2& pose,
                                 std::vector<Match>* matched, std::vector<Match>* by_centre,
                                 int needed) const {
  matched->clear();
  if (by_centre != nullptr) by_centre->clear();
  const Eigen::Isometry2d world_from_robot = pose.ToIsometry();
  const auto at_least = static_cast<std::size_t>(std::max(needed, 0));
  for (std::size_t k = 0; k < observed.size(); ++k) {
    if (matched->size() + (observed.size() - k) < at_least) return;
    if (classes[k] < 0) continue;
    const ObservedObject& s = observed[k];
    const Eigen::Vector2d surface = world_from_robot * s.surface;
    const Eigen::Vector2d ray = Unit(surface - pose.translation());
    int best = -1;
    const double radius = options_.agreement_radius + options_.agreement_per_metre * s.range;
    double best_error = radius;
    double best_centre_error = radius;
    for (const int o : objects_of_class_[static_cast<std::size_t>(classes[k])]) {
      const semantic::SemanticObject& object = objects_[static_cast<std::size_t>(o)];
      // The centre lies at most the outline's radius behind the surface: an object farther than
      // that plus the best error cannot do better (most of a large map).
      if ((surface - object.center).norm() - outline_radius_[static_cast<std::size_t>(o)] >=
          best_error) {
        continue;
      }
      if (std::any_of(matched->begin(), matched->end(),
                      [o](const Match& m) { return m.second == o; })) {
        continue;
      }
      const Eigen::Vector2d centre = surface + CenterBehindSurface(object, -ray) * ray;
      const double centre_error = (centre - object.center).norm();
      double error = centre_error;
      if (options_.agreement_by_outline && outlines_[static_cast<std::size_t>(o)].size() >= 3) {
        // A large object seen from close by or at a slant: the ray through the box centre hits
        // its surface far from the line to its centre, and the centre it implies is off by up
        // to half the object; the surface point itself lies on the mapped outline.
        const double inside = cv::pointPolygonTest(
            outlines_[static_cast<std::size_t>(o)],
            cv::Point2f(static_cast<float>(surface.x()), static_cast<float>(surface.y())), true);
        error = std::min(error, std::max(0.0, -inside));
      }
      if (error < best_error) {
        best_error = error;
        best_centre_error = centre_error;
        best = o;
      }
    }
    if (best < 0) continue;
    matched->emplace_back(static_cast<int>(k), best);
    if (by_centre != nullptr && best_centre_error < radius) {
      by_centre->emplace_back(static_cast<int>(k), best);
    }
  }
}

std::vector<std::pair<int, int>> PreLocalizer::MatchIds(std::span<const Match> matched) const {
  std::vector<std::pair<int, int>> ids;
  ids.reserve(matched.size());
  for (const auto& [k, o] : matched) ids.emplace_back(k, objects_[static_cast<std::size_t>(o)].id);
  return ids;
}

int PreLocalizer::Agreeing(const std::vector<ObservedObject>& observed, const Pose2& pose) const {
  std::vector<Match> matched;
  MatchAgreeing(observed, ClassesOf(observed), pose, &matched);
  return static_cast<int>(matched.size());
}

std::vector<PoseCandidate> PreLocalizer::Localize(
    const std::vector<ObservedObject>& observed,
    const std::function<double(const Pose2&)>& laser_score, const std::vector<int>* only,
    int min_agreeing, const std::function<Pose2(const Pose2&)>& laser_refine) const {
  // No pose explains more objects than are seen.
  if (min_agreeing > static_cast<int>(observed.size())) return {};
  const auto allowed = [&](int o) {
    const int id = objects_[static_cast<std::size_t>(o)].id;
    return only == nullptr || std::find(only->begin(), only->end(), id) != only->end();
  };
  const std::vector<int> classes = ClassesOf(observed);
  // A place that explains at least min_agreeing of the n objects explains at least two of any
  // n − min_agreeing + 2 of them (pigeonhole), and a pair of those gives its hypothesis: pairs
  // among the first that many (the newest: least odometry error), and one more in case a pair's
  // geometry fails, find it. A lock re-check asks for more than the tracked pose explains, often
  // all but one or two of a dozen objects, and pairs only among four of them.
  const std::size_t n = observed.size();
  const std::size_t pairing = min_agreeing >= 2 && options_.pair_only_as_needed
                                  ? std::min(n, n - static_cast<std::size_t>(min_agreeing) + 3)
                                  : n;
  std::vector<PoseCandidate> candidates;
  for (std::size_t i = 0; i < pairing; ++i) {
    for (std::size_t j = i + 1; j < pairing; ++j) {
      const double d = (observed[i].surface - observed[j].surface).norm();
      ForEachPair(classes[i], classes[j], d, options_.distance_slack, [&](int a, int b, double) {
        if (!allowed(a) || !allowed(b)) return;
        AddPairHypotheses(observed, static_cast<int>(i), static_cast<int>(j), a, b, &candidates);
      });
    }
  }
  Rate(observed, classes, laser_score, laser_refine, options_.min_laser_score, min_agreeing,
       &candidates);
  return RefineByLaser(observed, classes, laser_score, laser_refine,
                       BestDistinct(std::move(candidates)));
}

std::vector<PoseCandidate> PreLocalizer::LocalizeSingle(
    const std::vector<ObservedObject>& observed,
    const std::function<double(const Pose2&)>& laser_score,
    const std::function<Pose2(const Pose2&)>& laser_refine) const {
  std::vector<PoseCandidate> candidates;
  if (!laser_score) return candidates;
  const std::vector<int> classes = ClassesOf(observed);
  std::vector<std::size_t> nearest(observed.size());
  std::iota(nearest.begin(), nearest.end(), std::size_t{0});
  std::sort(nearest.begin(), nearest.end(), [&observed](std::size_t x, std::size_t y) {
    return observed[x].range < observed[y].range;
  });
  if (static_cast<int>(nearest.size()) > options_.max_single_objects) {
    nearest.resize(static_cast<std::size_t>(options_.max_single_objects));
  }
  for (const std::size_t i : nearest) {
    if (classes[i] < 0) continue;
    const ObservedObject& s = observed[i];
    const Eigen::Vector2d ray = Unit(s.surface);
    for (const int o : objects_of_class_[static_cast<std::size_t>(classes[i])]) {
      const semantic::SemanticObject& object = objects_[static_cast<std::size_t>(o)];
      const double radius = (s.surface + mean_behind_[static_cast<std::size_t>(o)] * ray).norm();
      const int samples = std::max(
          8, static_cast<int>(std::ceil(2.0 * M_PI * radius / options_.single_object_step)));
      for (int k = 0; k < samples; ++k) {
        const double phi = 2.0 * M_PI * k / samples;
        const Eigen::Vector2d outward(std::cos(phi), std::sin(phi));
        // The centre lies behind the surface seen from this side by the depth in this direction.
        const double range = (s.surface + CenterBehindSurface(object, outward) * ray).norm();
        const Eigen::Vector2d x = object.center + range * outward;
        if (!InFreeSpace(x)) continue;
        PoseCandidate candidate;
        candidate.pose = Pose2(x.x(), x.y(), std::atan2(-outward.y(), -outward.x()) - s.bearing);
        const double sigma = options_.position_std_base +
                             options_.position_std_per_metre * s.range +
                             0.5 * options_.single_object_step;
        candidate.covariance = Eigen::Vector3d(sigma * sigma, sigma * sigma,
                                               options_.heading_std * options_.heading_std)
                                   .asDiagonal();
        candidates.push_back(candidate);
      }
    }
  }
  // The laser rules out most points on the circles: rate only the rest (the agreement with the
  // other objects costs far more than the laser fit).
  std::erase_if(candidates, [&](const PoseCandidate& c) {
    return laser_score(c.pose) < options_.single_object_min_laser_score;
  });
  Rate(observed, classes, laser_score, laser_refine, options_.single_object_min_laser_score, 0,
       &candidates);
  return RefineByLaser(observed, classes, laser_score, laser_refine,
                       BestDistinct(std::move(candidates)));
}

// The centre a surface point implies is off by up to the object's extent where the box's centre
// ray misses the centre (a table or sofa seen from close by, at a slant, or only in part), and
// the mapped centre is the mean of such views: each object counts by the inverse of that
// variance, so that a table does not pull a pose that a computer and a cabinet agree on.
double PreLocalizer::AlignmentWeight(int object) const {
  if (!options_.weight_by_extent) return 1.0;
  const double extent = outline_radius_[static_cast<std::size_t>(object)];
  const double base = options_.centre_std_base;
  return 1.0 / (base * base + extent * extent);
}

void PreLocalizer::Refine(const std::vector<ObservedObject>& observed,
                          std::span<const Match> matched, Pose2* pose) const {
  if (matched.size() < 2) return;
  // The rigid transform that best aligns the centres the camera implies (robot frame) with the
  // mapped centres (world), in closed form (least squares, as Umeyama without scaling). In 2D the
  // best rotation is the angle of Σ (cross, dot) of the centred pairs; Σ over centred pairs is
  // Σ over the pairs less n times the product of the means.
  Eigen::Vector2d seen_sum = Eigen::Vector2d::Zero();
  Eigen::Vector2d mapped_sum = Eigen::Vector2d::Zero();
  double cross = 0.0;
  double dot = 0.0;
  double n = 0.0;  // the sum of the weights
  for (const auto& [k, o] : matched) {
    const ObservedObject& s = observed[static_cast<std::size_t>(k)];
    const semantic::SemanticObject& object = objects_[static_cast<std::size_t>(o)];
    const Eigen::Vector2d world_ray = Unit(object.center - pose->translation());
    const Eigen::Vector2d seen =
        s.surface + CenterBehindSurface(object, -world_ray) * Unit(s.surface);
    const double w = AlignmentWeight(o);
    seen_sum += w * seen;
    mapped_sum += w * object.center;
    cross += w * (seen.x() * object.center.y() - seen.y() * object.center.x());
    dot += w * seen.dot(object.center);
    n += w;
  }
  const Eigen::Vector2d seen_mean = seen_sum / n;
  const Eigen::Vector2d mapped_mean = mapped_sum / n;
  cross -= n * (seen_mean.x() * mapped_mean.y() - seen_mean.y() * mapped_mean.x());
  dot -= n * seen_mean.dot(mapped_mean);
  const double theta = std::atan2(cross, dot);
  const Eigen::Vector2d t = mapped_mean - Eigen::Rotation2Dd(theta) * seen_mean;
  const Pose2 refined(t.x(), t.y(), theta);
  // An alignment that lands outside free space or far away is not trusted.
  if (Standable(refined.translation()) &&
      (refined.translation() - pose->translation()).norm() < 1.0) {
    *pose = refined;
  }
}

void PreLocalizer::Rate(const std::vector<ObservedObject>& observed,
                        const std::vector<int>& classes,
                        const std::function<double(const Pose2&)>& laser_score,
                        const std::function<Pose2(const Pose2&)>& laser_refine,
                        double min_laser_score, int min_agreeing,
                        std::vector<PoseCandidate>* candidates) const {
  std::vector<Match> matched;
  std::vector<Match> centred;
  for (PoseCandidate& candidate : *candidates) {
    MatchAgreeing(observed, classes, candidate.pose, &matched, &centred);
    if (options_.refine) {
      // Only objects whose implied centre agrees steer the alignment: one that agrees by its
      // outline alone implies a centre that is off (that is why it needed the outline).
      Refine(observed, centred, &candidate.pose);
      MatchAgreeing(observed, classes, candidate.pose, &matched, nullptr, min_agreeing);
    }
    candidate.agreeing = static_cast<int>(matched.size());
    if (candidate.agreeing < min_agreeing) continue;  // dropped below
    candidate.matches = MatchIds(matched);
  }
  std::erase_if(*candidates,
                [min_agreeing](const PoseCandidate& c) { return c.agreeing < min_agreeing; });
  if (laser_score) {
    int most_agreeing = 0;           // over all candidates
    int most_agreeing_passing = -1;  // over those the laser's cut lets through
    for (PoseCandidate& candidate : *candidates) {
      candidate.laser_score = laser_score(candidate.pose);
      most_agreeing = std::max(most_agreeing, candidate.agreeing);
      if (candidate.laser_score >= min_laser_score) {
        most_agreeing_passing = std::max(most_agreeing_passing, candidate.agreeing);
      }
    }
    // The laser's fit is sharp (σ 0.05 m): a pose the objects put 0.2 m off the right place may
    // fit worse than the cut while a look-alike place that happens to be placed better passes
    // it. So a candidate below the cut that could still rank with the best — it explains as
    // many objects as the best that passes, or the most of all when none passes — is refined by
    // the laser before it is judged (refining every candidate would cost a Ceres solve for each
    // of what may be hundreds).
    const int worth_refining = most_agreeing_passing >= 0 ? most_agreeing_passing : most_agreeing;
    // Several pairs give hypotheses at one place, and BestDistinct keeps one of them: refine only
    // the best-fitting hypothesis per place (a Ceres solve each; a dozen look-alike offices give
    // dozens of them per frame), and none where one passing the cut explains as many objects.
    std::vector<std::size_t> order;
    for (std::size_t k = 0; k < candidates->size(); ++k) {
      const PoseCandidate& c = (*candidates)[k];
      if (c.laser_score < min_laser_score && c.agreeing >= worth_refining) order.push_back(k);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      return (*candidates)[x].laser_score > (*candidates)[y].laser_score;
    });
    std::vector<const PoseCandidate*> places;
    for (const PoseCandidate& c : *candidates) {
      if (c.laser_score >= min_laser_score) places.push_back(&c);
    }
    for (const std::size_t k : order) {
      PoseCandidate& candidate = (*candidates)[k];
      const bool placed = std::any_of(places.begin(), places.end(), [&](const PoseCandidate* p) {
        return p->agreeing >= candidate.agreeing && SamePlace(p->pose, candidate.pose);
      });
      if (placed) continue;
      RefineOneByLaser(observed, classes, laser_score, laser_refine, &candidate);
      places.push_back(&candidate);
    }
    std::erase_if(*candidates, [min_laser_score](const PoseCandidate& c) {
      return c.laser_score < min_laser_score;
    });
  }
}

void PreLocalizer::RefineOneByLaser(const std::vector<ObservedObject>& observed,
                                    const std::vector<int>& classes,
                                    const std::function<double(const Pose2&)>& laser_score,
                                    const std::function<Pose2(const Pose2&)>& laser_refine,
                                    PoseCandidate* candidate) const {
  if (!options_.laser_refine || !laser_score || !laser_refine) return;
  const Pose2 refined = laser_refine(candidate->pose);
  if ((refined.translation() - candidate->pose.translation()).norm() >
          options_.laser_refine_max_shift ||
      std::abs(NormalizeAngle(refined.theta - candidate->pose.theta)) >
          options_.laser_refine_max_turn ||
      !OffObstacles(refined.translation())) {
    // Slid along a corridor or into a neighbouring room: the objects' pose stands. The refined
    // pose need not be in the map's free space: the scan's better fit vouches for it, and a
    // robot wedged among furniture can stand where the mapping run's rays never reached
    // (office_floor seed 15, a development seed, trial 5: the scan refined the right office's
    // hypothesis onto the true pose, on an unknown cell, and it was refused).
    return;
  }
  std::vector<Match> matched;
  MatchAgreeing(observed, classes, refined, &matched, nullptr, candidate->agreeing);
  if (static_cast<int>(matched.size()) < candidate->agreeing) return;
  const double score = laser_score(refined);
  if (score < candidate->laser_score) return;
  candidate->pose = refined;
  candidate->laser_score = score;
  candidate->agreeing = static_cast<int>(matched.size());
  candidate->matches = MatchIds(matched);
}

std::vector<PoseCandidate> PreLocalizer::RefineByLaser(
    const std::vector<ObservedObject>& observed, const std::vector<int>& classes,
    const std::function<double(const Pose2&)>& laser_score,
    const std::function<Pose2(const Pose2&)>& laser_refine,
    std::vector<PoseCandidate> candidates) const {
  if (!options_.laser_refine || !laser_score || !laser_refine) return candidates;
  // Only the few kept hypotheses: one refined before the laser's cut starts where it ended.
  for (PoseCandidate& candidate : candidates) {
    RefineOneByLaser(observed, classes, laser_score, laser_refine, &candidate);
  }
  return BestDistinct(std::move(candidates));
}

bool PreLocalizer::SamePlace(const Pose2& a, const Pose2& b) const {
  return (a.translation() - b.translation()).norm() < options_.merge_distance &&
         std::abs(NormalizeAngle(a.theta - b.theta)) < options_.merge_heading;
}

bool PreLocalizer::DistinctPlaces(const Pose2& a, const Pose2& b) const {
  return (a.translation() - b.translation()).norm() > options_.distinct_place_distance ||
         std::abs(NormalizeAngle(a.theta - b.theta)) > options_.distinct_place_heading;
}

bool PreLocalizer::Decided(const std::vector<PoseCandidate>& candidates) const {
  if (candidates.empty()) return false;
  const PoseCandidate& best = candidates.front();
  return std::none_of(candidates.begin() + 1, candidates.end(), [&](const PoseCandidate& c) {
    const bool tie = c.agreeing >= best.agreeing &&
                     c.laser_score >= best.laser_score - options_.look_alike_laser_margin;
    const bool laser_disagrees =
        c.agreeing + 1 >= best.agreeing &&
        c.laser_score > best.laser_score + options_.look_alike_laser_margin;
    return (tie || laser_disagrees) && DistinctPlaces(c.pose, best.pose);
  });
}

std::vector<PoseCandidate> PreLocalizer::BestDistinct(std::vector<PoseCandidate> candidates) const {
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const PoseCandidate& x, const PoseCandidate& y) {
                     if (x.agreeing != y.agreeing) return x.agreeing > y.agreeing;
                     return x.laser_score > y.laser_score;
                   });
  // One hypothesis per place: the best of those that coincide.
  std::vector<PoseCandidate> kept;
  for (const PoseCandidate& candidate : candidates) {
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const PoseCandidate& k) {
      return SamePlace(k.pose, candidate.pose);
    });
    if (!duplicate) kept.push_back(candidate);
    if (static_cast<int>(kept.size()) >= options_.max_hypotheses) break;
  }
  return kept;
}

}  // namespace semchain::localization
