// `semchain eval relations|ate|rpe`: scores a trajectory and prints one JSON object (DESIGN.md §4).
#include <iostream>
#include <memory>
#include <string>

#include "apps/command.h"
#include "eval/ate.h"
#include "eval/relations.h"
#include "eval/rpe.h"
#include "io/trajectory_io.h"

namespace semchain::app {
namespace {

// Reads a trajectory and fails when it has no pose (an empty file is a wrong path, not a score).
Result<std::vector<StampedPose>> ReadPoses(const std::string& path) {
  Result<std::vector<StampedPose>> poses = ReadTrajectory(path);
  if (poses.ok() && poses->empty()) return Status::Error(path + ": no poses in trajectory file");
  return poses;
}

int RunRelations(const std::string& poses_path, const std::string& relations_path,
                 const eval::RelationOptions& options) {
  if (!(options.timestamp_tolerance_s >= 0.0)) {
    return ReportError(Status::Error("--tolerance must be >= 0 seconds"));
  }
  const Result<std::vector<StampedPose>> poses = ReadPoses(poses_path);
  if (!poses.ok()) return ReportError(poses.status());
  const Result<std::vector<eval::Relation>> relations = eval::ReadRelations(relations_path);
  if (!relations.ok()) return ReportError(relations.status());
  const Result<eval::RelationErrors> errors = eval::EvaluateRelations(*poses, *relations, options);
  if (!errors.ok()) return ReportError(errors.status().WithContext(relations_path));
  std::cout << eval::RelationErrorsToJson(*errors) << std::endl;
  return 0;
}

// Scores the trajectory at 'poses_path' against the one at 'truth_path', paired by 'pairing',
// with 'evaluate' (which returns a Result of what 'to_json' prints).
template <typename Evaluate, typename ToJson>
int ScoreAgainstTruth(const std::string& poses_path, const std::string& truth_path,
                      const eval::AteOptions& pairing, const Evaluate& evaluate,
                      const ToJson& to_json) {
  if (!(pairing.timestamp_tolerance_s >= 0.0) || !(pairing.max_interpolation_gap_s >= 0.0)) {
    return ReportError(Status::Error("--tolerance and --max-gap must be >= 0 seconds"));
  }
  const Result<std::vector<StampedPose>> poses = ReadPoses(poses_path);
  if (!poses.ok()) return ReportError(poses.status());
  const Result<std::vector<StampedPose>> truth = ReadPoses(truth_path);
  if (!truth.ok()) return ReportError(truth.status());
  const auto result = evaluate(*poses, *truth);
  if (!result.ok()) {
    return ReportError(result.status().WithContext(poses_path + " against " + truth_path));
  }
  std::cout << to_json(*result) << std::endl;
  return 0;
}

// The options of a trajectory scored against the truth: the two files and how they are paired.
void AddTrajectoryPairOptions(CLI::App* command, std::string* poses, std::string* truth,
                              eval::AteOptions* pairing) {
  command->add_option("--poses", *poses, "Estimated trajectory ('timestamp x y theta')")
      ->required();
  command->add_option("--truth", *truth, "True trajectory, e.g. RUN/truth.txt")->required();
  command->add_flag("--pair-by-index", pairing->pair_by_index,
                    "Score the i-th pose against the i-th truth pose (same count; timestamps "
                    "ignored): for logs whose timestamps cannot pair the poses");
  command
      ->add_option("--tolerance", pairing->timestamp_tolerance_s,
                   "Seconds within which the nearest truth pose is used as is")
      ->capture_default_str();
  command
      ->add_option("--max-gap", pairing->max_interpolation_gap_s,
                   "Longest gap (s) between truth poses to interpolate across")
      ->capture_default_str();
}

void AddRelations(CLI::App& eval, int& exit_code) {
  CLI::App* command = eval.add_subcommand(
      "relations",
      "Relation metric of Kuemmerle et al. 2009: mean/std of translational (m) and rotational "
      "(deg) errors, absolute and squared, as one JSON object");
  struct Args {
    std::string poses, relations;
    eval::RelationOptions options;
  };
  auto args = std::make_shared<Args>();
  command->add_option("--poses", args->poses, "Trajectory file: 'timestamp x y theta' per line")
      ->required();
  command
      ->add_option("--relations", args->relations,
                   "Relation file: 't1 t2 dx dy dz roll pitch dyaw' per line")
      ->required();
  command
      ->add_option("--tolerance", args->options.timestamp_tolerance_s,
                   "Seconds within which a relation's timestamp matches a pose")
      ->capture_default_str();
  command->callback([args, &exit_code] {
    exit_code = RunRelations(args->poses, args->relations, args->options);
  });
}

void AddAte(CLI::App& eval, int& exit_code) {
  CLI::App* command = eval.add_subcommand(
      "ate",
      "Absolute trajectory error against the truth (RMSE, mean, max in m; heading RMSE "
      "in deg) as one JSON object");
  struct Args {
    std::string poses, truth;
    eval::AteOptions options;
  };
  auto args = std::make_shared<Args>();
  AddTrajectoryPairOptions(command, &args->poses, &args->truth, &args->options);
  command->add_flag("--align", args->options.align,
                    "First fit the estimate to the truth with the best SE(2) transform");
  command->callback([args, &exit_code] {
    exit_code = ScoreAgainstTruth(
        args->poses, args->truth, args->options,
        [&](const auto& poses, const auto& truth) {
          return eval::EvaluateAte(poses, truth, args->options);
        },
        eval::AteResultToJson);
  });
}

void AddRpe(CLI::App& eval, int& exit_code) {
  CLI::App* command = eval.add_subcommand(
      "rpe",
      "Relative pose error over stretches of travel (drift between closures): median, p95 and "
      "max of the translation (m) and rotation (deg) errors per stretch length, as one JSON "
      "object");
  struct Args {
    std::string poses, truth;
    eval::RpeOptions options;
  };
  auto args = std::make_shared<Args>();
  AddTrajectoryPairOptions(command, &args->poses, &args->truth, &args->options.pairing);
  command
      ->add_option("--travel", args->options.travel_meters,
                   "Stretch lengths, metres travelled along the true path")
      ->delimiter(',')
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->callback([args, &exit_code] {
    exit_code = ScoreAgainstTruth(
        args->poses, args->truth, args->options.pairing,
        [&](const auto& poses, const auto& truth) {
          return eval::EvaluateRpe(poses, truth, args->options);
        },
        eval::RpeResultToJson);
  });
}

}  // namespace

void AddEvalCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand("eval", "Score a trajectory: relation metric, ATE or RPE");
  command->require_subcommand(1);
  AddRelations(*command, exit_code);
  AddAte(*command, exit_code);
  AddRpe(*command, exit_code);
}

}  // namespace semchain::app
