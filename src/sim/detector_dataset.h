#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "sim/rgbd_renderer.h"
#include "sim/world.h"

// The detector's training set (DESIGN.md §5.6, semchain dataset): frames of randomized
// furnished rooms (random_room.h) in the layout ultralytics users know,
//   images/{train,val,test}/*.png, labels/{train,val,test}/*.txt, data.yaml,
// one label line per object that shows enough of itself: "class cx cy w h", normalised to the
// image, the box bounding the object's visible pixels. Splits come from disjoint rooms.
namespace semchain::sim {

struct DatasetOptions {
  int images = 4000;
  std::uint64_t seed = 0;
  int width = 320;  // pixels
  int height = 256;
  int images_per_room = 10;
  // Rooms are dealt to the splits in this ratio (train : val : test), every tenth room first
  // to test, the next to val, so that each split draws from rooms of the whole seed range.
  int val_rooms_in_ten = 1;
  int test_rooms_in_ten = 1;
  int threads = 2;
  // An object is labelled when this much of its unoccluded silhouette shows and its box spans
  // this many pixels both ways: the detection model's defaults (DetectionModelSpec).
  double min_visible_fraction = 0.3;
  int min_box_pixels = 12;
  // RandomRoomOptions::borrowed_footprint_fraction of the rooms (0..1): objects whose size does
  // not tell their class.
  double borrowed_footprint_fraction = 0.0;
  // RandomRoomOptions::desk_clock_fraction of the rooms (0..1): clocks on tables.
  double desk_clock_fraction = 0.0;
  // Views of this world instead of random rooms, every image in the test split: how a detector
  // does on a world's own furniture (`bench detector`). Its classes must be the first of
  // DefaultClassNames(), in that order, so that label ids are the data set's. Groups of
  // images_per_room views count as its rooms.
  std::optional<World> world;

  Status Validate() const;
};

// One labelled object: its class index and its box in pixel-edge coordinates [x1, x2) × [y1, y2).
struct TruthBox {
  int class_id = 0;
  double box[4] = {0.0, 0.0, 0.0, 0.0};
};

// The truth boxes of a frame of 'world' rendered with 'image' (object ids and
// RenderOptions::count_unoccluded), by the rule of DatasetOptions.
std::vector<TruthBox> TruthBoxes(const World& world, const RgbdImage& image,
                                 double min_visible_fraction, int min_box_pixels);

// A YOLO label line of 'box' in a width × height image: "class cx cy w h", normalised.
std::string LabelLine(const TruthBox& box, int width, int height);

enum class Split { kTrain, kVal, kTest };
const char* SplitName(Split split);
Split SplitOfRoom(int room, const DatasetOptions& options);

struct DatasetSummary {
  int images[3] = {0, 0, 0};  // per Split
  int rooms[3] = {0, 0, 0};
  std::vector<std::array<int, 3>> instances;  // per class, per Split
};

// Renders the data set into 'out' (replacing an earlier data set there, atomically: a killed
// run leaves the earlier one or nothing). 'progress' is called with the images done so far.
// The same options give byte-identical files whatever the thread count.
Result<DatasetSummary> WriteDetectorDataset(const std::filesystem::path& out,
                                            const DatasetOptions& options,
                                            const std::function<void(int)>& progress = {});

}  // namespace semchain::sim
