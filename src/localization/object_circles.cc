#include "localization/object_circles.h"

#include <cmath>
#include <vector>

namespace semchain::localization {

Eigen::Vector2d UnitDirection(const Eigen::Vector2d& v) {
  const double n = v.norm();
  return n > 1e-12 ? Eigen::Vector2d(v / n) : Eigen::Vector2d(1.0, 0.0);
}

double MeanCenterBehindSurface(const semantic::SemanticObject& object) {
  double sum = 0.0;
  constexpr int kDirections = 8;
  for (int k = 0; k < kDirections; ++k) {
    const double a = 2.0 * M_PI * k / kDirections;
    sum += CenterBehindSurface(object, Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return sum / kDirections;
}

Eigen::Vector2d HeadingFrom(const Eigen::Vector2d& at, const Eigen::Vector2d& centre,
                            const Eigen::Vector2d& seen) {
  const Eigen::Vector2d world = UnitDirection(centre - at);
  const Eigen::Vector2d robot = UnitDirection(seen);
  return {world.dot(robot), robot.x() * world.y() - robot.y() * world.x()};
}

int IntersectCircles(const Eigen::Vector2d& c0, double r0, const Eigen::Vector2d& c1, double r1,
                     double slack, Eigen::Vector2d out[2]) {
  const Eigen::Vector2d delta = c1 - c0;
  const double d = delta.norm();
  if (d < 1e-9) return 0;  // concentric: no point, or a whole circle
  const Eigen::Vector2d u = delta / d;
  if (d > r0 + r1) {  // apart
    if (d - (r0 + r1) > slack) return 0;
    out[0] = c0 + u * (r0 + 0.5 * (d - r0 - r1));
    return 1;
  }
  if (d < std::abs(r0 - r1)) {  // one inside the other
    if (std::abs(r0 - r1) - d > slack) return 0;
    const double sign = r0 >= r1 ? 1.0 : -1.0;
    out[0] = c0 + sign * u * (r0 - 0.5 * (std::abs(r0 - r1) - d));
    return 1;
  }
  const double a = (r0 * r0 - r1 * r1 + d * d) / (2.0 * d);
  const double h2 = r0 * r0 - a * a;
  const Eigen::Vector2d base = c0 + a * u;
  if (h2 <= 1e-12) {
    out[0] = base;
    return 1;
  }
  const double h = std::sqrt(h2);
  const Eigen::Vector2d normal(-u.y(), u.x());
  out[0] = base + h * normal;
  out[1] = base - h * normal;
  return 2;
}

double CenterBehindSurface(const semantic::SemanticObject& object,
                           const Eigen::Vector2d& direction) {
  const std::vector<Eigen::Vector2d>& polygon = object.footprint;
  if (polygon.size() < 3) return 0.0;
  double best = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d a = polygon[k] - object.center;
    const Eigen::Vector2d e = polygon[(k + 1) % polygon.size()] - polygon[k];
    // Solve t·direction = a + s·e by Cramer's rule, t = t_num / det and s = s_num / det; the
    // tests are made on the numerators (det made positive), and only a farther hit divides: this
    // runs for every edge of every object on every hypothesis.
    double det = direction.y() * e.x() - direction.x() * e.y();
    if (std::abs(det) < 1e-12) continue;
    double t_num = a.y() * e.x() - a.x() * e.y();
    double s_num = direction.x() * a.y() - direction.y() * a.x();
    if (det < 0.0) {
      det = -det;
      t_num = -t_num;
      s_num = -s_num;
    }
    if (t_num > best * det && s_num >= -1e-9 * det && s_num <= (1.0 + 1e-9) * det) {
      best = t_num / det;
    }
  }
  return best;
}

}  // namespace semchain::localization
