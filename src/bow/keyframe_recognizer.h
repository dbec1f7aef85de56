#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "bow/bow_database.h"
#include "bow/bow_vocabulary.h"
#include "bow/orb_features.h"
#include "core/status.h"
#include "semantic/keyframes.h"

// Place recognition against the keyframes of semantic mapping (seed 000 §3.1 step 3): each
// keyframe's colour image is described by its TF-IDF vector in a BowDatabase; a frame's most
// similar keyframe is the query's best match.
namespace semchain::bow {

struct KeyframeRecognizerOptions {
  OrbOptions orb;
  int direct_index_level = 2;  // tree level of the direct index (1..L; deeper = finer)
};

struct KeyframeMatch {
  int keyframe = -1;   // index into keyframes().keyframes
  double score = 0.0;  // L1 score, 0..1
};

class KeyframeRecognizer {
 public:
  // Reads and describes every keyframe's colour image: run_dir/<frame>.png, with run_dir the
  // database's "run" unless 'run_dir' is given. A missing image is an error naming it.
  // 'progress' (may be empty) gets (done, total) keyframes.
  static Result<KeyframeRecognizer> Build(
      Vocabulary vocabulary, semantic::KeyframeDatabase keyframes,
      const KeyframeRecognizerOptions& options, const std::filesystem::path& run_dir = {},
      const std::function<void(std::size_t, std::size_t)>& progress = {});

  // The same from descriptors already extracted (one Mat per keyframe, in order).
  static KeyframeRecognizer FromDescriptors(Vocabulary vocabulary,
                                            semantic::KeyframeDatabase keyframes,
                                            const std::vector<cv::Mat>& descriptors,
                                            const KeyframeRecognizerOptions& options);

  // The keyframes most similar to a colour (RGB) or grey image, best first, at most
  // 'max_results', only those sharing a word with it.
  std::vector<KeyframeMatch> QueryImage(const cv::Mat& image, int max_results) const;
  // The same from the image's ORB descriptors.
  std::vector<KeyframeMatch> QueryDescriptors(const cv::Mat& descriptors, int max_results) const;

  const semantic::KeyframeDatabase& keyframes() const { return keyframes_; }
  const semantic::Keyframe& keyframe(int index) const { return keyframes_.keyframes[index]; }
  const Vocabulary& vocabulary() const { return vocabulary_; }
  const BowDatabase& database() const { return database_; }

 private:
  KeyframeRecognizer(Vocabulary vocabulary, semantic::KeyframeDatabase keyframes,
                     const KeyframeRecognizerOptions& options);

  Vocabulary vocabulary_;
  semantic::KeyframeDatabase keyframes_;
  KeyframeRecognizerOptions options_;
  BowDatabase database_;
};

}  // namespace semchain::bow
