#include "io/trajectory_io.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/atomic_file.h"

namespace semchain {

Result<std::vector<StampedPose>> ReadTrajectory(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return Status::Error(path.string() + ": cannot open trajectory file");
  std::vector<StampedPose> poses;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double t = 0.0, x = 0.0, y = 0.0, theta = 0.0;
    std::string extra;
    if (!(fields >> t >> x >> y >> theta) || (fields >> extra)) {
      return Status::Error(path.string() + ":" + std::to_string(line_number) +
                           ": expected 'timestamp x y theta'");
    }
    if (!std::isfinite(t) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(theta)) {
      return Status::Error(path.string() + ":" + std::to_string(line_number) +
                           ": non-finite value");
    }
    poses.push_back({t, Pose2(x, y, theta)});
  }
  return poses;
}

Status WriteTrajectory(const std::filesystem::path& path, const std::vector<StampedPose>& poses) {
  return WriteFileAtomically(path, [&poses](std::ostream& out) {
    out << "# timestamp x y theta\n" << std::setprecision(17);
    for (const StampedPose& p : poses) {
      out << p.timestamp << ' ' << p.pose.x << ' ' << p.pose.y << ' ' << p.pose.theta << '\n';
    }
    return Status::Ok();
  });
}

}  // namespace semchain
