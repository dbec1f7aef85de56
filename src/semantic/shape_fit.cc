#include "semantic/shape_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace semchain::semantic {
namespace {

// Distance from an observed surface point to the outline of a box (centre, yaw, half sizes).
struct BoxOutlineResidual {
  // 'free_space': the point is free space and costs only when inside the box.
  BoxOutlineResidual(const Eigen::Vector2d& p, double w, bool free = false)
      : point(p), weight(w), free_space(free) {}

  template <typename T>
  bool operator()(const T* const pose, const T* const half, T* residual) const {
    using std::abs;
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T dx = T(point.x()) - pose[0];
    const T dy = T(point.y()) - pose[1];
    const T c = cos(pose[2]);
    const T s = sin(pose[2]);
    const T u = abs(c * dx + s * dy) - half[0];  // along the width axis
    const T v = abs(-s * dx + c * dy) - half[1];
    T distance;
    if (u > T(0) && v > T(0)) {
      distance = sqrt(u * u + v * v + T(1e-12));
    } else {
      distance = u > v ? u : v;  // outside one slab, or inside (negative)
    }
    if (free_space) distance = distance < T(0) ? -distance : T(0);
    residual[0] = T(weight) * distance;
    return true;
  }

  Eigen::Vector2d point;
  double weight;
  bool free_space;
};

struct CircleOutlineResidual {
  CircleOutlineResidual(const Eigen::Vector2d& p, double w, bool free = false)
      : point(p), weight(w), free_space(free) {}

  template <typename T>
  bool operator()(const T* const center, const T* const radius, T* residual) const {
    using std::sqrt;
    const T dx = T(point.x()) - center[0];
    const T dy = T(point.y()) - center[1];
    T distance = sqrt(dx * dx + dy * dy + T(1e-12)) - radius[0];
    if (free_space) distance = distance < T(0) ? -distance : T(0);
    residual[0] = T(weight) * distance;
    return true;
  }

  Eigen::Vector2d point;
  double weight;
  bool free_space;
};

// Holds a size near its prior value.
struct SizePriorResidual {
  SizePriorResidual(double v, double s) : value(v), stddev(s) {}
  template <typename T>
  bool operator()(const T* const size, T* residual) const {
    residual[0] = (size[0] - T(value)) / T(stddev);
    return true;
  }
  double value;
  double stddev;
};

// Holds a box's half sizes near the prior's.
struct HalfSizePriorResidual {
  HalfSizePriorResidual(const Eigen::Vector2d& v, const Eigen::Vector2d& s) : value(v), stddev(s) {}
  template <typename T>
  bool operator()(const T* const half, T* residual) const {
    residual[0] = (half[0] - T(value.x())) / T(stddev.x());
    residual[1] = (half[1] - T(value.y())) / T(stddev.y());
    return true;
  }
  Eigen::Vector2d value;
  Eigen::Vector2d stddev;
};

ceres::Solver::Options SolverOptions() {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 50;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  return options;
}

// Observation residuals are scaled so that their total weight is the number of points divided
// by (cell size / 2)², i.e. each point carries the information of a measurement good to half a
// cell; the priors then only matter where the points leave a size undetermined.
constexpr double kPointStd = 0.025;

std::vector<double> NormalisedWeights(const std::vector<double>& weights) {
  double total = 0.0;
  for (double w : weights) total += w;
  std::vector<double> out(weights.size(), 1.0 / kPointStd);
  if (total <= 0.0) return out;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    out[i] = std::sqrt(weights[i] * static_cast<double>(weights.size()) / total) / kPointStd;
  }
  return out;
}

Eigen::Vector2d Centroid(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

// The unit normal of a face running along 'along', turned towards 'view_direction' (the camera).
Eigen::Vector2d NormalTowards(const Eigen::Vector2d& along, const Eigen::Vector2d& view_direction) {
  const Eigen::Vector2d normal(-along.y(), along.x());
  return normal.dot(view_direction) < 0.0 ? Eigen::Vector2d(-normal) : normal;
}

// How the points lie as a face along 'along', seen from where 'normal' points.
struct FaceSpan {
  double low = 0.0, high = 0.0;  // extent along the face
  // Along the normal (larger is nearer the camera): the face is where most points are (the
  // median); the spread behind it is read robustly (the 5th percentile) so that a few noisy
  // cells do not look like a side.
  double nearest = 0.0, farthest = 0.0;
};

FaceSpan SpanOf(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& along,
                const Eigen::Vector2d& normal) {
  FaceSpan span{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  std::vector<double> offsets;
  for (const Eigen::Vector2d& p : points) {
    span.low = std::min(span.low, p.dot(along));
    span.high = std::max(span.high, p.dot(along));
    offsets.push_back(p.dot(normal));
  }
  std::sort(offsets.begin(), offsets.end());
  span.nearest = offsets[offsets.size() / 2];
  span.farthest = offsets[static_cast<std::size_t>(0.05 * double(offsets.size() - 1))];
  return span;
}

// A wall that a face lies on runs on parallel to the face's line from beyond one of its ends:
// occupied cells within 'kWallHalfWidth' of one line, between the face's farthest points and
// its median widened by 'kWallBand' (the wall is where the farthest points are, a chair's back a
// little in front of it), for at least 'kWallRun' with no gap wider than 'kWallGap' (metres).
// An object's own face ends within a cell or two of its observed points (the detections' boxes
// were trimmed), and a wall met at an angle crosses the band within a short run.
constexpr double kWallBand = 0.075;
constexpr double kWallHalfWidth = 0.035;
constexpr double kWallRun = 0.5;
constexpr double kWallGap = 0.1;
static_assert(kWallRun + kWallGap <= kFaceWallReach);

// Whether the face 'span' (along 'along', its normal 'normal' towards the camera) lies on a wall
// of the laser map.
bool FaceOnWall(const FaceSpan& span, const Eigen::Vector2d& along, const Eigen::Vector2d& normal,
                const std::vector<Eigen::Vector2d>& occupied_points) {
  for (const double side : {-1.0, 1.0}) {
    const double end = side > 0.0 ? span.high : span.low;
    std::vector<Eigen::Vector2d> beyond;  // (distance beyond the end, offset along the normal)
    for (const Eigen::Vector2d& cell : occupied_points) {
      const double t = side * (cell.dot(along) - end);
      const double offset = cell.dot(normal);
      if (t > 0.0 && t <= kFaceWallReach && offset >= span.farthest - kWallBand &&
          offset <= span.nearest + kWallBand) {
        beyond.emplace_back(t, offset);
      }
    }
    std::sort(beyond.begin(), beyond.end(),
              [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() < b.x(); });
    for (const Eigen::Vector2d& line : beyond) {
      double reached = 0.0;
      for (const Eigen::Vector2d& cell : beyond) {
        if (std::abs(cell.y() - line.y()) > kWallHalfWidth) continue;
        if (cell.x() - reached > kWallGap) break;
        reached = cell.x();
      }
      if (reached >= kWallRun) return true;
    }
  }
  return false;
}

// The direction of the largest spread of 'points' (unit).
Eigen::Vector2d MajorAxis(const std::vector<Eigen::Vector2d>& points) {
  const Eigen::Vector2d centroid = Centroid(points);
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvectors().col(1);
}

FittedShape FitCircle(const std::vector<Eigen::Vector2d>& points,
                      const std::vector<double>& weights, const Eigen::Vector2d& view_direction,
                      const ClassShapePrior& prior, const std::vector<Eigen::Vector2d>& free_points,
                      const std::vector<Eigen::Vector2d>& occupied_points) {
  double center[2];
  double radius = prior.radius;
  // The wall a seen arc touches runs across the view or, seen at an angle, along the points
  // (what the camera took for the object reaches along the wall); in front of it is away from it.
  bool on_wall = false;
  Eigen::Vector2d out_of_wall = view_direction;
  if (!view_direction.isZero()) {
    for (const Eigen::Vector2d& across :
         {Eigen::Vector2d(-view_direction.y(), view_direction.x()), MajorAxis(points)}) {
      const Eigen::Vector2d normal = NormalTowards(across, view_direction);
      if (FaceOnWall(SpanOf(points, across, normal), across, normal, occupied_points)) {
        on_wall = true;
        out_of_wall = normal;
        break;
      }
    }
  }
  const Eigen::Vector2d start =
      Centroid(points) + (on_wall ? Eigen::Vector2d(out_of_wall * prior.radius)
                                  : Eigen::Vector2d(-0.5 * prior.radius * view_direction));
  center[0] = start.x();
  center[1] = start.y();
  ceres::Problem problem;
  for (std::size_t i = 0; i < points.size(); ++i) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<CircleOutlineResidual, 1, 2, 1>(
                                 new CircleOutlineResidual(points[i], weights[i])),
                             new ceres::HuberLoss(2.0), center, &radius);
  }
  for (const Eigen::Vector2d& p : on_wall ? std::vector<Eigen::Vector2d>() : free_points) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<CircleOutlineResidual, 1, 2, 1>(
                                 new CircleOutlineResidual(p, 1.0 / kPointStd, true)),
                             new ceres::HuberLoss(2.0), center, &radius);
  }
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SizePriorResidual, 1, 1>(
                               new SizePriorResidual(prior.radius, prior.size_std)),
                           nullptr, &radius);
  problem.SetParameterLowerBound(&radius, 0, 0.2 * prior.radius);
  ceres::Solver::Summary summary;
  ceres::Solve(SolverOptions(), &problem, &summary);

  FittedShape shape;
  shape.center = Eigen::Vector2d(center[0], center[1]);
  shape.radius = radius;
  constexpr int kSides = 16;
  for (int i = 0; i < kSides; ++i) {
    const double a = 2.0 * M_PI * i / kSides;
    shape.footprint.push_back(shape.center + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    const double r = (p - shape.center).norm() - radius;
    sum += r * r;
  }
  shape.rms_residual = std::sqrt(sum / static_cast<double>(points.size()));
  return shape;
}

struct BoxCandidate {
  double pose[3] = {0.0, 0.0, 0.0};
  double half[2] = {0.0, 0.0};
  double cost = 0.0;
};

// The width seen is held only loosely: the outline residuals and free space decide it.
constexpr double kFaceWidthStd = 0.1;
// Points spread this far (metres) behind the nearest show a side of the object.
constexpr double kSideSeenDepth = 0.25;

BoxCandidate SolveBox(const std::vector<Eigen::Vector2d>& points,
                      const std::vector<double>& weights,
                      const std::vector<Eigen::Vector2d>& free_points, const Eigen::Vector2d& start,
                      double yaw, const Eigen::Vector2d& half_prior,
                      const Eigen::Vector2d& half_std) {
  BoxCandidate box;
  box.pose[0] = start.x();
  box.pose[1] = start.y();
  box.pose[2] = yaw;
  box.half[0] = std::max(half_prior.x(), 0.02);
  box.half[1] = std::max(half_prior.y(), 0.02);
  ceres::Problem problem;
  for (std::size_t i = 0; i < points.size(); ++i) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BoxOutlineResidual, 1, 3, 2>(
                                 new BoxOutlineResidual(points[i], weights[i])),
                             new ceres::HuberLoss(2.0), box.pose, box.half);
  }
  for (const Eigen::Vector2d& p : free_points) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BoxOutlineResidual, 1, 3, 2>(
                                 new BoxOutlineResidual(p, 1.0 / kPointStd, true)),
                             new ceres::HuberLoss(2.0), box.pose, box.half);
  }
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<HalfSizePriorResidual, 2, 2>(
                               new HalfSizePriorResidual(half_prior, half_std)),
                           nullptr, box.half);
  problem.SetParameterLowerBound(box.half, 0, 0.01);
  problem.SetParameterLowerBound(box.half, 1, 0.01);
  ceres::Solver::Summary summary;
  ceres::Solve(SolverOptions(), &problem, &summary);
  box.cost = summary.final_cost;
  return box;
}

FittedShape FitBox(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& weights,
                   const Eigen::Vector2d& view_direction, const ClassShapePrior& prior,
                   const std::vector<Eigen::Vector2d>& free_points,
                   const std::vector<Eigen::Vector2d>& occupied_points) {
  const Eigen::Vector2d major = MajorAxis(points);
  // Sizes and start of a box of orientation 'yaw' from the points, and its fit.
  const auto solve = [&](double yaw) {
    const Eigen::Vector2d along(std::cos(yaw), std::sin(yaw));
    const Eigen::Vector2d normal = NormalTowards(along, view_direction);
    const FaceSpan span = SpanOf(points, along, normal);
    const double face = span.high - span.low;
    // A side seen (points reaching well back from the face) shows the depth. Otherwise what
    // lies behind the face is unseen: furniture is seldom deeper than it is wide, so the
    // class's depth is taken, but no more than the face is wide (this bounds the error when a
    // world's objects are smaller than the class prior).
    const double seen_depth = span.nearest - span.farthest;
    const bool side_seen = seen_depth > kSideSeenDepth;
    const double hidden = side_seen                 ? seen_depth
                          : view_direction.isZero() ? prior.depth
                                                    : std::min(prior.depth, face);
    // A thin object (a door in its frame, a clock) is in or on the wall either way.
    const bool on_wall = !view_direction.isZero() && !side_seen && hidden > kWallBand &&
                         FaceOnWall(span, along, normal, occupied_points);
    const Eigen::Vector2d start = 0.5 * (span.low + span.high) * along +
                                  (span.nearest + (on_wall ? 0.5 : -0.5) * hidden) * normal;
    return SolveBox(points, weights, on_wall ? std::vector<Eigen::Vector2d>() : free_points, start,
                    yaw, {0.5 * face, 0.5 * hidden},
                    {kFaceWidthStd, side_seen ? 0.5 * kFaceWidthStd : 0.5 * prior.size_std});
  };
  // Candidate orientations of the face: across the viewing direction, and along the points'
  // major axis (they differ when two faces were seen); the better fit is kept. (Refitting a
  // box that turned far from its start, as an L of two faces seen diagonally does, made the
  // simulated worlds' centres worse: 0.036 → 0.041 m mean, so it is not done.)
  // The view's candidate goes first and wins ties.
  std::vector<double> yaws;
  if (!view_direction.isZero()) {
    yaws.push_back(std::atan2(view_direction.y(), view_direction.x()) - M_PI / 2);
  }
  yaws.push_back(std::atan2(major.y(), major.x()));
  BoxCandidate best;
  bool have_best = false;
  for (const double yaw : yaws) {
    const BoxCandidate candidate = solve(yaw);
    if (!have_best || candidate.cost < 0.99 * best.cost - 1e-6) {
      best = candidate;
      have_best = true;
    }
  }

  FittedShape shape;
  shape.center = Eigen::Vector2d(best.pose[0], best.pose[1]);
  shape.yaw = best.pose[2];
  shape.width = 2.0 * best.half[0];
  shape.depth = 2.0 * best.half[1];
  const Eigen::Vector2d ax(std::cos(shape.yaw), std::sin(shape.yaw));
  const Eigen::Vector2d ay(-ax.y(), ax.x());
  for (const auto& [su, sv] :
       {std::pair{1, 1}, std::pair{-1, 1}, std::pair{-1, -1}, std::pair{1, -1}}) {
    shape.footprint.push_back(shape.center + su * best.half[0] * ax + sv * best.half[1] * ay);
  }
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    BoxOutlineResidual residual(p, 1.0);
    double r = 0.0;
    residual(best.pose, best.half, &r);
    sum += r * r;
  }
  shape.rms_residual = std::sqrt(sum / static_cast<double>(points.size()));
  return shape;
}

}  // namespace

FittedShape FitShape(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& weights,
                     const Eigen::Vector2d& view_direction, const ClassShapePrior& prior,
                     const std::vector<Eigen::Vector2d>& free_points,
                     const std::vector<Eigen::Vector2d>& occupied_points) {
  if (points.empty()) return {};
  const std::vector<double> scaled = NormalisedWeights(weights);
  return prior.shape == ClassShapePrior::Shape::kCircle
             ? FitCircle(points, scaled, view_direction, prior, free_points, occupied_points)
             : FitBox(points, scaled, view_direction, prior, free_points, occupied_points);
}

double ShapeExtent(const FittedShape& shape) {
  return shape.radius > 0.0 ? 2.0 * shape.radius : std::max(shape.width, shape.depth);
}

}  // namespace semchain::semantic
