#include "localization/particle_clusters.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/angles.h"

namespace semchain::localization {
namespace {

using Bin = Eigen::Vector3i;
struct BinLess {
  bool operator()(const Bin& a, const Bin& b) const {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  }
};

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

}  // namespace

std::vector<PoseCluster> ClusterParticles(const std::vector<Particle>& particles,
                                          const Eigen::Vector3d& bin_size) {
  // Bin → list of particle indices, then flood fill over touching bins. Headings are binned from
  // −π so that the bins tile the circle, and the last heading bin touches the first: nav2 never
  // wraps a particle's heading, so a cloud it tracks keeps one winding and is not cut at ±π.
  const int heading_bins =
      std::max(1, static_cast<int>(std::ceil(2.0 * kPi / bin_size.z() - 1e-9)));
  std::map<Bin, std::vector<int>, BinLess> bins;
  for (int i = 0; i < static_cast<int>(particles.size()); ++i) {
    const Pose2& p = particles[static_cast<std::size_t>(i)].pose;
    const int heading = std::clamp(static_cast<int>(std::floor((p.theta + kPi) / bin_size.z())), 0,
                                   heading_bins - 1);
    const Bin bin(static_cast<int>(std::floor(p.x / bin_size.x())),
                  static_cast<int>(std::floor(p.y / bin_size.y())), heading);
    bins[bin].push_back(i);
  }
  std::map<Bin, bool, BinLess> visited;
  std::vector<PoseCluster> clusters;
  for (const auto& [seed, unused] : bins) {
    if (visited[seed]) continue;
    Accumulator accumulator;
    std::vector<Bin> stack = {seed};
    visited[seed] = true;
    while (!stack.empty()) {
      const Bin bin = stack.back();
      stack.pop_back();
      for (const int i : bins.at(bin)) accumulator.Add(particles[static_cast<std::size_t>(i)]);
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dt = -1; dt <= 1; ++dt) {
            const Bin next(bin.x() + dx, bin.y() + dy,
                           (bin.z() + dt + heading_bins) % heading_bins);
            if (bins.count(next) == 0 || visited[next]) continue;
            visited[next] = true;
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
