// semchain bag export RUN --out FILE.bag [--no-images] [--compression none|lz4|bz2]
// semchain bag import FILE.bag --out RUN [--scan-topic T] [--odom-frame F] [--base-frame F]
//                     [--camera NS] [--color-topic T] [--depth-topic T] [--camera-yaml FILE]
//                     [--detections-topic T] ...
// Compiled in only where ROS 1 is found (SEMCHAIN_WITH_ROS).
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "apps/command.h"
#include "ros/bag_export.h"
#include "ros/bag_import.h"

namespace semchain::app {
namespace {

void PrintWarnings(const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) {
    std::fprintf(stderr, "semchain: warning: %s\n", warning.c_str());
  }
}

void AddExport(CLI::App& bag, int& exit_code) {
  CLI::App* command = bag.add_subcommand(
      "export",
      "Write a run directory as a ROS bag: /scan, /tf, /tf_static, /odom, the camera's images "
      "and camera_info, /semchain/detections and /semchain/truth (DESIGN.md section 5.7)");
  struct Args {
    std::string run, out;
    bool no_images = false;
    std::string compression = "none";
    ros1::BagExportOptions options;
  };
  auto args = std::make_shared<Args>();
  command
      ->add_option("RUN", args->run,
                   "Run directory (semchain simulate or bag import), or a CARMEN log (.clf, .gz)")
      ->required();
  command->add_option("--out", args->out, "Bag file to write (replaced atomically)")->required();
  command->add_flag("--no-images", args->no_images,
                    "Leave the colour and depth images out (detections and camera_info stay)");
  command
      ->add_option("--compression", args->compression,
                   "Chunk compression: none (as rosbag record makes them), lz4 or bz2")
      ->check(CLI::IsMember({"none", "lz4", "bz2"}))
      ->capture_default_str();
  command->callback([args, &exit_code] {
    args->options.images = !args->no_images;
    args->options.compression = args->compression == "lz4"   ? ros1::BagCompression::kLz4
                                : args->compression == "bz2" ? ros1::BagCompression::kBz2
                                                             : ros1::BagCompression::kNone;
    const Result<ros1::BagExportSummary> summary =
        ros1::ExportRunToBag(args->run, args->out, args->options);
    if (!summary.ok()) {
      exit_code = ReportError(summary.status());
      return;
    }
    std::printf("wrote %s: %zu scans, %zu camera frames, %zu images, %zu messages",
                args->out.c_str(), summary->scans, summary->frames, summary->images,
                summary->messages);
    if (summary->stamp_offset_seconds != 0) {
      std::printf(" (stamps + %lld s)", static_cast<long long>(summary->stamp_offset_seconds));
    }
    std::printf("\n");
    if (summary->restamped_scans > 0) {
      std::fprintf(stderr,
                   "semchain: warning: %zu scans were stamped at or before the scan before them; "
                   "stamped 1 ms after it, to keep the log's order\n",
                   summary->restamped_scans);
    }
    exit_code = 0;
  });
}

void AddImport(CLI::App& bag, int& exit_code) {
  CLI::App* command = bag.add_subcommand(
      "import",
      "Turn a ROS bag into a run directory for slam, semantic and localize: log.clf (scans with "
      "odometry from tf), camera.yaml, frames/, detections.jsonl, truth.txt");
  struct Args {
    std::string bag, out;
    ros1::BagImportOptions options;
    double camera_max_range = 0.0;
  };
  auto args = std::make_shared<Args>();
  ros1::BagImportOptions& options = args->options;
  command->add_option("BAG", args->bag, "ROS 1 bag file")->required();
  command->add_option("--out", args->out, "Run directory to write (replaces an earlier run)")
      ->required();
  command->add_option("--scan-topic", options.topics.scan, "sensor_msgs/LaserScan topic")
      ->capture_default_str();
  command->add_option("--odom-frame", options.frames.odom, "Odometry frame in tf")
      ->capture_default_str();
  command->add_option("--base-frame", options.frames.base, "Robot frame in tf")
      ->capture_default_str();
  command
      ->add_option("--odom-topic", options.topics.odom,
                   "nav_msgs/Odometry topic, used when tf has no odom -> base transform")
      ->capture_default_str();
  command
      ->add_option("--camera", options.topics.camera,
                   "RGB-D camera namespace: colour from NS/color/image_raw, NS/rgb/image_raw or "
                   "NS/image_raw, depth from NS/depth/image_raw, "
                   "NS/aligned_depth_to_color/image_raw or NS/depth_registered/image_raw (each "
                   "also as image_transport's /compressed or /compressedDepth), camera_info "
                   "beside the colour image")
      ->capture_default_str();
  command->add_option("--color-topic", options.topics.color_image,
                      "Colour image topic (sensor_msgs/Image or CompressedImage; T/compressed "
                      "is taken when the bag has only that)");
  command->add_option("--depth-topic", options.topics.depth_image,
                      "Depth image aligned to colour (sensor_msgs/Image, or CompressedImage "
                      "from compressed_depth_image_transport; T/compressedDepth is taken when "
                      "the bag has only that), e.g. /camera/aligned_depth_to_color/image_raw");
  command->add_option("--camera-info-topic", options.topics.camera_info,
                      "sensor_msgs/CameraInfo topic (default: beside the colour image)");
  command->add_option("--camera-yaml", options.camera_yaml,
                      "camera.yaml with the camera's intrinsics, mounting and max_range, used "
                      "instead of camera_info and tf (a bag with an uncalibrated camera_info, "
                      "or no tf of the camera)");
  command->add_flag(
      "--no-camera", [args](std::int64_t) { args->options.import_camera = false; },
      "Import the scans, odometry and truth only (no frames, no camera.yaml)");
  command
      ->add_option("--detections-topic", options.topics.detections,
                   "std_msgs/String topic of detections.jsonl records")
      ->capture_default_str();
  command
      ->add_option("--max-pair-gap", options.max_pair_gap_s,
                   "Seconds within which a depth image pairs with a colour image, and "
                   "detections with a frame")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--camera-max-range", args->camera_max_range,
                   "camera.yaml max_range in metres (default: from the bag's run info, else the "
                   "deepest depth reading)")
      ->check(CLI::PositiveNumber);
  command->callback([args, &exit_code] {
    if (args->camera_max_range > 0.0) args->options.camera_max_range = args->camera_max_range;
    const Result<ros1::BagImportSummary> summary =
        ros1::ImportBagToRun(args->bag, args->out, args->options);
    if (!summary.ok()) {
      exit_code = ReportError(summary.status());
      return;
    }
    PrintWarnings(summary->warnings);
    std::printf(
        "wrote %s: %zu scans (odometry from %s), %zu camera frames, %zu detection "
        "records, %zu truth poses\n",
        args->out.c_str(), summary->scans, summary->odometry.c_str(), summary->frames,
        summary->detection_records, summary->truth_poses);
    exit_code = 0;
  });
}

}  // namespace

void AddBagCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand("bag", "Convert between run directories and ROS 1 bags");
  command->require_subcommand(1);
  AddExport(*command, exit_code);
  AddImport(*command, exit_code);
}

}  // namespace semchain::app
