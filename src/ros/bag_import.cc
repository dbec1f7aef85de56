#include "ros/bag_import.h"

#include <sensor_msgs/LaserScan.h>
#include <std_msgs/String.h>

#include <cstdio>
#include <memory>
#include <optional>

#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "io/camera_io.h"
#include "io/carmen.h"
#include "io/detections_io.h"
#include "io/trajectory_io.h"
#include "ros/bag_reader.h"
#include "ros/bag_transforms.h"
#include "ros/camera_import.h"
#include "ros/detections_import.h"
#include "ros/scan_import.h"
#include "ros/truth_import.h"
#include "sim/run_directory.h"

namespace semchain::ros1 {
namespace fs = std::filesystem;
namespace {

// The bag's run info (one message), if it has one.
Result<std::optional<RunInfo>> ReadRunInfo(BagReader& reader, const std::string& topic) {
  std::optional<RunInfo> info;
  const Status status = reader.ForEach<std_msgs::String>(
      {topic}, [&info](const std_msgs::String& msg, const BagMessage& message) -> Status {
        Result<RunInfo> parsed = ParseRunInfo(msg.data, message.where);
        if (!parsed.ok()) return parsed.status();
        info = *parsed;
        return Status::Ok();
      });
  if (!status.ok()) return status;
  return info;
}

// tf, or the odometry topic where tf lacks odom → base.
Result<std::unique_ptr<BagTransforms>> LoadTransforms(BagReader& reader,
                                                      const BagImportOptions& options,
                                                      std::string* source) {
  Result<std::unique_ptr<BagTransforms>> transforms = BagTransforms::Load(reader, options.topics);
  if (!transforms.ok()) return transforms;
  const BagFrames& frames = options.frames;
  *source = "tf " + frames.odom + " -> " + frames.base;
  if (!(*transforms)->Connects(frames.odom, frames.base) && reader.Has(options.topics.odom)) {
    SEMCHAIN_RETURN_IF_ERROR(
        (*transforms)->AddOdometry(reader, options.topics.odom, frames.odom, frames.base));
    *source = options.topics.odom;
  }
  return transforms;
}

// Everything read from the bag, before it is written.
struct ImportedRun {
  std::string odometry;  // where it came from
  ImportedTruth truth;
  ImportedLog log;
  ImportedCamera camera;
  std::vector<FrameDetections> detections;
};

// Reads the bag; the camera's frames are written into 'dir' as they stream by.
Result<ImportedRun> ReadBag(BagReader& reader, const fs::path& dir, ImportContext& context) {
  const BagImportOptions& options = context.options;
  ImportedRun run;
  SEMCHAIN_RETURN_IF_ERROR(reader.Require<sensor_msgs::LaserScan>(options.topics.scan));
  Result<std::optional<RunInfo>> run_info = ReadRunInfo(reader, options.topics.run_info);
  if (!run_info.ok()) return run_info.status();
  context.run_info = *run_info;
  if (context.run_info) context.stamp_offset_seconds = context.run_info->stamp_offset_seconds;
  Result<std::unique_ptr<BagTransforms>> transforms =
      LoadTransforms(reader, options, &run.odometry);
  if (!transforms.ok()) return transforms.status();
  Result<ImportedTruth> truth = ImportTruth(reader, context);
  if (!truth.ok()) return truth.status();
  run.truth = std::move(*truth);

  Result<CameraTopics> camera_topics =
      options.import_camera ? ResolveCameraTopics(reader, options.topics) : CameraTopics{};
  if (!camera_topics.ok()) return camera_topics.status();

  // The progress bar counts scans and images, the bulk of the work.
  std::optional<ProgressBar> progress;
  if (options.show_progress) {
    progress.emplace("bag import", reader.MessageCount({options.topics.scan, camera_topics->color,
                                                        camera_topics->depth}));
    reader.set_on_message(
        [&progress, done = std::size_t{0}]() mutable { progress->Update(++done); });
  }
  Result<ImportedLog> log = ImportScans(reader, **transforms, run.truth.by_stamp, context);
  if (!log.ok()) return log.status();
  run.log = std::move(*log);
  Result<ImportedCamera> camera = ImportCamera(reader, **transforms, *camera_topics, dir, context);
  if (!camera.ok()) return camera.status();
  run.camera = std::move(*camera);
  reader.set_on_message(nullptr);
  if (progress) progress->Finish();

  Result<std::vector<FrameDetections>> detections =
      ImportDetections(reader, run.camera.frames, context);
  if (!detections.ok()) return detections.status();
  run.detections = std::move(*detections);
  if ((*transforms)->rejected() > 0) {
    context.warnings.push_back(std::to_string((*transforms)->rejected()) +
                               " tf transforms ignored (tf2 refused them)");
  }
  return run;
}

BagImportSummary Summarize(const ImportedRun& run, ImportContext& context) {
  if (run.log.non_finite_ranges > 0) {
    context.warnings.push_back(std::to_string(run.log.non_finite_ranges) +
                               " NaN or infinite ranges written as the scan's range_max "
                               "(no return)");
  }
  BagImportSummary summary;
  summary.scans = run.log.scans;
  summary.skipped_scans = run.log.skipped_scans;
  summary.non_finite_ranges = run.log.non_finite_ranges;
  summary.frames = run.camera.frames.size();
  summary.detection_records = run.detections.size();
  summary.truth_poses = run.truth.poses.size();
  summary.odometry = run.odometry;
  summary.stamp_offset_seconds = context.stamp_offset_seconds;
  summary.warnings = context.warnings;
  return summary;
}

std::string FormatRunYaml(const fs::path& bag_path, const BagImportSummary& summary,
                          double duration_s) {
  char duration[40];
  std::snprintf(duration, sizeof(duration), "%.9g", duration_s);
  std::string text = "# What `semchain bag import` did to make this run directory.\n";
  text += "source: " + bag_path.string() + "\n";
  text += "scans: " + std::to_string(summary.scans) + "\n";
  text += "scans_left_out: " + std::to_string(summary.skipped_scans) + "\n";
  text += "duration_s: " + std::string(duration) + "\n";
  text += "frames: " + std::to_string(summary.frames) + "\n";
  text += "odometry: " + summary.odometry + "\n";
  text += "stamp_offset_s: " + std::to_string(summary.stamp_offset_seconds) + "\n";
  return text;
}

// Writes the run's files (the frames are there already) into 'dir'.
Status WriteRunFiles(const fs::path& dir, const ImportedRun& run, const RunInfo* run_info,
                     const std::string& run_yaml) {
  SEMCHAIN_RETURN_IF_ERROR(carmen::WriteLog(dir / "log.clf", run.log.log));
  if (!run.truth.poses.empty()) {
    SEMCHAIN_RETURN_IF_ERROR(WriteTrajectory(dir / "truth.txt", run.truth.poses));
  }
  if (run.camera.camera) {
    SEMCHAIN_RETURN_IF_ERROR(WriteCameraYaml(dir / "camera.yaml", *run.camera.camera));
  }
  if (!run.detections.empty()) {
    SEMCHAIN_RETURN_IF_ERROR(WriteDetectionsJsonl(dir / "detections.jsonl", run.detections));
  }
  if (run_info != nullptr && run_info->world_yaml) {
    SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(dir / "world.yaml", *run_info->world_yaml));
  }
  return WriteFileAtomically(dir / "run.yaml", run_yaml);
}

// Reads the bag and writes every file of the run into 'dir' (the staging directory).
Result<BagImportSummary> ImportInto(BagReader& reader, const fs::path& dir,
                                    ImportContext& context) {
  Result<ImportedRun> run = ReadBag(reader, dir, context);
  if (!run.ok()) return run.status();
  const BagImportSummary summary = Summarize(*run, context);
  const std::string run_yaml =
      FormatRunYaml(reader.path(), summary, run->log.last_stamp - run->log.first_stamp);
  const RunInfo* run_info = context.run_info ? &*context.run_info : nullptr;
  SEMCHAIN_RETURN_IF_ERROR(WriteRunFiles(dir, *run, run_info, run_yaml));
  return summary;
}

}  // namespace

Result<BagImportSummary> ImportBagToRun(const fs::path& bag_path, const fs::path& run_dir,
                                        const BagImportOptions& options) {
  fs::path dir = run_dir.lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();
  if (dir.empty() || dir == ".") return Status::Error("the output directory must be named");
  Result<std::unique_ptr<BagReader>> reader = BagReader::Open(bag_path);
  if (!reader.ok()) return reader.status();
  Result<fs::path> staging = sim::BeginRunDirectory(dir);
  if (!staging.ok()) return staging.status();
  ImportContext context{options, std::nullopt, 0, {}};
  Result<BagImportSummary> summary = ImportInto(**reader, *staging, context);
  if (!summary.ok()) {
    sim::AbandonRunDirectory(*staging);
    return summary;
  }
  SEMCHAIN_RETURN_IF_ERROR(sim::FinishRunDirectory(*staging, dir));
  return summary;
}

}  // namespace semchain::ros1
