#include "bow/keyframe_recognizer.h"

#include <algorithm>

#include "bow/run_features.h"
#include "core/check.h"
#include "io/rgbd_frame_io.h"

namespace semchain::bow {

namespace fs = std::filesystem;

KeyframeRecognizer::KeyframeRecognizer(Vocabulary vocabulary, semantic::KeyframeDatabase keyframes,
                                       const KeyframeRecognizerOptions& options)
    : vocabulary_(std::move(vocabulary)),
      keyframes_(std::move(keyframes)),
      options_(options),
      database_(vocabulary_.words(),
                std::clamp(options.direct_index_level, 1, std::max(1, vocabulary_.levels()))) {
  SEMCHAIN_CHECK(!vocabulary_.empty());
}

Result<KeyframeRecognizer> KeyframeRecognizer::Build(
    Vocabulary vocabulary, semantic::KeyframeDatabase keyframes,
    const KeyframeRecognizerOptions& options, const fs::path& run_dir,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  std::string invalid;
  if (!options.orb.Validate(&invalid)) return Status::Error("ORB options: " + invalid);
  if (vocabulary.empty()) return Status::Error("empty vocabulary");
  const fs::path run = run_dir.empty() ? fs::path(keyframes.run) : run_dir;
  if (run.empty() && !keyframes.keyframes.empty()) {
    return Status::Error(
        "the keyframes name no folder of images (the map was made without camera images); "
        "the bag-of-words stage needs the keyframes' colour images");
  }
  std::vector<fs::path> images;
  for (const semantic::Keyframe& keyframe : keyframes.keyframes) {
    images.push_back(ColorImagePath(run, keyframe.frame));
  }
  Result<std::vector<cv::Mat>> descriptors = ExtractImageDescriptors(images, options.orb, progress);
  if (!descriptors.ok()) return descriptors.status();
  return FromDescriptors(std::move(vocabulary), std::move(keyframes), *descriptors, options);
}

KeyframeRecognizer KeyframeRecognizer::FromDescriptors(Vocabulary vocabulary,
                                                       semantic::KeyframeDatabase keyframes,
                                                       const std::vector<cv::Mat>& descriptors,
                                                       const KeyframeRecognizerOptions& options) {
  SEMCHAIN_CHECK(descriptors.size() == keyframes.keyframes.size());
  KeyframeRecognizer recognizer(std::move(vocabulary), std::move(keyframes), options);
  for (const cv::Mat& d : descriptors) {
    FeatureVector features;
    BowVector vector =
        recognizer.vocabulary_.Transform(d, recognizer.database_.direct_index_level(), &features);
    recognizer.database_.Add(std::move(vector), std::move(features));
  }
  return recognizer;
}

std::vector<KeyframeMatch> KeyframeRecognizer::QueryImage(const cv::Mat& image,
                                                          int max_results) const {
  return QueryDescriptors(ExtractOrbDescriptors(image, options_.orb), max_results);
}

std::vector<KeyframeMatch> KeyframeRecognizer::QueryDescriptors(const cv::Mat& descriptors,
                                                                int max_results) const {
  std::vector<KeyframeMatch> matches;
  for (const BowMatch& match : database_.Query(vocabulary_.Transform(descriptors), max_results)) {
    matches.push_back({match.entry, match.score});
  }
  return matches;
}

}  // namespace semchain::bow
