#include "bow/k_majority.h"

#include <algorithm>
#include <limits>
#include <opencv2/core/hal/hal.hpp>
#include <random>

#include "core/check.h"

namespace semchain::bow {
namespace {

// The centre nearest to descriptor row 'row' (lowest index on a tie) and its distance.
std::pair<int, int> Nearest(const cv::Mat& centers, const unsigned char* row) {
  int best = 0;
  int best_distance = std::numeric_limits<int>::max();
  for (int c = 0; c < centers.rows; ++c) {
    const int d = HammingDistance(centers.ptr<unsigned char>(c), row, centers.cols);
    if (d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  return {best, best_distance};
}

// k-means++ seeding with the squared Hamming distance as the draw weight.
cv::Mat SeedCenters(const cv::Mat& descriptors, const std::vector<int>& rows, int k, Rng& rng) {
  cv::Mat centers;
  std::uniform_int_distribution<std::size_t> first(0, rows.size() - 1);
  centers.push_back(descriptors.row(rows[first(rng)]));
  std::vector<double> weight(rows.size(), std::numeric_limits<double>::max());
  while (centers.rows < k) {
    const cv::Mat last = centers.row(centers.rows - 1);
    double total = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double d = HammingDistance(last.ptr<unsigned char>(0),
                                       descriptors.ptr<unsigned char>(rows[i]), descriptors.cols);
      weight[i] = std::min(weight[i], d * d);
      total += weight[i];
    }
    if (total <= 0.0) break;  // every row equals a centre already: fewer clusters
    std::discrete_distribution<std::size_t> draw(weight.begin(), weight.end());
    centers.push_back(descriptors.row(rows[draw(rng)]));
  }
  return centers;
}

// Drops the clusters no row was assigned to and renumbers the assignment.
void DropEmptyClusters(KMajorityResult* result) {
  std::vector<int> members(static_cast<std::size_t>(result->centers.rows), 0);
  for (int c : result->assignment) ++members[c];
  std::vector<int> renumber(members.size(), -1);
  cv::Mat kept;
  for (std::size_t c = 0; c < members.size(); ++c) {
    if (members[c] == 0) continue;
    renumber[c] = kept.rows;
    kept.push_back(result->centers.row(static_cast<int>(c)));
  }
  for (int& c : result->assignment) c = renumber[c];
  result->centers = kept;
}

}  // namespace

bool KMajorityOptions::Validate(std::string* error) const {
  if (k < 2) {
    *error = "k must be at least 2, got " + std::to_string(k);
    return false;
  }
  if (max_iterations < 1) {
    *error = "max_iterations must be at least 1";
    return false;
  }
  return true;
}

int HammingDistance(const unsigned char* a, const unsigned char* b, int bytes) {
  return cv::hal::normHamming(a, b, bytes);
}

cv::Mat MajorityDescriptor(const cv::Mat& descriptors, const std::vector<int>& rows) {
  SEMCHAIN_CHECK(descriptors.type() == CV_8UC1);
  const int bytes = descriptors.cols;
  std::vector<int> ones(static_cast<std::size_t>(bytes) * 8, 0);
  for (int row : rows) {
    const unsigned char* d = descriptors.ptr<unsigned char>(row);
    for (int byte = 0; byte < bytes; ++byte) {
      for (int bit = 0; bit < 8; ++bit) ones[byte * 8 + bit] += (d[byte] >> (7 - bit)) & 1;
    }
  }
  cv::Mat majority = cv::Mat::zeros(1, bytes, CV_8UC1);
  unsigned char* m = majority.ptr<unsigned char>(0);
  const std::size_t n = rows.size();
  for (int byte = 0; byte < bytes; ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      if (2 * static_cast<std::size_t>(ones[byte * 8 + bit]) > n) {
        m[byte] = static_cast<unsigned char>(m[byte] | (1 << (7 - bit)));
      }
    }
  }
  return majority;
}

KMajorityResult KMajority(const cv::Mat& descriptors, const std::vector<int>& rows,
                          const KMajorityOptions& options, Rng& rng) {
  SEMCHAIN_CHECK(descriptors.type() == CV_8UC1 && !rows.empty());
  KMajorityResult result;
  result.assignment.assign(rows.size(), -1);
  if (rows.size() <= static_cast<std::size_t>(options.k)) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
      result.centers.push_back(descriptors.row(rows[i]));
      result.assignment[i] = Nearest(result.centers, descriptors.ptr<unsigned char>(rows[i])).first;
    }
    DropEmptyClusters(&result);  // identical rows share the first one's cluster
    return result;
  }
  result.centers = SeedCenters(descriptors, rows, options.k, rng);
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    bool moved = false;
    std::vector<std::vector<int>> members(static_cast<std::size_t>(result.centers.rows));
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const int c = Nearest(result.centers, descriptors.ptr<unsigned char>(rows[i])).first;
      moved = moved || c != result.assignment[i];
      result.assignment[i] = c;
      members[c].push_back(rows[i]);
    }
    if (!moved) break;
    for (std::size_t c = 0; c < members.size(); ++c) {
      // An empty cluster keeps its centre; it is dropped at the end if it stays empty.
      if (!members[c].empty()) {
        MajorityDescriptor(descriptors, members[c]).copyTo(result.centers.row(static_cast<int>(c)));
      }
    }
  }
  DropEmptyClusters(&result);
  return result;
}

}  // namespace semchain::bow
