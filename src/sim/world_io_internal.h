#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/yaml_reader.h"
#include "sim/world.h"

// Pieces of the world parser shared by its sections (world_io*.cc); not part of the API.
namespace semchain::sim::internal {

// Reads map[key] into '*value'; a missing key is an error.
Status ReadRequired(const yaml::Node& map, const std::string& key, double* value);
// Reads map[key] (required or optional) and checks that it is > 0.
Status ReadPositive(const yaml::Node& map, const std::string& key, double* value, bool required);
// Reads an optional map[key] and checks that it is >= 0.
Status ReadNonNegative(const yaml::Node& map, const std::string& key, double* value);
Status ReadNonNegativeInt(const yaml::Node& map, const std::string& key, int* value);
// Reads an optional map[key] and checks that it lies in [low, high].
Status ReadInRange(const yaml::Node& map, const std::string& key, double low, double high,
                   double* value);

// A list of [x, y] points with at least 'min_points' entries; 'what' names it in errors
// ("a wall needs at least 2 points, got 1").
Status ParsePointList(const yaml::Node& node, std::size_t min_points, const std::string& what,
                      std::vector<Eigen::Vector2d>* points);

std::string JoinNames(const std::vector<std::string>& names);

// The list root[key] ("objects" or "obstacles") of solids; objects of the classes with a shape
// (object_shapes.h) are built of parts unless the world or the object says shape: prism.
Status ParseSolids(const yaml::Node& root, const std::string& key, const World& world,
                   std::vector<Solid>* solids);
// The world's object_shapes, shell (wall and floor looks) and lighting keys.
Status ParseShellAndLighting(const yaml::Node& root, World* world);

// The robot section (start pose, lidar, camera, odometry noise, speeds and rates).
Status ParseRobot(const yaml::Node& node, RobotSpec* robot);
// The detection error model section.
Status ParseDetectionModel(const yaml::Node& node, DetectionModelSpec* model);

}  // namespace semchain::sim::internal
