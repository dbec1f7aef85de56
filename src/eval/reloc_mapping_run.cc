#include "eval/reloc_mapping_run.h"

#include <nlohmann/json.hpp>

#include "bow/bow_vocabulary.h"
#include "bow/orb_features.h"
#include "bow/run_features.h"
#include "core/atomic_file.h"
#include "eval/ate.h"
#include "io/carmen.h"
#include "mapping/slam_pipeline.h"
#include "semantic/keyframe_selection.h"
#include "semantic/semantic_map_io.h"
#include "semantic/semantic_run.h"
#include "sim/simulator.h"

namespace semchain::eval {
namespace fs = std::filesystem;
namespace {

// The SLAM of a simulated mapping run in 'run', with the benchmark's options.
Result<mapping::SlamResult> MappingSlam(const fs::path& run, std::uint64_t seed) {
  Result<carmen::Log> log = carmen::ReadLog(run / "log.clf");
  if (!log.ok()) return log.status();
  Result<std::vector<StampedScan>> scans = mapping::ScansFromLog(*log, (run / "log.clf").string());
  if (!scans.ok()) return scans.status();
  mapping::SlamOptions slam_options;
  slam_options.rbpf.seed = seed;
  return mapping::RunSlam(*scans, slam_options);
}

}  // namespace

Result<std::shared_ptr<const bow::KeyframeRecognizer>> BuildRelocRecognizer(
    const RelocBuiltMap& built, const fs::path& run, std::uint64_t seed) {
  Result<std::vector<fs::path>> images = bow::ListColorFrames(run);
  if (!images.ok()) return images.status();
  Result<std::vector<cv::Mat>> descriptors =
      bow::ExtractImageDescriptors(*images, bow::OrbOptions());
  if (!descriptors.ok()) return descriptors.status();
  bow::VocabularyOptions options;
  options.seed = seed;
  Result<bow::Vocabulary> vocabulary = bow::Vocabulary::Train(*descriptors, options);
  if (!vocabulary.ok()) return vocabulary.status();
  semantic::KeyframeDatabase database{run.string(),
                                      semantic::SelectCoveringKeyframes(built.keyframes)};
  Result<bow::KeyframeRecognizer> recognizer = bow::KeyframeRecognizer::Build(
      std::move(*vocabulary), std::move(database), bow::KeyframeRecognizerOptions(), run);
  if (!recognizer.ok()) return recognizer.status();
  return std::shared_ptr<const bow::KeyframeRecognizer>(
      std::make_shared<bow::KeyframeRecognizer>(std::move(*recognizer)));
}

Result<RelocBuiltMap> BuildRelocMap(const sim::World& world, const RelocBenchmarkOptions& options,
                                    const fs::path& run) {
  const std::uint64_t seed = options.seed;
  sim::SimulationOptions simulation;
  simulation.seed = seed;
  simulation.show_progress = false;
  SEMCHAIN_RETURN_IF_ERROR(sim::Simulate(world, simulation, run));
  Result<mapping::SlamResult> slam_result = MappingSlam(run, seed);
  if (!slam_result.ok()) return slam_result.status();
  const mapping::SlamResult& slam = *slam_result;

  RelocBuiltMap built;
  built.occupancy = mapping::GridToMapImage(slam.map);
  built.trajectory = slam.trajectory;
  Result<std::vector<StampedPose>> truth = ReadTrajectory(run / "truth.txt");
  if (!truth.ok()) return truth.status();
  Result<AteResult> ate = EvaluateAte(slam.trajectory, *truth);
  if (ate.ok()) built.ate = ate->ate_rmse_m;
  semantic::SemanticRunInputs inputs;
  inputs.run_dir = run;
  inputs.occupancy = built.occupancy;
  inputs.trajectory = slam.trajectory;
  if (options.detect) {
    Result<std::vector<FrameDetections>> detections = options.detect(run);
    if (!detections.ok()) return detections.status();
    inputs.detections = std::move(*detections);
  }
  Result<semantic::SemanticMappingResult> mapped =
      semantic::MapRun(inputs, semantic::SemanticMapOptions());
  if (!mapped.ok()) return mapped.status();
  built.semantic = mapped->map;
  built.keyframes = mapped->keyframes;
  return built;
}

// The mapping run's map as kept in RUN/map: map.yaml, semantic.json, keyframes.json, ate.json.
Status WriteRelocMap(const RelocBuiltMap& built, const fs::path& run) {
  const fs::path dir = run / "map";
  SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(dir));
  SEMCHAIN_RETURN_IF_ERROR(mapping::WriteMap(dir / "map.yaml", built.occupancy));
  SEMCHAIN_RETURN_IF_ERROR(semantic::WriteSemanticJson(dir / "semantic.json", built.semantic));
  SEMCHAIN_RETURN_IF_ERROR(
      semantic::WriteKeyframes(dir / "keyframes.json", {"..", built.keyframes}));
  SEMCHAIN_RETURN_IF_ERROR(WriteTrajectory(dir / "trajectory.txt", built.trajectory));
  return WriteFileAtomically(dir / "ate.json",
                             nlohmann::json({{"ate_rmse_m", built.ate}}).dump() + "\n");
}

Result<RelocBuiltMap> ReadRelocMap(const fs::path& run, std::uint64_t seed) {
  const fs::path dir = run / "map";
  RelocBuiltMap built;
  Result<mapping::MapImage> occupancy = mapping::ReadMap(dir / "map.yaml");
  if (!occupancy.ok()) return occupancy.status();
  built.occupancy = std::move(*occupancy);
  Result<semantic::SemanticMap> map = semantic::ReadSemanticJson(dir / "semantic.json");
  if (!map.ok()) return map.status();
  built.semantic = std::move(*map);
  Result<semantic::KeyframeDatabase> keyframes = semantic::ReadKeyframes(dir / "keyframes.json");
  if (!keyframes.ok()) return keyframes.status();
  built.keyframes = std::move(keyframes->keyframes);
  Result<std::string> ate = ReadFile(dir / "ate.json");
  if (!ate.ok()) return ate.status();
  const nlohmann::json parsed = nlohmann::json::parse(*ate, nullptr, /*allow_exceptions=*/false);
  if (!parsed.is_object() || !parsed.contains("ate_rmse_m") || !parsed["ate_rmse_m"].is_number()) {
    return Status::Error((dir / "ate.json").string() + ": expected {\"ate_rmse_m\": number}");
  }
  built.ate = parsed["ate_rmse_m"].get<double>();
  if (fs::exists(dir / "trajectory.txt")) {
    Result<std::vector<StampedPose>> trajectory = ReadTrajectory(dir / "trajectory.txt");
    if (!trajectory.ok()) return trajectory.status();
    built.trajectory = std::move(*trajectory);
  } else {
    // Kept before the trajectory was: the SLAM is deterministic for its seed, so running it
    // again gives the kept map's trajectory.
    Result<mapping::SlamResult> slam = MappingSlam(run, seed);
    if (!slam.ok()) return slam.status();
    built.trajectory = slam->trajectory;
    SEMCHAIN_RETURN_IF_ERROR(WriteTrajectory(dir / "trajectory.txt", built.trajectory));
  }
  return built;
}

}  // namespace semchain::eval
