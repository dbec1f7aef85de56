#include "eval/closure_reference.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <utility>

#include "core/angles.h"
#include "core/check.h"

namespace semchain::eval {
namespace {

// The log's scans: which one a timestamp belongs to, and the odometry's travel between two.
class ScanIndex {
 public:
  explicit ScanIndex(ScanTrack scans) : scans_(std::move(scans)) {
    SEMCHAIN_CHECK(scans_.timestamps.size() == scans_.odometry.size());
    for (std::size_t i = 0; i < scans_.timestamps.size(); ++i) {
      by_time_.emplace_back(scans_.timestamps[i], static_cast<int>(i));
      if (i == 0) {
        travel_.push_back(0.0);
        turn_.push_back(0.0);
        continue;
      }
      const Pose2 step = scans_.odometry[i - 1].Between(scans_.odometry[i]);
      travel_.push_back(travel_.back() + step.translation().norm());
      turn_.push_back(turn_.back() + std::abs(NormalizeAngle(step.theta)));
    }
    std::sort(by_time_.begin(), by_time_.end());
  }

  // The scan stamped nearest to 't', when within 'tolerance'.
  std::optional<int> At(double t, double tolerance) const {
    const auto it = std::lower_bound(by_time_.begin(), by_time_.end(),
                                     std::make_pair(t, std::numeric_limits<int>::min()));
    std::optional<int> best;
    double best_gap = tolerance;
    if (it != by_time_.end() && it->first - t <= best_gap) {
      best_gap = it->first - t;
      best = it->second;
    }
    if (it != by_time_.begin() && t - std::prev(it)->first <= best_gap) {
      best = std::prev(it)->second;
    }
    return best;
  }

  double Travel(int a, int b) const {
    return std::abs(travel_[static_cast<std::size_t>(b)] - travel_[static_cast<std::size_t>(a)]);
  }
  double Turn(int a, int b) const {
    return std::abs(turn_[static_cast<std::size_t>(b)] - turn_[static_cast<std::size_t>(a)]);
  }
  // Whether the odometry may bridge scans 'a' and 'b' under 'options'.
  bool Bridges(int a, int b, const ClosureReferenceOptions& options) const {
    return Travel(a, b) <= options.max_bridge_meters && Turn(a, b) <= options.max_bridge_radians;
  }
  // Scan 'to' in the frame of scan 'from' by the odometry.
  Pose2 Odometry(int from, int to) const {
    return scans_.odometry[static_cast<std::size_t>(from)].Between(
        scans_.odometry[static_cast<std::size_t>(to)]);
  }
  int size() const { return static_cast<int>(scans_.timestamps.size()); }
  bool Valid(int i) const { return i >= 0 && i < size(); }

 private:
  ScanTrack scans_;
  std::vector<std::pair<double, int>> by_time_;
  std::vector<double> travel_;
  std::vector<double> turn_;
};

// The anchored scans just before and after 'i' (sorted 'anchors'), -1 where none.
std::pair<int, int> Neighbours(const std::vector<int>& anchors, int i) {
  const auto it = std::lower_bound(anchors.begin(), anchors.end(), i);
  return {it == anchors.begin() ? -1 : *std::prev(it), it == anchors.end() ? -1 : *it};
}

class IndexedReference : public ClosureReference {
 public:
  explicit IndexedReference(std::vector<Pose2> poses) : poses_(std::move(poses)) {}
  std::optional<Pose2> Relative(int from, int to) const override {
    const auto n = static_cast<int>(poses_.size());
    if (from < 0 || to < 0 || from >= n || to >= n) return std::nullopt;
    return poses_[static_cast<std::size_t>(from)].Between(poses_[static_cast<std::size_t>(to)]);
  }

 private:
  std::vector<Pose2> poses_;
};

class TimedReference : public ClosureReference {
 public:
  TimedReference(const std::vector<StampedPose>& reference, ScanTrack scans,
                 const ClosureReferenceOptions& options)
      : scans_(std::move(scans)), options_(options) {
    for (const StampedPose& pose : reference) {
      const std::optional<int> scan = scans_.At(pose.timestamp, options_.timestamp_tolerance_s);
      if (scan && poses_.emplace(*scan, pose.pose).second) anchors_.push_back(*scan);
    }
    std::sort(anchors_.begin(), anchors_.end());
  }

  std::optional<Pose2> Relative(int from, int to) const override {
    const std::optional<Pose2> a = PoseOf(from);
    const std::optional<Pose2> b = PoseOf(to);
    if (!a || !b) return std::nullopt;
    return a->Between(*b);
  }

 private:
  std::optional<Pose2> PoseOf(int scan) const {
    if (!scans_.Valid(scan)) return std::nullopt;
    if (const auto it = poses_.find(scan); it != poses_.end()) return it->second;
    const auto [before, after] = Neighbours(anchors_, scan);
    int nearest = -1;
    for (const int anchor : {before, after}) {
      if (anchor < 0 || !scans_.Bridges(anchor, scan, options_)) continue;
      if (nearest < 0 || scans_.Travel(anchor, scan) < scans_.Travel(nearest, scan)) {
        nearest = anchor;
      }
    }
    if (nearest < 0) return std::nullopt;
    return poses_.at(nearest) * scans_.Odometry(nearest, scan);
  }

  ScanIndex scans_;
  ClosureReferenceOptions options_;
  std::map<int, Pose2> poses_;
  std::vector<int> anchors_;
};

class RelationReference : public ClosureReference {
 public:
  RelationReference(const std::vector<Relation>& relations, ScanTrack scans,
                    const ClosureReferenceOptions& options)
      : scans_(std::move(scans)), options_(options) {
    for (const Relation& relation : relations) {
      const std::optional<int> a = scans_.At(relation.t1, options_.timestamp_tolerance_s);
      const std::optional<int> b = scans_.At(relation.t2, options_.timestamp_tolerance_s);
      if (!a || !b || *a == *b) continue;
      Link(*a, *b, relation.delta, options_.relation_sigma_meters);
    }
    for (const auto& [scan, edges] : graph_) anchors_.push_back(scan);
    // Bridges between scans next to each other among those with a relation.
    for (std::size_t k = 0; k + 1 < anchors_.size(); ++k) {
      const int a = anchors_[k], b = anchors_[k + 1];
      if (const std::optional<double> cost = BridgeCost(a, b)) {
        Link(a, b, scans_.Odometry(a, b), *cost);
      }
    }
  }

  // Dijkstra from 'from' over relations and bridges, by estimated error, within the budget.
  std::optional<Pose2> Relative(int from, int to) const override {
    if (!scans_.Valid(from) || !scans_.Valid(to)) return std::nullopt;
    if (from == to) return Pose2();
    // The entries into the graph from 'from' and its exits towards 'to' (the scans themselves
    // when they have a relation, else bridges to their neighbours).
    std::map<int, Edge> exits;  // keyed by the graph scan, the edge to 'to'
    for (const int anchor : Ends(to)) {
      const double cost = anchor == to ? 0.0 : *BridgeCost(anchor, to);
      exits[anchor] = {to, scans_.Odometry(anchor, to), cost};
    }
    if (exits.empty()) return std::nullopt;
    using Entry = std::pair<double, int>;  // cost so far, scan
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    std::map<int, std::pair<double, Pose2>> reached;  // scan: cost, pose in the frame of 'from'
    const auto relax = [&](int scan, double cost, const Pose2& pose) {
      if (cost > options_.max_path_error_meters) return;
      const auto it = reached.find(scan);
      if (it != reached.end() && it->second.first <= cost) return;
      reached[scan] = {cost, pose};
      queue.emplace(cost, scan);
    };
    for (const int anchor : Ends(from)) {
      relax(anchor, anchor == from ? 0.0 : *BridgeCost(from, anchor),
            scans_.Odometry(from, anchor));
    }
    const int target = -1;  // 'to' itself, reached through an exit
    while (!queue.empty()) {
      const auto [cost, scan] = queue.top();
      queue.pop();
      const auto& [best, pose] = reached.at(scan);
      if (cost > best) continue;
      if (scan == target) return pose;
      if (const auto exit = exits.find(scan); exit != exits.end()) {
        relax(target, cost + exit->second.cost, pose * exit->second.relative);
      }
      for (const Edge& edge : graph_.at(scan)) {
        relax(edge.to, cost + edge.cost, pose * edge.relative);
      }
    }
    return std::nullopt;
  }

 private:
  struct Edge {
    int to = 0;
    Pose2 relative;  // 'to' in the frame of the edge's scan
    double cost = 0.0;
  };

  void Link(int a, int b, const Pose2& b_in_a, double cost) {
    graph_[a].push_back({b, b_in_a, cost});
    graph_[b].push_back({a, b_in_a.Inverse(), cost});
  }

  std::optional<double> BridgeCost(int a, int b) const {
    if (!scans_.Bridges(a, b, options_)) return std::nullopt;
    return options_.bridge_sigma_meters + options_.bridge_sigma_per_meter * scans_.Travel(a, b);
  }

  // 'scan' itself when it has a relation, else its neighbours among those that do, within a
  // bridge.
  std::vector<int> Ends(int scan) const {
    if (graph_.count(scan)) return {scan};
    std::vector<int> ends;
    const auto [before, after] = Neighbours(anchors_, scan);
    for (const int anchor : {before, after}) {
      if (anchor >= 0 && BridgeCost(anchor, scan)) ends.push_back(anchor);
    }
    return ends;
  }

  ScanIndex scans_;
  ClosureReferenceOptions options_;
  std::map<int, std::vector<Edge>> graph_;
  std::vector<int> anchors_;
};

}  // namespace

std::unique_ptr<ClosureReference> MakeIndexedReference(std::vector<Pose2> poses) {
  return std::make_unique<IndexedReference>(std::move(poses));
}

std::unique_ptr<ClosureReference> MakeTimedReference(const std::vector<StampedPose>& reference,
                                                     ScanTrack scans,
                                                     const ClosureReferenceOptions& options) {
  return std::make_unique<TimedReference>(reference, std::move(scans), options);
}

std::unique_ptr<ClosureReference> MakeRelationReference(const std::vector<Relation>& relations,
                                                        ScanTrack scans,
                                                        const ClosureReferenceOptions& options) {
  return std::make_unique<RelationReference>(relations, std::move(scans), options);
}

}  // namespace semchain::eval
