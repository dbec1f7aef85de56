#include "localization/particle_clusters.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "core/angles.h"
#include "core/check.h"
#include "localization/key_index.h"

namespace semchain::localization {
namespace {

// A bin (x, y, heading) packed into 21 bits each, offset so that the keys sort as the bins do
// lexicographically: the clusters are flood-filled from seeds in that order (as they were from
// an ordered map), so their sums, and the estimate, do not depend on the container.
constexpr std::int64_t kFieldOffset = std::int64_t{1} << 20;
constexpr std::uint64_t kFieldMask = (std::uint64_t{1} << 21) - 1;

std::uint64_t PackBin(std::int64_t x, std::int64_t y, std::int64_t heading) {
  return (static_cast<std::uint64_t>(x + kFieldOffset) << 42) |
         (static_cast<std::uint64_t>(y + kFieldOffset) << 21) |
         static_cast<std::uint64_t>(heading + kFieldOffset);
}
std::int64_t FieldOf(std::uint64_t key, int shift) {
  return static_cast<std::int64_t>((key >> shift) & kFieldMask) - kFieldOffset;
}

struct Accumulator {
  double weight = 0.0, x = 0.0, y = 0.0, xx = 0.0, xy = 0.0, yy = 0.0, c = 0.0, s = 0.0;
  int count = 0;
  void Add(const Particle& p) {
    const double w = p.weight;
    weight += w;
    x += w * p.pose.x;
    y += w * p.pose.y;
    xx += w * p.pose.x * p.pose.x;
    xy += w * p.pose.x * p.pose.y;
    yy += w * p.pose.y * p.pose.y;
    c += w * std::cos(p.pose.theta);
    s += w * std::sin(p.pose.theta);
    ++count;
  }
  PoseCluster Finish() const {
    PoseCluster cluster;
    cluster.weight = weight;
    cluster.count = count;
    if (!(weight > 0.0)) return cluster;
    const double mx = x / weight, my = y / weight;
    cluster.mean = Pose2(mx, my, std::atan2(s, c));
    cluster.covariance(0, 0) = std::max(0.0, xx / weight - mx * mx);
    cluster.covariance(1, 1) = std::max(0.0, yy / weight - my * my);
    cluster.covariance(0, 1) = cluster.covariance(1, 0) = xy / weight - mx * my;
    const double r = std::min(1.0, std::hypot(c, s) / weight);
    cluster.covariance(2, 2) = r > 0.0 ? -2.0 * std::log(r) : 1e9;
    return cluster;
  }
};

// The occupied bins in key order, each with its particles in index order.
struct SortedBins {
  std::vector<std::uint64_t> keys;
  std::vector<int> first;  // bin b holds order[first[b] .. first[b + 1])
  std::vector<int> order;  // particle indices grouped by bin
  KeyIndex index;          // key → bin
};

SortedBins BinParticles(const std::vector<Particle>& particles, const Eigen::Vector3d& bin_size,
                        int heading_bins) {
  // Bins numbered as first met (one hash look-up per particle), then only the distinct keys
  // sorted: a converged cloud has far fewer bins than particles.
  KeyIndex met;
  met.Clear(particles.size());
  std::vector<std::uint64_t> met_keys;
  std::vector<int> bin_of(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Pose2& p = particles[i].pose;
    const int heading = std::clamp(static_cast<int>(std::floor((p.theta + kPi) / bin_size.z())), 0,
                                   heading_bins - 1);
    const auto x = static_cast<std::int64_t>(std::floor(p.x / bin_size.x()));
    const auto y = static_cast<std::int64_t>(std::floor(p.y / bin_size.y()));
    SEMCHAIN_CHECK(std::abs(x) < kFieldOffset && std::abs(y) < kFieldOffset);
    const std::uint64_t key = PackBin(x, y, heading);
    const auto [bin, added] = met.Insert(key);
    if (added) met_keys.push_back(key);
    bin_of[i] = bin;
  }
  std::vector<int> sorted(met_keys.size());
  for (std::size_t b = 0; b < sorted.size(); ++b) sorted[b] = static_cast<int>(b);
  std::sort(sorted.begin(), sorted.end(), [&](int a, int b) { return met_keys[a] < met_keys[b]; });
  std::vector<int> rank(sorted.size());
  SortedBins bins;
  bins.index.Clear(sorted.size());
  bins.first.assign(sorted.size() + 1, 0);
  for (std::size_t r = 0; r < sorted.size(); ++r) {
    rank[sorted[r]] = static_cast<int>(r);
    bins.keys.push_back(met_keys[sorted[r]]);
    bins.index.Insert(met_keys[sorted[r]]);
  }
  // Counting sort of the particles by bin rank, stable: each bin lists its particles in order.
  for (const int bin : bin_of) ++bins.first[rank[bin] + 1];
  for (std::size_t r = 1; r < bins.first.size(); ++r) bins.first[r] += bins.first[r - 1];
  bins.order.resize(particles.size());
  std::vector<int> next(bins.first.begin(), bins.first.end() - 1);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    bins.order[next[rank[bin_of[i]]]++] = static_cast<int>(i);
  }
  return bins;
}

}  // namespace

std::vector<PoseCluster> ClusterParticles(const std::vector<Particle>& particles,
                                          const Eigen::Vector3d& bin_size) {
  // Flood fill over touching bins. Headings are binned from −π so that the bins tile the
  // circle, and the last heading bin touches the first: nav2 never wraps a particle's heading,
  // so a cloud it tracks keeps one winding and is not cut at ±π.
  const int heading_bins =
      std::max(1, static_cast<int>(std::ceil(2.0 * kPi / bin_size.z() - 1e-9)));
  const SortedBins bins = BinParticles(particles, bin_size, heading_bins);
  const int count = static_cast<int>(bins.keys.size());
  std::vector<char> visited(static_cast<std::size_t>(count), 0);
  std::vector<PoseCluster> clusters;
  std::vector<int> stack;
  for (int seed = 0; seed < count; ++seed) {
    if (visited[seed]) continue;
    Accumulator accumulator;
    stack.assign(1, seed);
    visited[seed] = 1;
    while (!stack.empty()) {
      const int bin = stack.back();
      stack.pop_back();
      for (int k = bins.first[bin]; k < bins.first[bin + 1]; ++k) {
        accumulator.Add(particles[static_cast<std::size_t>(bins.order[k])]);
      }
      const std::uint64_t key = bins.keys[bin];
      const std::int64_t x = FieldOf(key, 42), y = FieldOf(key, 21), heading = FieldOf(key, 0);
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dt = -1; dt <= 1; ++dt) {
            const int next = bins.index.Find(
                PackBin(x + dx, y + dy, (heading + dt + heading_bins) % heading_bins));
            if (next < 0 || visited[next]) continue;
            visited[next] = 1;
            stack.push_back(next);
          }
        }
      }
    }
    clusters.push_back(accumulator.Finish());
  }
  std::sort(clusters.begin(), clusters.end(),
            [](const PoseCluster& a, const PoseCluster& b) { return a.weight > b.weight; });
  return clusters;
}

}  // namespace semchain::localization
