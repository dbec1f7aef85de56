#include "semantic/keyframe_selection.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/angles.h"

namespace semchain::semantic {
namespace {

bool Shows(const Keyframe& keyframe, int id) {
  return id >= 0 && std::any_of(keyframe.objects.begin(), keyframe.objects.end(),
                                [id](const KeyframeObject& o) { return o.id == id; });
}

// How much of an object's chain neighbourhood a keyframe shows: the object and each neighbour.
int Neighbourhood(const Keyframe& keyframe, const KeyframeObject& object) {
  return 1 + (Shows(keyframe, object.upstream) ? 1 : 0) +
         (Shows(keyframe, object.downstream) ? 1 : 0);
}

}  // namespace

bool KeyframeSelectionOptions::Validate(std::string* error) const {
  if (views_per_object < 0 || !(distinct_view_meters >= 0.0) || !(distinct_view_radians >= 0.0)) {
    *error = "views_per_object, distinct_view_meters and distinct_view_radians must be >= 0";
    return false;
  }
  return true;
}

std::vector<Keyframe> SelectCoveringKeyframes(const std::vector<Keyframe>& keyframes,
                                              const KeyframeSelectionOptions& options) {
  if (options.views_per_object <= 0) return keyframes;
  // The most of each object's neighbourhood any frame shows: only frames showing that much are
  // views of it (a frame with the object alone does not tell which chain node it is, when a
  // frame with its neighbours exists).
  std::map<int, int> best;
  for (const Keyframe& keyframe : keyframes) {
    for (const KeyframeObject& object : keyframe.objects) {
      int& b = best[object.id];
      b = std::max(b, Neighbourhood(keyframe, object));
    }
  }
  std::map<int, std::vector<Pose2>> views;  // the poses of each object's kept views
  const auto distinct = [&](int id, const Pose2& pose) {
    const std::vector<Pose2>& kept = views[id];
    return std::all_of(kept.begin(), kept.end(), [&](const Pose2& v) {
      return (v.translation() - pose.translation()).norm() >= options.distinct_view_meters ||
             std::abs(NormalizeAngle(v.theta - pose.theta)) >= options.distinct_view_radians;
    });
  };
  // Whether a keyframe is a new view of one of its objects that still lacks views.
  const auto adds_view = [&](const Keyframe& keyframe, const KeyframeObject& object) {
    return static_cast<int>(views[object.id].size()) < options.views_per_object &&
           Neighbourhood(keyframe, object) == best[object.id] && distinct(object.id, keyframe.pose);
  };
  const auto gain = [&](const Keyframe& keyframe) {
    return static_cast<int>(
        std::count_if(keyframe.objects.begin(), keyframe.objects.end(),
                      [&](const KeyframeObject& object) { return adds_view(keyframe, object); }));
  };
  std::vector<bool> kept(keyframes.size(), false);
  while (true) {
    int chosen = -1;
    int chosen_gain = 0;
    for (std::size_t k = 0; k < keyframes.size(); ++k) {
      if (kept[k]) continue;
      const int g = gain(keyframes[k]);
      // Ties: the frame showing more objects (more for the bag of words to match), then the
      // earlier one (deterministic).
      if (g > chosen_gain || (g == chosen_gain && g > 0 &&
                              keyframes[k].objects.size() >
                                  keyframes[static_cast<std::size_t>(chosen)].objects.size())) {
        chosen = static_cast<int>(k);
        chosen_gain = g;
      }
    }
    if (chosen < 0) break;
    const Keyframe& keyframe = keyframes[static_cast<std::size_t>(chosen)];
    std::vector<int> added;
    for (const KeyframeObject& object : keyframe.objects) {
      if (adds_view(keyframe, object)) added.push_back(object.id);
    }
    for (const int id : added) views[id].push_back(keyframe.pose);
    kept[static_cast<std::size_t>(chosen)] = true;
  }
  std::vector<Keyframe> selected;
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    if (kept[k]) selected.push_back(keyframes[k]);
  }
  return selected;
}

}  // namespace semchain::semantic
