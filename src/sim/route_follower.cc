#include "sim/route_follower.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/angles.h"

namespace semchain::sim {
namespace {

// One step of a plan: drive to a point, or rotate in place by an angle (which may exceed 2π).
struct Leg {
  enum class Kind { kGoTo, kRotate };
  Kind kind = Kind::kGoTo;
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  double rotation = 0.0;  // kRotate: signed radians still to turn
  std::string name;       // for error messages, e.g. "mapping_route[3] (4.00, 1.00)"
};

std::string PointName(const std::string& label, const Eigen::Vector2d& p) {
  char text[64];
  std::snprintf(text, sizeof(text), " (%.2f, %.2f)", p.x(), p.y());
  return label + text;
}

// The turn from 'pose' to the heading, of 36 around, with the most room ahead (up to
// 'look_ahead'); the first of equals counter-clockwise from 'pose', so no turn when it has as much.
double TurnToMostOpen(const Scene& scene, const Pose2& pose, double radius, double clearance,
                      double look_ahead) {
  constexpr int kHeadings = 36;
  double most_room = -1.0;
  double turn = 0.0;
  for (int k = 0; k < kHeadings; ++k) {
    const double candidate = NormalizeAngle(2.0 * std::numbers::pi * k / kHeadings);
    const double room = FreeDistanceAhead(scene, Pose2(pose.x, pose.y, pose.theta + candidate),
                                          radius, clearance, look_ahead);
    if (room > most_room) {
      most_room = room;
      turn = candidate;
    }
  }
  return turn;
}

Result<std::vector<Leg>> PlanLegs(const Scene& scene, const RobotSpec& robot,
                                  const RouteSpec& route, const Pose2& start,
                                  const TrialOptions& trial) {
  std::vector<Leg> legs;
  if (route.kind == RouteSpec::Kind::kTrial) {
    legs.push_back({Leg::Kind::kRotate, {}, trial.rotation_radians, "the trial rotation"});
    Pose2 turned(start.x, start.y, start.theta + trial.rotation_radians);
    if (trial.face_most_open) {
      const double turn = TurnToMostOpen(scene, turned, robot.radius, trial.stop_clearance_meters,
                                         trial.open_look_ahead_meters);
      if (turn != 0.0) legs.push_back({Leg::Kind::kRotate, {}, turn, "the turn to open space"});
      turned.theta += turn;
    }
    const double distance = FreeDistanceAhead(
        scene, turned, robot.radius, trial.stop_clearance_meters, trial.forward_distance_meters);
    const Eigen::Vector2d goal = turned * Eigen::Vector2d(distance, 0.0);
    if (distance > 0.0)
      legs.push_back({Leg::Kind::kGoTo, goal, 0.0, PointName("the trial goal", goal)});
    if (trial.rotation_after_radians != 0.0) {
      legs.push_back(
          {Leg::Kind::kRotate, {}, trial.rotation_after_radians, "the rotation after the drive"});
    }
    return legs;
  }
  const bool mapping = route.kind == RouteSpec::Kind::kMapping;
  const auto& points = mapping ? scene.world().mapping_route : route.waypoints;
  if (points.empty()) {
    return Status::Error(mapping ? "the world has no mapping_route" : "the route has no waypoints");
  }
  const std::string label = mapping ? "mapping_route" : "waypoint";
  for (std::size_t i = 0; i < points.size(); ++i) {
    legs.push_back({Leg::Kind::kGoTo, points[i], 0.0,
                    PointName(label + "[" + std::to_string(i) + "]", points[i])});
  }
  return legs;
}

// Runs the legs of a plan one after the other, each within a generous time budget.
class LegRunner {
 public:
  LegRunner(std::vector<Leg> legs, const DriveOptions& drive, const Pose2& start)
      : legs_(std::move(legs)), controller_(drive) {
    if (!legs_.empty()) budget_ = Budget(legs_[0], start);
  }

  bool done() const { return current_ >= legs_.size(); }
  const std::string& name() const { return legs_[std::min(current_, legs_.size() - 1)].name; }

  // The command for the next 'dt' seconds from 'pose'. A leg with nothing left to do ends
  // here and the next one starts in the same step.
  VelocityCommand Command(const Pose2& pose, double dt) {
    while (!done()) {
      bool finished = false;
      const VelocityCommand command = LegCommand(legs_[current_], pose, dt, &finished);
      if (!finished) return command;
      if (++current_ < legs_.size()) {
        leg_start_ = elapsed_;
        budget_ = Budget(legs_[current_], pose);
      }
    }
    return {};
  }

  // Counts 'dt' seconds against the current leg's budget; an error once it is spent.
  Status Spend(double dt) {
    elapsed_ += dt;
    if (done() || elapsed_ - leg_start_ <= budget_) return Status::Ok();
    return Status::Error(name() + " not reached within " +
                         std::to_string(static_cast<int>(budget_)) + " s");
  }

 private:
  // Twice the ideal time plus ten seconds.
  double Budget(const Leg& leg, const Pose2& pose) const {
    const DriveOptions& drive = controller_.options();
    if (leg.kind == Leg::Kind::kRotate) {
      return 2.0 * std::abs(leg.rotation) / drive.max_turn_rate + 10.0;
    }
    const double distance = (leg.goal - pose.translation()).norm();
    return 2.0 * (distance / drive.max_speed + kPi / drive.max_turn_rate) + 10.0;
  }

  VelocityCommand LegCommand(Leg& leg, const Pose2& pose, double dt, bool* finished) const {
    if (leg.kind == Leg::Kind::kGoTo) {
      *finished = controller_.Reached(pose, leg.goal);
      return *finished ? VelocityCommand{} : controller_.Command(pose, leg.goal, dt);
    }
    *finished = std::abs(leg.rotation) < 1e-9;
    if (*finished) return {};
    const double rate = std::min(controller_.options().max_turn_rate, std::abs(leg.rotation) / dt);
    const double turn = std::copysign(rate, leg.rotation);
    leg.rotation -= turn * dt;
    return {0.0, turn};
  }

  std::vector<Leg> legs_;
  PointController controller_;
  std::size_t current_ = 0;
  double elapsed_ = 0.0;
  double leg_start_ = 0.0;  // when the current leg began (seconds)
  double budget_ = 0.0;     // how long the current leg may take
};

}  // namespace

DriveOptions DriveOptionsFor(const RobotSpec& robot) {
  DriveOptions options;
  options.max_speed = robot.max_speed;
  options.max_turn_rate = robot.max_turn_rate;
  options.min_speed = std::min(options.min_speed, robot.max_speed);
  return options;
}

double FreeDistanceAhead(const Scene& scene, const Pose2& pose, double radius, double clearance,
                         double limit) {
  // Rays across the robot's width; a surface met at distance d by the ray at lateral offset y
  // stops the disc when its front at that offset, sqrt(r² - y²) ahead of the centre, gets there.
  double free = limit;
  for (int k = -4; k <= 4; ++k) {
    const double y = radius * k / 4.0;
    const double front = std::sqrt(std::max(0.0, radius * radius - y * y));
    const Eigen::Vector2d origin = pose * Eigen::Vector2d(0.0, y);
    const auto hits = scene.CastAll(origin, pose.theta, limit + radius + clearance + 0.1);
    if (!hits.empty()) free = std::min(free, hits.front().distance - front - clearance);
  }
  return std::max(0.0, free);
}

Result<std::vector<TrajectorySample>> GenerateTrajectory(const Scene& scene, const RobotSpec& robot,
                                                         const RouteSpec& route, const Pose2& start,
                                                         const TrajectoryOptions& options) {
  if (options.check_collisions && scene.IsOccupied(start.translation(), robot.radius)) {
    return Status::Error("the start pose" + PointName("", start.translation()) +
                         " is closer than the robot's radius to a surface");
  }
  Result<std::vector<Leg>> legs = PlanLegs(scene, robot, route, start, options.trial);
  if (!legs.ok()) return legs.status();
  LegRunner runner(std::move(*legs), DriveOptionsFor(robot), start);
  const double period = 1.0 / options.sample_rate_hz;
  const double dt = period / options.control_substeps;
  std::vector<TrajectorySample> samples = {{0.0, start, {}}};
  Pose2 pose = start;
  while (!runner.done()) {
    VelocityCommand command;
    for (int s = 0; s < options.control_substeps; ++s) {
      command = runner.Command(pose, dt);
      pose = IntegrateDiffDrive(pose, command, dt);
      if (options.check_collisions && scene.IsOccupied(pose.translation(), robot.radius)) {
        return Status::Error("the robot hits a surface at" + PointName("", pose.translation()) +
                             " on its way to " + runner.name());
      }
    }
    SEMCHAIN_RETURN_IF_ERROR(runner.Spend(period));
    // k / rate rather than k * period: 1.8 s, not 1.8000000000000003 s.
    const double time = static_cast<double>(samples.size()) / options.sample_rate_hz;
    samples.push_back({time, pose, command});
  }
  return samples;
}

}  // namespace semchain::sim
