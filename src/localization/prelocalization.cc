#include "localization/prelocalization.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "core/angles.h"

// Hypothesis generation: the poses where the circles around a retrieved pair of mapped objects
// meet (Localize) or the points on the circle around one mapped object (LocalizeSingle). Their
// agreement with the other objects, the laser's rating and the ranking are in
// prelocalization_rating.cc.
namespace semchain::localization {
namespace {

// Fixed-point iterations of the centre-behind-surface correction, at most, and the move of the
// position below which it has settled (the depth changes little with the direction seen from).
constexpr int kRefinements = 4;
constexpr double kSettledMeters = 1e-3;

// Where an object's centre is in the robot frame, the camera having seen its surface: behind the
// surface by the centre's depth 'behind' in the direction seen.
Eigen::Vector2d CentreInRobot(const ObservedObject& s, double behind) {
  return Eigen::Vector2d(s.surface + behind * UnitDirection(s.surface));
}

// Moves the intersection 'x' of the circles around mapped objects 'oa' and 'ob' (seen as 'si'
// and 'sj') to where it is with the depth behind the surface seen from it (a fixed point: the
// depth depends on the direction, the direction on the position); 'pi' and 'pj' are the centres
// in the robot frame seen from there. False when the circles no longer meet.
bool SettleOnCircles(const semantic::SemanticObject& oa, const semantic::SemanticObject& ob,
                     const ObservedObject& si, const ObservedObject& sj, double slack,
                     Eigen::Vector2d* x, Eigen::Vector2d* pi, Eigen::Vector2d* pj) {
  for (int iteration = 0; iteration < kRefinements; ++iteration) {
    *pi = CentreInRobot(si, CenterBehindSurface(oa, UnitDirection(*x - oa.center)));
    *pj = CentreInRobot(sj, CenterBehindSurface(ob, UnitDirection(*x - ob.center)));
    Eigen::Vector2d refined[2];
    const int n = IntersectCircles(oa.center, pi->norm(), ob.center, pj->norm(), slack, refined);
    if (n == 0) return false;
    const Eigen::Vector2d next =
        n == 2 && (refined[1] - *x).norm() < (refined[0] - *x).norm() ? refined[1] : refined[0];
    const bool settled = (next - *x).norm() < kSettledMeters;
    *x = next;
    if (settled) break;
  }
  return true;
}

}  // namespace

PreLocalizer::PreLocalizer(const semantic::SemanticMap& map, const mapping::MapImage& occupancy,
                           const PreLocalizationOptions& options)
    : objects_(map.objects),
      pairs_(objects_, options.distance_tolerance),
      space_(occupancy, options.clearance, options.unknown_reach),
      options_(options) {
  for (const semantic::SemanticObject& object : objects_) {
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
}

std::vector<int> PreLocalizer::ClassesOf(const std::vector<ObservedObject>& observed) const {
  std::vector<int> classes;
  classes.reserve(observed.size());
  for (const ObservedObject& s : observed) classes.push_back(pairs_.ClassId(s.class_name));
  return classes;
}

std::vector<std::tuple<int, int, double>> PreLocalizer::RetrievePairs(const std::string& class_a,
                                                                      const std::string& class_b,
                                                                      double d,
                                                                      double slack) const {
  std::vector<std::tuple<int, int, double>> found;
  pairs_.ForEachPair(pairs_.ClassId(class_a), pairs_.ClassId(class_b), d, slack,
                     [&](int oa, int ob, double distance) {
                       found.emplace_back(objects_[static_cast<std::size_t>(oa)].id,
                                          objects_[static_cast<std::size_t>(ob)].id, distance);
                     });
  return found;
}

void PreLocalizer::AddPairHypotheses(const std::vector<ObservedObject>& observed, int i, int j,
                                     int a, int b, std::vector<PoseCandidate>* out) const {
  const semantic::SemanticObject& oa = objects_[a];
  const semantic::SemanticObject& ob = objects_[b];
  const ObservedObject& si = observed[i];
  const ObservedObject& sj = observed[j];
  Eigen::Vector2d points[2];
  // Range errors grow with range: far circles may miss each other by more.
  const double slack =
      options_.circle_slack + options_.circle_slack_per_metre * (si.range + sj.range);
  const int count = IntersectCircles(
      oa.center, CentreInRobot(si, mean_behind_[static_cast<std::size_t>(a)]).norm(), ob.center,
      CentreInRobot(sj, mean_behind_[static_cast<std::size_t>(b)]).norm(), slack, points);
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
    // Refined with the depth behind the surface seen from this position.
    Eigen::Vector2d x = points[k];
    Eigen::Vector2d pi, pj;
    if (!SettleOnCircles(oa, ob, si, sj, slack, &x, &pi, &pj)) continue;
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
    if (!space_.Standable(candidate.pose.translation())) continue;
    if (!headings_agree(candidate.pose.translation())) continue;
    candidate.covariance =
        Eigen::Vector3d(sigma * sigma, sigma * sigma, options_.heading_std * options_.heading_std)
            .asDiagonal();
    out->push_back(candidate);
  }
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
      pairs_.ForEachPair(classes[i], classes[j], d, options_.distance_slack,
                         [&](int a, int b, double) {
                           if (!allowed(a) || !allowed(b)) return;
                           AddPairHypotheses(observed, static_cast<int>(i), static_cast<int>(j), a,
                                             b, &candidates);
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
    const Eigen::Vector2d ray = UnitDirection(s.surface);
    for (const int o : pairs_.ObjectsOfClass(classes[i])) {
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
        if (!space_.InFreeSpace(x)) continue;
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

}  // namespace semchain::localization
