// Vocabulary::Train (bow_vocabulary.h): the hierarchical k-majority tree and its IDF weights.
#include <algorithm>
#include <cmath>
#include <set>

#include "bow/bow_vocabulary.h"
#include "bow/k_majority.h"
#include "core/check.h"
#include "core/rng.h"

namespace semchain::bow {
namespace {

struct TreeBuilder {
  const cv::Mat& all;  // every training descriptor, one per row
  const VocabularyOptions& options;
  Rng rng;
  VocabularyData data;
  // Called after each subtree under the root: (done, total) with total = root children + 1.
  std::function<void(std::size_t, std::size_t)> progress;

  int AddNode(int parent, const cv::Mat& descriptor) {
    data.parent.push_back(parent);
    data.word.push_back(-1);
    data.weight.push_back(0.0);
    data.descriptors.push_back(descriptor);
    return static_cast<int>(data.parent.size()) - 1;
  }

  // Splits 'node' (at 'depth') holding descriptor rows 'rows' until level L; a node that is
  // not split becomes a word.
  void Split(int node, int depth, const std::vector<int>& rows) {
    if (depth >= options.levels || rows.size() <= 1) {
      data.word[node] = NextWord();
      return;
    }
    KMajorityOptions k_options;
    k_options.k = options.branching;
    k_options.max_iterations = options.max_iterations;
    const KMajorityResult clusters = KMajority(all, rows, k_options, rng);
    if (clusters.centers.rows <= 1) {  // all rows identical: nothing to split
      data.word[node] = NextWord();
      return;
    }
    std::vector<std::vector<int>> members(static_cast<std::size_t>(clusters.centers.rows));
    for (std::size_t i = 0; i < rows.size(); ++i)
      members[clusters.assignment[i]].push_back(rows[i]);
    std::vector<int> children;
    for (int c = 0; c < clusters.centers.rows; ++c) {
      children.push_back(AddNode(node, clusters.centers.row(c)));
    }
    for (std::size_t c = 0; c < children.size(); ++c) {
      Split(children[c], depth + 1, members[c]);
      if (depth == 0 && progress) progress(c + 1, children.size() + 1);
    }
  }

  int NextWord() { return next_word++; }
  int next_word = 0;
};

// The IDF weights log(N / n_i) of the leaves of 'vocabulary' (bow_vocabulary.h).
void SetIdfWeights(const std::vector<cv::Mat>& images, const Vocabulary& vocabulary,
                   VocabularyData* data) {
  std::vector<int> images_with_word(static_cast<std::size_t>(vocabulary.words()), 0);
  for (const cv::Mat& image : images) {
    std::set<WordId> seen;
    for (int row = 0; row < image.rows; ++row) seen.insert(vocabulary.Word(image.ptr(row)));
    for (WordId word : seen) ++images_with_word[word];
  }
  const double n = static_cast<double>(images.size());
  for (std::size_t node = 0; node < data->word.size(); ++node) {
    const WordId word = data->word[node];
    if (word < 0) continue;
    data->weight[node] = std::log(n / std::max(1, images_with_word[word]));
  }
}

}  // namespace

Result<Vocabulary> Vocabulary::Train(
    const std::vector<cv::Mat>& images, const VocabularyOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  std::string invalid;
  if (!options.Validate(&invalid)) return Status::Error("vocabulary options: " + invalid);
  cv::Mat all;
  for (std::size_t i = 0; i < images.size(); ++i) {
    if (images[i].empty()) continue;
    if (images[i].type() != CV_8UC1 || images[i].cols != kOrbDescriptorBytes) {
      return Status::Error("training image " + std::to_string(i) + ": descriptors are not " +
                           std::to_string(kOrbDescriptorBytes) + "-byte binary rows");
    }
    all.push_back(images[i]);
  }
  if (all.rows < options.branching) {
    return Status::Error("vocabulary: " + std::to_string(all.rows) +
                         " descriptors are too few to train (need at least k = " +
                         std::to_string(options.branching) + ")");
  }
  TreeBuilder builder{all, options, MakeRng(options.seed, 0), {}, progress};
  builder.data.branching = options.branching;
  builder.data.levels = options.levels;
  builder.data.training_images = static_cast<int>(images.size());
  builder.AddNode(-1, cv::Mat::zeros(1, kOrbDescriptorBytes, CV_8UC1));
  std::vector<int> rows(static_cast<std::size_t>(all.rows));
  for (int i = 0; i < all.rows; ++i) rows[i] = i;
  builder.Split(0, 0, rows);
  Result<Vocabulary> unweighted = FromData(builder.data);
  SEMCHAIN_CHECK(unweighted.ok());
  SetIdfWeights(images, *unweighted, &builder.data);
  if (progress) {  // the IDF pass is the last step
    const auto root_children =
        std::count(builder.data.parent.begin(), builder.data.parent.end(), 0);
    const std::size_t total = static_cast<std::size_t>(root_children) + 1;
    progress(total, total);
  }
  return FromData(std::move(builder.data));
}

}  // namespace semchain::bow
