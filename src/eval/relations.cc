#include "eval/relations.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/angles.h"
#include "core/atomic_file.h"
#include "eval/statistics.h"
#include "io/text_fields.h"
#include "io/trajectory_lookup.h"

namespace semchain::eval {

Result<std::vector<Relation>> ReadRelations(const std::filesystem::path& path) {
  Result<std::string> contents = ReadFile(path);
  if (!contents.ok()) return contents.status();
  std::istringstream in(*contents);
  std::vector<Relation> relations;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    text::FieldReader fields(line, path.string() + ":" + std::to_string(line_number));
    Relation relation;
    double unused = 0.0;
    // The fields are assigned, not passed through Pose2's constructor, so that the file's
    // values are kept exactly; the error wraps angles anyway.
    SEMCHAIN_RETURN_IF_ERROR(fields.Double("t1", &relation.t1));
    SEMCHAIN_RETURN_IF_ERROR(fields.Double("t2", &relation.t2));
    SEMCHAIN_RETURN_IF_ERROR(fields.Double("dx", &relation.delta.x));
    SEMCHAIN_RETURN_IF_ERROR(fields.Double("dy", &relation.delta.y));
    SEMCHAIN_RETURN_IF_ERROR(fields.Double("dz", &unused));
    SEMCHAIN_RETURN_IF_ERROR(fields.Double("roll", &unused));
    SEMCHAIN_RETURN_IF_ERROR(fields.Double("pitch", &unused));
    SEMCHAIN_RETURN_IF_ERROR(fields.Double("dyaw", &relation.delta.theta));
    SEMCHAIN_RETURN_IF_ERROR(fields.End());
    relations.push_back(relation);
  }
  return relations;
}

RelationError ErrorOfRelation(const Relation& relation, const Pose2& x_i, const Pose2& x_j) {
  const Pose2 estimate = x_i.Between(x_j);               // δ* = x_i⁻¹ ⊕ x_j
  const Pose2 error = relation.delta.Between(estimate);  // δ⁻¹ ⊕ δ*
  return {std::hypot(error.x, error.y), std::abs(NormalizeAngle(error.theta))};
}

Result<RelationErrors> EvaluateRelations(const std::vector<StampedPose>& trajectory,
                                         const std::vector<Relation>& relations,
                                         const RelationOptions& options) {
  const TrajectoryLookup lookup(trajectory);
  RelationErrors result;
  result.relations = relations.size();
  std::vector<double> trans, rot, trans_sq, rot_sq;
  for (const Relation& relation : relations) {
    const std::optional<Pose2> x_i = lookup.Nearest(relation.t1, options.timestamp_tolerance_s);
    const std::optional<Pose2> x_j = lookup.Nearest(relation.t2, options.timestamp_tolerance_s);
    if (!x_i || !x_j) continue;
    const RelationError error = ErrorOfRelation(relation, *x_i, *x_j);
    const double rot_deg = RadToDeg(error.rot_rad);
    trans.push_back(error.trans_m);
    rot.push_back(rot_deg);
    trans_sq.push_back(error.trans_m * error.trans_m);
    rot_sq.push_back(rot_deg * rot_deg);
  }
  result.matched = trans.size();
  if (result.matched == 0) {
    return Status::Error("none of the " + std::to_string(relations.size()) +
                         " relations has both timestamps in the trajectory (within " +
                         text::FormatDouble(options.timestamp_tolerance_s) + " s)");
  }
  const MeanStd t = ComputeMeanStd(trans), r = ComputeMeanStd(rot);
  const MeanStd t2 = ComputeMeanStd(trans_sq), r2 = ComputeMeanStd(rot_sq);
  result.trans_mean_m = t.mean;
  result.trans_std_m = t.std;
  result.rot_mean_deg = r.mean;
  result.rot_std_deg = r.std;
  result.trans_sq_mean = t2.mean;
  result.trans_sq_std = t2.std;
  result.rot_sq_mean = r2.mean;
  result.rot_sq_std = r2.std;
  return result;
}

std::string RelationErrorsToJson(const RelationErrors& e) {
  const nlohmann::ordered_json json = {
      {"relations", e.relations},         {"matched", e.matched},
      {"trans_mean_m", e.trans_mean_m},   {"trans_std_m", e.trans_std_m},
      {"rot_mean_deg", e.rot_mean_deg},   {"rot_std_deg", e.rot_std_deg},
      {"trans_sq_mean", e.trans_sq_mean}, {"trans_sq_std", e.trans_sq_std},
      {"rot_sq_mean", e.rot_sq_mean},     {"rot_sq_std", e.rot_sq_std}};
  return json.dump(2);
}

}  // namespace semchain::eval
