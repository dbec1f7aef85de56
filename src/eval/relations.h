#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"
#include "io/trajectory_io.h"

// The relation-based SLAM accuracy metric of Kümmerle et al., "On measuring the accuracy of
// SLAM algorithms", Autonomous Robots 27(4), 2009 (DESIGN.md §4, shared/data/README.md).
namespace semchain::eval {

// One reference relation: the motion 'delta' from the robot pose at 't1' to the one at 't2',
// expressed in the frame of the first (δ_ij of the paper).
struct Relation {
  double t1 = 0.0;
  double t2 = 0.0;
  Pose2 delta;
};

// Reads a relation file: one "t1 t2 dx dy dz roll pitch dyaw" line per relation (the 3D
// fields dz, roll and pitch must be there and are ignored); '#' lines and blank lines are
// skipped. Errors name file and line.
Result<std::vector<Relation>> ReadRelations(const std::filesystem::path& path);

struct RelationOptions {
  // A relation's timestamps match the trajectory pose nearest to them when within this; the
  // public relation files round the logs' timestamps to 10 µs.
  double timestamp_tolerance_s = 1e-3;
};

// The metric's summary: mean and (population) standard deviation of the absolute and squared
// translational (m, m²) and rotational (deg, deg²) errors over the matched relations.
struct RelationErrors {
  std::size_t relations = 0;  // relations given
  std::size_t matched = 0;    // relations whose two timestamps both matched a pose
  double trans_mean_m = 0.0;
  double trans_std_m = 0.0;
  double rot_mean_deg = 0.0;
  double rot_std_deg = 0.0;
  double trans_sq_mean = 0.0;
  double trans_sq_std = 0.0;
  double rot_sq_mean = 0.0;
  double rot_sq_std = 0.0;
};

// The error of one relation against the estimate's δ* = x_i⁻¹ ⊕ x_j: e = δ* ⊖ δ = δ⁻¹ ⊕ δ*,
// so |trans(e)| = |t(δ*) - t(δ)| and |rot(e)| = |θ(δ*) - θ(δ)| wrapped to [0, π].
struct RelationError {
  double trans_m = 0.0;
  double rot_rad = 0.0;
};
RelationError ErrorOfRelation(const Relation& relation, const Pose2& x_i, const Pose2& x_j);

// Scores 'trajectory' (any order) against 'relations'. Fails when no relation matches, since
// every statistic would be undefined.
Result<RelationErrors> EvaluateRelations(const std::vector<StampedPose>& trajectory,
                                         const std::vector<Relation>& relations,
                                         const RelationOptions& options = {});

// The JSON object `semchain eval relations` prints (keys as in DESIGN.md §4).
std::string RelationErrorsToJson(const RelationErrors& errors);

}  // namespace semchain::eval
