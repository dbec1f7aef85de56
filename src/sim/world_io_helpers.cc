#include <string>
#include <vector>

#include "sim/world_io_internal.h"

namespace semchain::sim::internal {

Status ReadRequired(const yaml::Node& map, const std::string& key, double* value) {
  Result<yaml::Node> node = map.Get(key);
  if (!node.ok()) return node.status();
  Result<double> number = node->AsDouble();
  if (!number.ok()) return number.status();
  *value = *number;
  return Status::Ok();
}

Status ReadPositive(const yaml::Node& map, const std::string& key, double* value, bool required) {
  if (!required && !map.Has(key)) return Status::Ok();
  SEMCHAIN_RETURN_IF_ERROR(ReadRequired(map, key, value));
  if (*value <= 0.0) return map.Get(key)->Error("must be positive");
  return Status::Ok();
}

Status ReadNonNegative(const yaml::Node& map, const std::string& key, double* value) {
  if (!map.Has(key)) return Status::Ok();
  SEMCHAIN_RETURN_IF_ERROR(ReadRequired(map, key, value));
  if (*value < 0.0) return map.Get(key)->Error("must not be negative");
  return Status::Ok();
}

Status ReadNonNegativeInt(const yaml::Node& map, const std::string& key, int* value) {
  if (!map.Has(key)) return Status::Ok();
  SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(map, key, value));
  if (*value < 0) return map.Get(key)->Error("must not be negative");
  return Status::Ok();
}

Status ReadInRange(const yaml::Node& map, const std::string& key, double low, double high,
                   double* value) {
  if (!map.Has(key)) return Status::Ok();
  SEMCHAIN_RETURN_IF_ERROR(ReadRequired(map, key, value));
  if (*value < low || *value > high) {
    return map.Get(key)->Error("must lie in [" + std::to_string(low) + ", " + std::to_string(high) +
                               "]");
  }
  return Status::Ok();
}

Status ParsePointList(const yaml::Node& node, std::size_t min_points, const std::string& what,
                      std::vector<Eigen::Vector2d>* points) {
  if (!node.IsSequence()) return node.Error("expected a list of [x, y] points");
  if (node.size() < min_points) {
    return node.Error(what + " needs at least " + std::to_string(min_points) + " point" +
                      (min_points == 1 ? "" : "s") + ", got " + std::to_string(node.size()));
  }
  points->clear();
  for (std::size_t i = 0; i < node.size(); ++i) {
    Result<std::vector<double>> xy = node.At(i).AsDoubleList(2);
    if (!xy.ok()) return xy.status();
    points->emplace_back((*xy)[0], (*xy)[1]);
  }
  return Status::Ok();
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) joined += (joined.empty() ? "" : ", ") + name;
  return joined;
}

}  // namespace semchain::sim::internal
