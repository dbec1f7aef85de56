#include "bow/occlusion_inference.h"

#include <algorithm>

namespace semchain::bow {
namespace {

// Chain neighbours farther apart than this are never in one camera frame, so they cannot be the
// pair seen now around a hidden object (a chain wraps from one end of a hall to the other; the
// pre-localizer pairs nothing farther apart either).
constexpr double kMaxNeighboursDistance = 15.0;

// The node of 'id' with its neighbours when both neighbours' classes are seen now and the two
// could be in view together.
bool Fits(const semantic::SemanticMap& map, int id, const std::vector<std::string>& classes,
          const std::vector<int>& current, OccludedObject* object) {
  semantic::ChainNeighbours neighbours;
  if (!semantic::FindChainNeighbours(map, id, &neighbours)) return false;
  const semantic::SemanticObject* self = map.Find(id);
  const semantic::SemanticObject* up = map.Find(neighbours.upstream);
  const semantic::SemanticObject* down = map.Find(neighbours.downstream);
  if (self == nullptr || up == nullptr || down == nullptr || up == down) return false;
  if ((up->center - down->center).norm() > kMaxNeighboursDistance) return false;
  std::vector<int> needed(classes.size(), 0);
  for (const semantic::SemanticObject* o : {up, down}) {
    const auto it = std::find(classes.begin(), classes.end(), o->class_name);
    if (it == classes.end()) return false;
    ++needed[static_cast<std::size_t>(it - classes.begin())];
  }
  for (std::size_t c = 0; c < classes.size(); ++c) {
    if (current[c] < needed[c]) return false;
  }
  *object = {id, self->class_name, up->id, down->id, (up->center - down->center).norm()};
  return true;
}

std::vector<OccludedObject> FittingNodes(const semantic::SemanticMap& map,
                                         const std::vector<int>& ids,
                                         const std::vector<std::string>& classes,
                                         const std::vector<int>& current) {
  std::vector<OccludedObject> fitting;
  for (int id : ids) {
    OccludedObject object;
    if (Fits(map, id, classes, current, &object)) fitting.push_back(object);
  }
  return fitting;
}

std::string IdList(const std::vector<OccludedObject>& objects) {
  std::string list;
  for (const OccludedObject& o : objects) list += (list.empty() ? "" : ", ") + std::to_string(o.id);
  return list;
}

}  // namespace

std::vector<std::string> CountVectorClasses(const semantic::SemanticMap& map) {
  std::vector<std::string> classes = DefaultClassNames();
  for (const std::string& name : map.classes) {
    if (std::find(classes.begin(), classes.end(), name) == classes.end()) classes.push_back(name);
  }
  return classes;
}

std::vector<int> CountClasses(const std::vector<std::string>& names,
                              const std::vector<std::string>& classes) {
  std::vector<int> counts(classes.size(), 0);
  for (const std::string& name : names) {
    const auto it = std::find(classes.begin(), classes.end(), name);
    if (it != classes.end()) ++counts[static_cast<std::size_t>(it - classes.begin())];
  }
  return counts;
}

std::vector<int> CountClasses(const std::vector<Detection>& detections,
                              const std::vector<std::string>& classes) {
  std::vector<std::string> names;
  for (const Detection& detection : detections) names.push_back(detection.class_name);
  return CountClasses(names, classes);
}

std::vector<int> CountClasses(const semantic::Keyframe& keyframe,
                              const std::vector<std::string>& classes) {
  std::vector<std::string> names;
  for (const semantic::KeyframeObject& object : keyframe.objects)
    names.push_back(object.class_name);
  return CountClasses(names, classes);
}

std::vector<int> ClassDifference(const std::vector<int>& keyframe,
                                 const std::vector<int>& current) {
  std::vector<int> difference(std::max(keyframe.size(), current.size()), 0);
  for (std::size_t i = 0; i < difference.size(); ++i) {
    difference[i] = (i < keyframe.size() ? keyframe[i] : 0) - (i < current.size() ? current[i] : 0);
  }
  return difference;
}

OcclusionInference InferOccludedObjects(const semantic::SemanticMap& map,
                                        const semantic::Keyframe& keyframe,
                                        const std::vector<Detection>& detections) {
  OcclusionInference result;
  result.classes = CountVectorClasses(map);
  result.current_counts = CountClasses(detections, result.classes);
  result.keyframe_counts = CountClasses(keyframe, result.classes);
  result.difference = ClassDifference(result.keyframe_counts, result.current_counts);
  const auto add_reason = [&](const std::string& why) {
    result.reason += (result.reason.empty() ? "" : "; ") + why;
  };
  for (std::size_t c = 0; c < result.classes.size(); ++c) {
    const int missing = result.difference[c];
    if (missing <= 0) continue;
    const std::string& name = result.classes[c];
    std::vector<int> in_keyframe;
    for (const semantic::KeyframeObject& o : keyframe.objects) {
      if (o.class_name == name &&
          std::find(in_keyframe.begin(), in_keyframe.end(), o.id) == in_keyframe.end()) {
        in_keyframe.push_back(o.id);
      }
    }
    std::vector<OccludedObject> fitting =
        FittingNodes(map, in_keyframe, result.classes, result.current_counts);
    if (fitting.empty()) {  // the keyframe's own objects do not fit: any node of the class
      std::vector<int> of_class;
      for (const semantic::SemanticObject& o : map.objects) {
        if (o.class_name == name) of_class.push_back(o.id);
      }
      fitting = FittingNodes(map, of_class, result.classes, result.current_counts);
    }
    if (fitting.empty()) {
      add_reason(name + ": no chain node whose neighbours' classes are both seen now");
    } else if (static_cast<int>(fitting.size()) > missing) {
      add_reason(name + ": " + std::to_string(fitting.size()) + " chain nodes fit (ids " +
                 IdList(fitting) + ")");
    } else {
      result.occluded.insert(result.occluded.end(), fitting.begin(), fitting.end());
    }
  }
  if (result.occluded.empty() && result.reason.empty()) {
    result.reason = "no class of the keyframe is missing in the current frame";
  }
  return result;
}

RankedOcclusionInference InferOccludedObjects(const semantic::SemanticMap& map,
                                              const std::vector<const semantic::Keyframe*>& ranked,
                                              const std::vector<Detection>& detections) {
  RankedOcclusionInference result;
  if (ranked.empty()) {
    result.inference.reason = "no keyframe to compare with";
    return result;
  }
  const std::vector<std::string> classes = CountVectorClasses(map);
  const std::vector<int> current = CountClasses(detections, classes);
  // The first covering keyframe whose inference names a hidden object; else the first covering
  // one (its inference says why it fails); else the most similar.
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    const std::vector<int> difference = ClassDifference(CountClasses(*ranked[i], classes), current);
    const bool covers =
        std::all_of(difference.begin(), difference.end(), [](int d) { return d >= 0; });
    const bool more =
        std::any_of(difference.begin(), difference.end(), [](int d) { return d > 0; });
    if (!covers || !more) continue;
    OcclusionInference inference = InferOccludedObjects(map, *ranked[i], detections);
    const bool first_covering = result.used < 0;
    if (first_covering || !inference.occluded.empty()) {
      result.used = static_cast<int>(i);
      result.inference = std::move(inference);
    }
    if (!result.inference.occluded.empty()) return result;
  }
  if (result.used < 0) {
    result.used = 0;
    result.inference = InferOccludedObjects(map, *ranked[0], detections);
  }
  return result;
}

}  // namespace semchain::bow
