#pragma once

#include <string>
#include <vector>

#include "semantic/keyframes.h"

// Which of the frames that show mapped objects are kept as keyframes (seed 000 §3.1 step 2: "the
// keyframes chosen should cover each object together with its upstream and downstream objects").
// Every frame with a mapped object is a candidate; most of them repeat their neighbours (a
// camera at 5–10 Hz sees the same objects from nearly the same pose for seconds). The kept set
// covers every object: for each, up to 'views_per_object' keyframes from distinct poses that show
// it with as many of its chain neighbours as any frame does, chosen greedily (the frame that
// covers the most objects still short of views first, as in the greedy set cover).
namespace semchain::semantic {

struct KeyframeSelectionOptions {
  // Keyframes per object (distinct views); 0 keeps every candidate frame. More than one: the bag
  // of words recognises a place from another viewpoint than the one keyframe it was mapped from.
  int views_per_object = 3;
  // Two keyframes of an object are distinct views when their poses are this far apart in
  // position (metres) or heading (radians).
  double distinct_view_meters = 0.5;
  double distinct_view_radians = 0.35;

  bool Validate(std::string* error) const;
};

// The covering subset of 'keyframes', in their order.
std::vector<Keyframe> SelectCoveringKeyframes(const std::vector<Keyframe>& keyframes,
                                              const KeyframeSelectionOptions& options = {});

}  // namespace semchain::semantic
