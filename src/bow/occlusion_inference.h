#pragma once

#include <string>
#include <vector>

#include "semantic/keyframes.h"
#include "semantic/semantic_map.h"
#include "sensors/detection.h"

// Occlusion immunity, seed 000 §3.1 step 4 (DESIGN.md §3.7; the paper's Fig. 20–21): the class
// counts of the current frame and of its most similar keyframe differ by the hidden object's
// class; its chain node is the node of that class whose upstream and downstream neighbours'
// classes are seen now, and those two neighbours (two hops apart in the chain, distance D)
// give the pre-localization.
namespace semchain::bow {

// The class order of the count vectors: door, cabinet, bucket, chair, stool
// (DefaultClassNames()), then the map's other classes in its order.
std::vector<std::string> CountVectorClasses(const semantic::SemanticMap& map);

// How many of 'names' have each class of 'classes' (names of other classes are not counted).
std::vector<int> CountClasses(const std::vector<std::string>& names,
                              const std::vector<std::string>& classes);
std::vector<int> CountClasses(const std::vector<Detection>& detections,
                              const std::vector<std::string>& classes);
std::vector<int> CountClasses(const semantic::Keyframe& keyframe,
                              const std::vector<std::string>& classes);

// keyframe − current per class: a positive entry is a class the keyframe has and the current
// frame misses (paper: (0,1,1,1,0) − (0,1,0,1,0) = (0,0,1,0,0), the bucket).
std::vector<int> ClassDifference(const std::vector<int>& keyframe, const std::vector<int>& current);

struct OccludedObject {
  int id = -1;  // the hidden object's map id
  std::string class_name;
  int upstream = -1;  // its chain neighbours' ids: the objects pre-localization uses
  int downstream = -1;
  double neighbours_distance = 0.0;  // D: between the two neighbours' centres, metres
};

struct OcclusionInference {
  std::vector<std::string> classes;  // CountVectorClasses(map)
  std::vector<int> current_counts;
  std::vector<int> keyframe_counts;
  std::vector<int> difference;           // keyframe − current
  std::vector<OccludedObject> occluded;  // the hidden objects that could be decided
  // Empty when every missing class was resolved; otherwise why not, e.g. "bucket: 2 chain
  // nodes fit (ids 4, 9)" or "no class of the keyframe is missing in the current frame".
  std::string reason;
};

// Step 4 for the current frame's 'detections' and its best 'keyframe'. For each class the
// keyframe has more of, the candidates are first the keyframe's objects of that class, and
// when none of them fits every chain node of that class in 'map'; a candidate fits when the
// classes of both its chain neighbours (from 'map') are among the current detections and the
// neighbours are close enough (15 m) to be in one frame. A class
// is decided when no more candidates fit than the keyframe has extra objects of it.
OcclusionInference InferOccludedObjects(const semantic::SemanticMap& map,
                                        const semantic::Keyframe& keyframe,
                                        const std::vector<Detection>& detections);

struct RankedOcclusionInference {
  int used = -1;  // index into 'ranked' of the keyframe the inference used; -1 when empty
  OcclusionInference inference;
};

// Step 4 over the bag-of-words ranking 'ranked' (most similar first): the keyframe used is the
// first that shows every object class seen now at least as often and some class more often
// (step 2: a keyframe should cover the hidden object with its up- and downstream neighbours)
// and whose inference names a hidden object; when none names one, the first such covering
// keyframe, and when none covers, the most similar one (whose inference then says why it fails).
RankedOcclusionInference InferOccludedObjects(const semantic::SemanticMap& map,
                                              const std::vector<const semantic::Keyframe*>& ranked,
                                              const std::vector<Detection>& detections);

}  // namespace semchain::bow
