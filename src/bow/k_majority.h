#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/rng.h"

// k-majority clustering of binary descriptors (Grana et al. 2013; the k-means step of DBoW2's
// hierarchical vocabulary, seed 000 §3.1 step 1): k-means with the Hamming distance, where a
// cluster's centre is the bitwise majority of its members (the median in Hamming space).
namespace semchain::bow {

struct KMajorityOptions {
  int k = 10;               // clusters wanted (fewer when there are fewer distinct rows)
  int max_iterations = 20;  // assignment rounds; the loop stops earlier when nothing moves
  bool Validate(std::string* error) const;
};

struct KMajorityResult {
  cv::Mat centers;              // CV_8UC1, one descriptor per row, no empty cluster
  std::vector<int> assignment;  // per input row: its centre's row in 'centers'
};

// The Hamming distance between two descriptors of 'bytes' bytes.
int HammingDistance(const unsigned char* a, const unsigned char* b, int bytes);

// The bitwise majority of the rows 'rows' of 'descriptors' (CV_8UC1): a bit is set when more
// than half of the rows set it (a tie leaves it clear). One row of the descriptor width.
cv::Mat MajorityDescriptor(const cv::Mat& descriptors, const std::vector<int>& rows);

// Clusters the rows 'rows' of 'descriptors' (CV_8UC1) into at most options.k clusters. The
// first centre is a uniformly drawn row and each further one a row drawn with probability
// proportional to its squared distance to the nearest centre so far (k-means++, seeded by
// 'rng'); then rows go to their nearest centre (the lowest index on a tie) and centres become
// their members' majority until no row moves. With at most k rows each row is its own cluster.
KMajorityResult KMajority(const cv::Mat& descriptors, const std::vector<int>& rows,
                          const KMajorityOptions& options, Rng& rng);

}  // namespace semchain::bow
