#pragma once

#include <Eigen/Core>
#include <functional>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/pose2.h"
#include "localization/mapped_pairs.h"
#include "localization/object_circles.h"
#include "localization/observed_object.h"
#include "localization/prelocalization_options.h"
#include "localization/standable_space.h"
#include "mapping/map_io.h"
#include "semantic/semantic_map.h"

// Semantic pre-localization (seed 000 §3.1, seed 001 §2.1–2.2, DESIGN.md §3.6): the objects a
// frame shows are matched to pairs of mapped objects of the same classes whose distance D
// agrees with the observed one ((1 − α)D < d < (1 + α)D, seed 001); the robot is where the
// circles around the two mapped centres, with the measured ranges as radii, intersect in free
// space, its heading where the bearings agree. Look-alike places give several hypotheses, so all
// are returned, ranked by how many of the other objects in view agree and by the laser scan.
namespace semchain::localization {

// A robot pose explaining what the frame shows.
struct PoseCandidate {
  Pose2 pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  int agreeing = 0;          // objects in view that the pose explains (the pair included)
  double laser_score = 0.0;  // of the current scan at this pose (0 when not rated)
  std::vector<std::pair<int, int>> matches;  // (observed index, mapped object id)
};

class PreLocalizer {
 public:
  PreLocalizer(const semantic::SemanticMap& map, const mapping::MapImage& occupancy,
               const PreLocalizationOptions& options);

  // Hypotheses for a frame's observed objects (at least two needed), best first.
  // 'laser_score' (may be empty) rates a pose by the current laser scan, higher is better.
  // 'only' (may be null) restricts the mapped pairs to these object ids (e.g. the chain
  // neighbours of an object the bag of words found hidden). Hypotheses that explain fewer than
  // 'min_agreeing' of the observed objects are dropped before the laser rates them (a caller
  // that only wants poses explaining more than one it has).
  // 'laser_refine' (may be empty) moves a pose to where the current scan fits the map best
  // nearby (see PreLocalizationOptions::laser_refine; needs 'laser_score').
  std::vector<PoseCandidate> Localize(
      const std::vector<ObservedObject>& observed,
      const std::function<double(const Pose2&)>& laser_score = {},
      const std::vector<int>* only = nullptr, int min_agreeing = 0,
      const std::function<Pose2(const Pose2&)>& laser_refine = {}) const;

  // Hypotheses from single objects, for when no two objects in view form a mapped pair (a
  // corridor where the objects are far apart): the robot lies on the circle around each mapped
  // object of the observed class, at the measured range, facing it at the measured bearing. Only
  // the laser tells the poses on the circles apart, so 'laser_score' is required; the nearest
  // 'max_single_objects' observations are used, best laser fit first.
  std::vector<PoseCandidate> LocalizeSingle(
      const std::vector<ObservedObject>& observed,
      const std::function<double(const Pose2&)>& laser_score,
      const std::function<Pose2(const Pose2&)>& laser_refine = {}) const;

  // The mapped pairs of classes (a, b) whose distance D satisfies the tolerance for an
  // observed distance d missing by up to 'slack' metres first (seed 001 retrieval when 0):
  // (object id a, object id b, D).
  std::vector<std::tuple<int, int, double>> RetrievePairs(const std::string& class_a,
                                                          const std::string& class_b, double d,
                                                          double slack = 0.0) const;

  // How many of 'observed' a robot at 'pose' explains (a mapped object of the observed class
  // lies where the pose puts it, as for the hypotheses' agreement).
  int Agreeing(const std::vector<ObservedObject>& observed, const Pose2& pose) const;

  // Whether the best of 'candidates' (ordered as Localize returns them) stands out: no
  // hypothesis at a distinct place explains as many objects with a laser fit within
  // look_alike_laser_margin of it, nor one object fewer with a fit better by more than that
  // margin (the objects and the laser disagree: lab_loop seed 3, a development seed, trial 32,
  // five cabinets and a door fitted a place 3.6 m off at 0.66 where the right one explained four
  // at 0.997). Empty candidates decide nothing.
  bool Decided(const std::vector<PoseCandidate>& candidates) const;
  // Whether 'a' and 'b' are different places (distinct_place_distance / _heading).
  bool DistinctPlaces(const Pose2& a, const Pose2& b) const;

  const PreLocalizationOptions& options() const { return options_; }

 private:
  // An observed object matched to a mapped one: (observed index, index into objects_).
  using Match = std::pair<int, int>;

  // The class ids (MappedPairs::ClassId) of observed objects.
  std::vector<int> ClassesOf(const std::vector<ObservedObject>& observed) const;
  // Hypotheses from observed objects i and j seen as mapped objects a and b.
  void AddPairHypotheses(const std::vector<ObservedObject>& observed, int i, int j, int a, int b,
                         std::vector<PoseCandidate>* out) const;
  // Moves 'candidate' where 'laser_refine' says the scan fits best, within the limits of
  // PreLocalizationOptions::laser_refine (agreement, matches and laser score updated).
  void RefineOneByLaser(const std::vector<ObservedObject>& observed,
                        const std::vector<int>& classes,
                        const std::function<double(const Pose2&)>& laser_score,
                        const std::function<Pose2(const Pose2&)>& laser_refine,
                        PoseCandidate* candidate) const;
  // RefineOneByLaser for each candidate, then merges and ranks them again (BestDistinct).
  std::vector<PoseCandidate> RefineByLaser(const std::vector<ObservedObject>& observed,
                                           const std::vector<int>& classes,
                                           const std::function<double(const Pose2&)>& laser_score,
                                           const std::function<Pose2(const Pose2&)>& laser_refine,
                                           std::vector<PoseCandidate> candidates) const;
  // Merges coinciding candidates (the best first) and keeps max_hypotheses.
  std::vector<PoseCandidate> BestDistinct(std::vector<PoseCandidate> candidates) const;
  // The observed objects a robot at 'pose' explains, each matched to one mapped object.
  // 'by_centre' (may be null): those of them whose implied centre agrees (not only the outline).
  // With 'needed' > 0 the search stops, 'matched' incomplete, as soon as fewer than 'needed' can
  // be reached: a caller that drops such a pose need not count the rest (a lock re-check asks
  // for all but one of a dozen objects, and most pairs' poses miss two at once).
  void MatchAgreeing(const std::vector<ObservedObject>& observed, const std::vector<int>& classes,
                     const Pose2& pose, std::vector<Match>* matched,
                     std::vector<Match>* by_centre = nullptr, int needed = 0) const;
  // The matches as PoseCandidate::matches names them: (observed index, mapped object id).
  std::vector<std::pair<int, int>> MatchIds(std::span<const Match> matched) const;
  // Poses within merge_distance and merge_heading: one hypothesis.
  bool SamePlace(const Pose2& a, const Pose2& b) const;
  // How much a mapped object counts in Refine (see PreLocalizationOptions::weight_by_extent).
  double AlignmentWeight(int object) const;
  // Least-squares pose over the matches (see PreLocalizationOptions::refine).
  void Refine(const std::vector<ObservedObject>& observed, std::span<const Match> matched,
              Pose2* pose) const;
  // Agreement and refinement of every candidate; drops those agreeing with fewer than
  // 'min_agreeing' objects, then rates the rest by the laser (those explaining the most objects
  // refined by it first when they fit below the cut) and drops what it rules out.
  void Rate(const std::vector<ObservedObject>& observed, const std::vector<int>& classes,
            const std::function<double(const Pose2&)>& laser_score,
            const std::function<Pose2(const Pose2&)>& laser_refine, double min_laser_score,
            int min_agreeing, std::vector<PoseCandidate>* candidates) const;
  // Rate's laser part: each candidate's laser score; those explaining the most objects that fit
  // below the cut are refined by the laser first (one per place), then the cut drops the rest.
  void RateByLaser(const std::vector<ObservedObject>& observed, const std::vector<int>& classes,
                   const std::function<double(const Pose2&)>& laser_score,
                   const std::function<Pose2(const Pose2&)>& laser_refine, double min_laser_score,
                   std::vector<PoseCandidate>* candidates) const;

  std::vector<semantic::SemanticObject> objects_;
  // Per object: the largest distance from its centre to its outline (a bound on the centre's
  // depth behind any surface seen) and the mean over directions (the depth behind a surface
  // seen from an unknown side).
  std::vector<double> outline_radius_;
  std::vector<double> mean_behind_;
  std::vector<std::vector<cv::Point2f>> outlines_;  // per object: its footprint, for OpenCV
  MappedPairs pairs_;                               // indices into objects_
  StandableSpace space_;
  PreLocalizationOptions options_;
};

}  // namespace semchain::localization
