#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "sensors/laser_scan.h"

// A laser scan turned into what mapping and scan matching use: beam endpoints and directions in
// the robot frame (the laser offset applied), split into returns and free-space-only beams.
namespace semchain::mapping {

struct ScanPreparationOptions {
  // Readings below this are treated as no return (the sensor's own body, dust).
  double min_range_meters = 0.05;
  // Usable range: a return beyond it marks free space up to it but no obstacle, because far
  // endpoints are sparse and their angular error large (GMapping's maxUrange).
  double max_range_meters = 30.0;
  // A no-return beam (reading >= the sensor's max range, e.g. 81.91 in mit-csail) says nothing
  // by default: glass and black surfaces give no return at short range. When this is positive
  // such beams clear free space up to this many metres.
  double no_return_clear_meters = 0.0;

  bool Validate(std::string* error) const;
};

struct PreparedBeam {
  Eigen::Vector2d endpoint;   // robot frame, metres
  Eigen::Vector2d direction;  // unit vector, robot frame
  bool hit = false;           // true: the endpoint is an obstacle; false: free space only
};

struct PreparedScan {
  double timestamp = 0.0;
  Eigen::Vector2d sensor_origin = Eigen::Vector2d::Zero();  // laser position, robot frame
  std::vector<PreparedBeam> beams;
  // Readings that measured something: a return at any range, or no echo within the sensor's
  // max range (open space). Not the zero readings of a sensor that measured nothing in that
  // direction (a Neato's 70 %). How many returns a scan match must find is relative to this.
  int measured = 0;
  int HitCount() const;
};

// Converts 'scan' taken by a laser at 'laser_offset' in the robot frame.
PreparedScan PrepareScan(const LaserScan& scan, const Pose2& laser_offset,
                         const ScanPreparationOptions& options);

// The returns a scan matcher scores: endpoints and unit beam directions in the robot frame.
struct MatchPoints {
  std::vector<Eigen::Vector2d> points;
  std::vector<Eigen::Vector2d> directions;
  // The scan's measured readings at this selection's beam step (at least its points): what it
  // could have held had every measured reading returned within range.
  int measured = 0;
  std::size_t size() const { return points.size(); }
};

// The returns of 'scan' closer than 'max_range_meters', every 'beam_step'-th one.
MatchPoints SelectMatchPoints(const PreparedScan& scan, double max_range_meters, int beam_step = 1);

}  // namespace semchain::mapping
