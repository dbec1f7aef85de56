#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/angles.h"
#include "localization/prelocalization.h"

// How pre-localization rates its hypotheses: the objects in view a pose explains, the
// least-squares alignment over them, the laser's fit and refinement, and the ranking that keeps
// one hypothesis per place and says whether the best stands out from look-alike places.
namespace semchain::localization {

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
    const Eigen::Vector2d ray = UnitDirection(surface - pose.translation());
    int best = -1;
    const double radius = options_.agreement_radius + options_.agreement_per_metre * s.range;
    double best_error = radius;
    double best_centre_error = radius;
    for (const int o : pairs_.ObjectsOfClass(classes[k])) {
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
    const Eigen::Vector2d world_ray = UnitDirection(object.center - pose->translation());
    const Eigen::Vector2d seen =
        s.surface + CenterBehindSurface(object, -world_ray) * UnitDirection(s.surface);
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
  if (space_.Standable(refined.translation()) &&
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
    RateByLaser(observed, classes, laser_score, laser_refine, min_laser_score, candidates);
  }
}

void PreLocalizer::RateByLaser(const std::vector<ObservedObject>& observed,
                               const std::vector<int>& classes,
                               const std::function<double(const Pose2&)>& laser_score,
                               const std::function<Pose2(const Pose2&)>& laser_refine,
                               double min_laser_score,
                               std::vector<PoseCandidate>* candidates) const {
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
      !space_.OffObstacles(refined.translation())) {
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
