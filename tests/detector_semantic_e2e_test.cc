// `semchain semantic --detector` end to end: the tiny YOLOv8-format test model runs on
// the rendered frames of a room with pure red, green and blue boxes, and its detections (depth
// from the depth frames) build the semantic map as the simulator's detections would.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "detection/run_detection.h"
#include "detection/yolo_detector.h"
#include "io/carmen.h"
#include "mapping/map_io.h"
#include "mapping/slam_pipeline.h"
#include "semantic/semantic_run.h"
#include "sim/simulator.h"
#include "sim/world_io.h"

namespace semchain {
namespace {

namespace fs = std::filesystem;

TEST(DetectorSemanticTest, TinyModelDetectionsMapTheColouredBoxes) {
  const fs::path run =
      fs::temp_directory_path() / ("semchain_detector_semantic_" + std::to_string(::getpid()));
  fs::remove_all(run);
  const fs::path source(SEMCHAIN_SOURCE_DIR);
  const Result<sim::World> world = sim::LoadWorld(source / "tests/data/coloured_boxes.yaml");
  ASSERT_TRUE(world.ok()) << world.status().message();
  sim::SimulationOptions simulation;
  simulation.seed = 2;
  simulation.show_progress = false;
  ASSERT_TRUE(sim::Simulate(*world, simulation, run).ok());

  const Result<carmen::Log> log = carmen::ReadLog(run / "log.clf");
  ASSERT_TRUE(log.ok());
  const auto scans = mapping::ScansFromLog(*log, "log.clf");
  ASSERT_TRUE(scans.ok());
  mapping::SlamOptions slam_options;
  slam_options.rbpf.seed = 2;
  const mapping::SlamResult slam = mapping::RunSlam(*scans, slam_options);

  detection::YoloOptions yolo;
  yolo.input_width = 320;
  yolo.input_height = 256;
  auto detector = detection::LoadYoloDetector(
      source / "src/detection/testdata/tiny_squares_raw.onnx", {}, yolo);
  ASSERT_TRUE(detector.ok()) << detector.status().message();
  const Result<std::vector<FrameDetections>> detections =
      detection::DetectRunFrames(**detector, run);
  ASSERT_TRUE(detections.ok()) << detections.status().message();

  semantic::SemanticRunInputs inputs;
  inputs.run_dir = run;
  inputs.occupancy = mapping::GridToMapImage(slam.map);
  inputs.trajectory = slam.trajectory;
  inputs.detections = *detections;
  const Result<semantic::SemanticMappingResult> result =
      semantic::MapRun(inputs, semantic::SemanticMapOptions());
  fs::remove_all(run);
  ASSERT_TRUE(result.ok()) << result.status().message();

  // One object per box, of its colour, where the box stands.
  const auto& objects = result->map.objects;
  ASSERT_EQ(objects.size(), world->objects.size());
  for (const sim::Solid& box : world->objects) {
    const auto found = std::find_if(objects.begin(), objects.end(), [&box](const auto& object) {
      return object.class_name == box.class_name;
    });
    ASSERT_NE(found, objects.end()) << box.class_name << " not mapped";
    EXPECT_LT((found->center - box.footprint.center).norm(), 0.12) << box.class_name;
    // Once: no second object of its class on or near it.
    const double reach = std::max(0.3, 0.5 * std::hypot(box.footprint.width, box.footprint.depth));
    EXPECT_EQ(std::count_if(objects.begin(), objects.end(),
                            [&box, reach](const auto& object) {
                              return object.class_name == box.class_name &&
                                     (object.center - box.footprint.center).norm() <= reach;
                            }),
              1)
        << box.class_name << " mapped more than once";
  }
}

}  // namespace
}  // namespace semchain
