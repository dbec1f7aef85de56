#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "localization/pose_hypothesis.h"
#include "semantic/semantic_map.h"

// /semchain/objects for RViz: every object's footprint and class, the chain list, and the
// hypotheses of the latest pre-localization. Namespaces "objects", "labels", "chains" and
// "hypotheses"; ids are stable within a namespace, so a new array replaces the old one.
namespace semchain::ros1 {

visualization_msgs::MarkerArray ObjectMarkers(
    const semantic::SemanticMap& map, const std::vector<localization::PoseHypothesis>& hypotheses,
    const std::string& frame_id);

}  // namespace semchain::ros1
