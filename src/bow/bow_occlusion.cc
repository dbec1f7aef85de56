#include "bow/bow_occlusion.h"

#include <algorithm>

#include "bow/bow_vocabulary_io.h"

namespace semchain::bow {

Result<KeyframeRecognizer> LoadKeyframeRecognizer(const std::filesystem::path& vocabulary,
                                                  const std::filesystem::path& keyframes_json,
                                                  const KeyframeRecognizerOptions& options,
                                                  const std::filesystem::path& run_dir) {
  Result<Vocabulary> words = ReadVocabulary(vocabulary);
  if (!words.ok()) return words.status();
  Result<semantic::KeyframeDatabase> keyframes = semantic::ReadKeyframes(keyframes_json);
  if (!keyframes.ok()) return keyframes.status();
  return KeyframeRecognizer::Build(std::move(*words), std::move(*keyframes), options, run_dir);
}

OcclusionQuery QueryOccludedObjects(const KeyframeRecognizer& recognizer,
                                    const semantic::SemanticMap& map, const cv::Mat& descriptors,
                                    const std::vector<Detection>& detections,
                                    const OcclusionQueryOptions& options) {
  OcclusionQuery query;
  query.matches = recognizer.QueryDescriptors(descriptors, std::max(1, options.candidates));
  std::vector<const semantic::Keyframe*> ranked;
  for (const KeyframeMatch& match : query.matches)
    ranked.push_back(&recognizer.keyframe(match.keyframe));
  query.inference = InferOccludedObjects(map, ranked, detections);
  return query;
}

}  // namespace semchain::bow
