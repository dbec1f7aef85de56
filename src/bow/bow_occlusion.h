#pragma once

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "bow/keyframe_recognizer.h"
#include "bow/occlusion_inference.h"
#include "core/status.h"
#include "semantic/semantic_map.h"
#include "sensors/detection.h"

// Seed 000 §3.1 steps 3–4 in one call, for localization when pre-localization fails (an object
// of the chain hidden): the frame's bag-of-words ranking of the keyframes, then the hidden
// object's chain node and its two neighbours.
namespace semchain::bow {

// The vocabulary file (bow_vocabulary_io.h) and the keyframes of MAP/keyframes.json with their
// colour images (from the file's "run", or 'run_dir' when given) in a KeyframeRecognizer.
Result<KeyframeRecognizer> LoadKeyframeRecognizer(const std::filesystem::path& vocabulary,
                                                  const std::filesystem::path& keyframes_json,
                                                  const KeyframeRecognizerOptions& options = {},
                                                  const std::filesystem::path& run_dir = {});

struct OcclusionQueryOptions {
  int candidates = 5;  // most similar keyframes the inference may choose from (1 = the paper's)
};

struct OcclusionQuery {
  std::vector<KeyframeMatch> matches;  // the ranking, best first
  // inference.used indexes 'matches' (-1 when no keyframe shares a word with the frame).
  RankedOcclusionInference inference;
};

// The frame's ORB descriptors ranked against the keyframes, then InferOccludedObjects over the
// ranking (occlusion_inference.h) with the frame's 'detections'.
OcclusionQuery QueryOccludedObjects(const KeyframeRecognizer& recognizer,
                                    const semantic::SemanticMap& map, const cv::Mat& descriptors,
                                    const std::vector<Detection>& detections,
                                    const OcclusionQueryOptions& options = {});

}  // namespace semchain::bow
