#include "sim/detector_dataset.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/atomic_file.h"
#include "io/yolo_labels.h"
#include "sensors/detection.h"
#include "sim/detection_model.h"
#include "sim/random_room.h"
#include "sim/scene.h"

namespace semchain::sim {
namespace {
namespace fs = std::filesystem;

fs::path TempPath(const std::string& name) {
  const fs::path path = fs::path(testing::TempDir()) / name;
  fs::remove_all(path);
  return path;
}

// Every file under 'dir' with its bytes, by relative path.
std::map<std::string, std::string> Snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    files[fs::relative(entry.path(), dir).string()] = *ReadFile(entry.path());
  }
  return files;
}

DatasetOptions SmallSet(int threads) {
  DatasetOptions options;
  options.images = 24;
  options.images_per_room = 2;
  options.seed = 17;
  options.width = 160;
  options.height = 128;
  options.threads = threads;
  return options;
}

TEST(RandomRoomTest, HoldsEveryClassAndPassesValidation) {
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const World world = RandomRoom(seed);
    std::set<std::string> classes;
    for (const Solid& solid : world.objects) {
      classes.insert(solid.class_name);
      EXPECT_EQ(solid.shape, ObjectShape::kParts);
      EXPECT_FALSE(solid.parts.empty());
    }
    EXPECT_GE(classes.size(), 9u) << "seed " << seed;
    EXPECT_TRUE(classes.count("door") && classes.count("computer") && classes.count("clock"))
        << "seed " << seed;
  }
}

bool WithinRange(double width, double depth, const ClassSizeRange& range) {
  constexpr double kSlack = 1e-9;
  return width >= range.width_min - kSlack && width <= range.width_max + kSlack &&
         depth >= range.depth_min - kSlack && depth <= range.depth_max + kSlack;
}

// Footprint sizes along the solid's own axes (a round one: its diameter both ways).
std::pair<double, double> FootprintSize(const Solid& solid) {
  if (solid.footprint.shape == Footprint::Shape::kCircle) {
    return {2.0 * solid.footprint.radius, 2.0 * solid.footprint.radius};
  }
  return {solid.footprint.width, solid.footprint.depth};
}

// With every footprint borrowed, furniture takes the sizes of the other classes of its size
// group (a sofa as deep as a bed), never of a class outside it, and keeps its own height.
TEST(RandomRoomTest, BorrowedFootprintsComeFromTheSizeGroup) {
  RandomRoomOptions options;
  options.borrowed_footprint_fraction = 1.0;
  int outside_own_range = 0, furniture = 0;
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    for (const Solid& solid : RandomRoom(seed, options).objects) {
      const std::vector<std::string> donors = FootprintDonors(solid.class_name);
      if (donors.empty() || solid.footprint.shape == Footprint::Shape::kCircle) continue;
      ++furniture;
      const auto [width, depth] = FootprintSize(solid);
      const ClassSizeRange own = SizeRangeOf(solid.class_name);
      EXPECT_GE(solid.height, own.height_min - 1e-9) << solid.class_name;
      EXPECT_LE(solid.height, own.height_max + 1e-9) << solid.class_name;
      bool from_a_donor = false;
      for (const std::string& donor : donors) {
        from_a_donor = from_a_donor || WithinRange(width, depth, SizeRangeOf(donor));
      }
      EXPECT_TRUE(from_a_donor) << solid.class_name << " " << width << " x " << depth;
      if (!WithinRange(width, depth, own)) ++outside_own_range;
    }
  }
  EXPECT_GT(furniture, 100);
  EXPECT_GT(outside_own_range, furniture / 3);
  EXPECT_TRUE(FootprintDonors("door").empty());
  EXPECT_TRUE(FootprintDonors("computer").empty());
  EXPECT_EQ(FootprintDonors("sofa"), (std::vector<std::string>{"cabinet", "table", "bed"}));
  EXPECT_EQ(FootprintDonors("cabinet"),
            (std::vector<std::string>{"bucket", "chair", "stool", "table", "sofa", "bed"}));
}

// Without borrowing, every piece of furniture keeps to its class's own footprint range.
TEST(RandomRoomTest, ByDefaultFurnitureKeepsItsOwnSizes) {
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    for (const Solid& solid : RandomRoom(seed).objects) {
      if (FootprintDonors(solid.class_name).empty()) continue;
      if (solid.footprint.shape == Footprint::Shape::kCircle) continue;
      const auto [width, depth] = FootprintSize(solid);
      EXPECT_TRUE(WithinRange(width, depth, SizeRangeOf(solid.class_name)))
          << solid.class_name << " " << width << " x " << depth;
    }
  }
}

// With every clock asked for on a desk, clocks stand on the tables' tops, within their
// footprints and clear of the computers; rooms keep the same walls and furniture as without.
TEST(RandomRoomTest, DeskClocksStandOnTablesClearOfComputers) {
  RandomRoomOptions options;
  options.desk_clock_fraction = 1.0;
  int on_desks = 0, on_walls = 0;
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    const World world = RandomRoom(seed, options);
    std::vector<const Solid*> tables, computers;
    for (const Solid& solid : world.objects) {
      if (solid.class_name == "table") tables.push_back(&solid);
      if (solid.class_name == "computer") computers.push_back(&solid);
    }
    for (const Solid& clock : world.objects) {
      if (clock.class_name != "clock") continue;
      const ClassSizeRange wall = SizeRangeOf("clock");
      if (clock.base_height >= wall.base_min - 1e-9) {
        ++on_walls;
        continue;
      }
      ++on_desks;
      const ClassSizeRange desk = DeskClockSizeRange();
      EXPECT_LE(clock.footprint.depth, desk.depth_max + 1e-9);
      EXPECT_GE(clock.height, desk.height_min - 1e-9);
      const auto under = std::find_if(tables.begin(), tables.end(), [&](const Solid* table) {
        return std::abs(table->base_height + table->height - clock.base_height) < 1e-9 &&
               FootprintContains(table->footprint, clock.footprint.center);
      });
      ASSERT_NE(under, tables.end()) << "seed " << seed << ": a desk clock on no table";
      // Both face the table's edges, so in the table's frame they are boxes along its axes.
      const double yaw = (*under)->footprint.yaw;
      const Eigen::Vector2d along(std::cos(yaw), std::sin(yaw)), across(-along.y(), along.x());
      for (const Solid* computer : computers) {
        const Eigen::Vector2d d = computer->footprint.center - clock.footprint.center;
        const bool apart =
            std::abs(d.dot(along)) >= 0.5 * (clock.footprint.width + computer->footprint.width) ||
            std::abs(d.dot(across)) >= 0.5 * (clock.footprint.depth + computer->footprint.depth);
        EXPECT_TRUE(apart) << "seed " << seed << ": a desk clock inside a computer";
      }
    }
    // What is placed before the clocks (walls, doors, the large pieces, the tables) is drawn
    // as without desk clocks.
    const World plain = RandomRoom(seed);
    ASSERT_EQ(plain.walls.size(), world.walls.size());
    for (std::size_t i = 0; i < plain.objects.size() && plain.objects[i].class_name != "clock";
         ++i) {
      ASSERT_LT(i, world.objects.size());
      EXPECT_EQ(plain.objects[i].class_name, world.objects[i].class_name);
      EXPECT_EQ(plain.objects[i].footprint.center, world.objects[i].footprint.center);
    }
  }
  EXPECT_GT(on_desks, 20);
  EXPECT_GT(on_walls, 0);  // rooms whose tables leave no room
}

// The truth box of every labelled object is the bounding box of its rendered pixels, and its
// label line parses back to that box.
TEST(DetectorDatasetTest, TruthBoxesBoundTheRenderedMasksAndLabelsParseBack) {
  int checked = 0;
  for (std::uint64_t seed = 0; seed < 6; ++seed) {
    const World world = RandomRoom(seed);
    const Scene scene(world);
    for (int target = 0; target < static_cast<int>(world.objects.size()); target += 3) {
      const std::optional<CameraView> view =
          RandomCameraView(world, target, 320, 256, seed + target);
      if (!view) continue;
      RenderOptions options = MakeRenderOptions(view->camera, 1);
      options.count_unoccluded = true;
      const RgbdImage image =
          RenderRgbd(scene, MakeMountedCamera(view->camera), view->robot_pose, options);
      const std::vector<TruthBox> boxes = TruthBoxes(world, image, 0.3, 12);
      // Masks, found independently.
      std::map<int, std::array<int, 4>> bounds;  // object -> u0, v0, u1, v1 (inclusive)
      for (int v = 0; v < image.object_ids.rows; ++v) {
        for (int u = 0; u < image.object_ids.cols; ++u) {
          const int id = image.object_ids.at<std::int32_t>(v, u);
          if (id < 0) continue;
          auto [it, fresh] = bounds.try_emplace(id, std::array<int, 4>{u, v, u, v});
          if (!fresh) {
            it->second = {std::min(it->second[0], u), std::min(it->second[1], v),
                          std::max(it->second[2], u), std::max(it->second[3], v)};
          }
        }
      }
      std::string text;
      for (const TruthBox& box : boxes) text += LabelLine(box, 320, 256) + "\n";
      const Result<std::vector<YoloLabel>> parsed = ParseYoloLabels(text, "labels", 10);
      ASSERT_TRUE(parsed.ok()) << parsed.status().message();
      ASSERT_EQ(parsed->size(), boxes.size());
      for (std::size_t i = 0; i < boxes.size(); ++i) {
        // Find the object this box belongs to: same class, same mask bounds.
        bool matched = false;
        for (const auto& [id, b] : bounds) {
          if (DefaultClassNames()[boxes[i].class_id] != world.objects[id].class_name) continue;
          const double mask[4] = {double(b[0]), double(b[1]), b[2] + 1.0, b[3] + 1.0};
          bool same = true;
          for (int k = 0; k < 4; ++k) same = same && std::abs(mask[k] - boxes[i].box[k]) <= 1.0;
          matched = matched || same;
        }
        EXPECT_TRUE(matched) << "box " << i << " bounds no object's mask";
        const std::array<double, 4> back = (*parsed)[i].PixelBox(320, 256);
        for (int k = 0; k < 4; ++k) EXPECT_NEAR(back[k], boxes[i].box[k], 0.5);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 20);
}

TEST(DetectorDatasetTest, SameSeedGivesTheSameBytesWhateverTheThreads) {
  const fs::path out = TempPath("dataset_same");
  ASSERT_TRUE(WriteDetectorDataset(out, SmallSet(1)).ok());
  const auto first = Snapshot(out);
  const Result<DatasetSummary> again = WriteDetectorDataset(out, SmallSet(2));  // replaces it
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(Snapshot(out), first);
  EXPECT_EQ(first.size(), 2u * 24u + 2u);  // images and labels, data.yaml, summary.json
  EXPECT_EQ(again->images[0] + again->images[1] + again->images[2], 24);
}

TEST(DetectorDatasetTest, SplitsComeFromDisjointRooms) {
  const fs::path out = TempPath("dataset_splits");
  const Result<DatasetSummary> summary = WriteDetectorDataset(out, SmallSet(2));
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  std::map<std::string, std::set<std::string>> rooms;  // split -> room prefixes
  for (const char* split : {"train", "val", "test"}) {
    for (const auto& entry : fs::directory_iterator(out / "images" / split)) {
      const std::string stem = entry.path().stem().string();
      rooms[split].insert(stem.substr(0, stem.find('_')));
      EXPECT_TRUE(fs::exists(out / "labels" / split / (stem + ".txt"))) << stem;
      EXPECT_TRUE(ReadYoloLabels(out / "labels" / split / (stem + ".txt"), 10).ok()) << stem;
    }
  }
  EXPECT_FALSE(rooms["train"].empty());
  EXPECT_FALSE(rooms["val"].empty());
  EXPECT_FALSE(rooms["test"].empty());
  for (const std::string& room : rooms["train"]) {
    EXPECT_FALSE(rooms["val"].count(room) || rooms["test"].count(room)) << room;
  }
  for (const std::string& room : rooms["val"]) EXPECT_FALSE(rooms["test"].count(room)) << room;
  const std::string yaml = *ReadFile(out / "data.yaml");
  EXPECT_NE(yaml.find("train: images/train\nval: images/val\ntest: images/test\nnc: 10\n"),
            std::string::npos);
  EXPECT_NE(
      yaml.find("names: [door, cabinet, bucket, chair, stool, table, sofa, computer, bed, clock]"),
      std::string::npos);
}

// Views of a given world: every image in the test split, every label one of that world's
// objects as the renderer shows it.
TEST(DetectorDatasetTest, ViewsOfAGivenWorldGoToTheTestSplit) {
  DatasetOptions options = SmallSet(2);
  options.world = RandomRoom(5);
  const fs::path out = TempPath("dataset_world");
  const Result<DatasetSummary> summary = WriteDetectorDataset(out, options);
  ASSERT_TRUE(summary.ok()) << summary.status().message();
  EXPECT_EQ(summary->images[0] + summary->images[1], 0);
  EXPECT_EQ(summary->images[2], 24);
  EXPECT_TRUE(fs::is_empty(out / "images" / "train"));
  int labelled = 0;
  std::set<int> classes;
  for (const auto& entry : fs::directory_iterator(out / "labels" / "test")) {
    const Result<std::vector<YoloLabel>> labels = ReadYoloLabels(entry.path(), 10);
    ASSERT_TRUE(labels.ok()) << labels.status().message();
    for (const YoloLabel& label : *labels) classes.insert(label.class_id);
    labelled += static_cast<int>(labels->size());
  }
  EXPECT_GT(labelled, 24);
  // The room's objects and nothing else: its classes, most of them seen.
  std::set<int> in_room;
  for (const Solid& solid : options.world->objects) {
    const auto& names = DefaultClassNames();
    in_room.insert(
        static_cast<int>(std::find(names.begin(), names.end(), solid.class_name) - names.begin()));
  }
  for (const int c : classes) EXPECT_TRUE(in_room.count(c)) << "class " << c;
  EXPECT_GE(classes.size(), in_room.size() - 2);
  EXPECT_NE(ReadFile(out / "summary.json")->find("\"world\": \"random_room_5\""),
            std::string::npos);
}

TEST(DetectorDatasetTest, AWorldOfOtherClassesIsAnError) {
  DatasetOptions options = SmallSet(1);
  options.world = RandomRoom(5);
  options.world->classes = {"chair", "door"};
  const fs::path out = TempPath("dataset_world_classes");
  const Result<DatasetSummary> summary = WriteDetectorDataset(out, options);
  ASSERT_FALSE(summary.ok());
  EXPECT_NE(summary.status().message().find("its classes must be the first of the ten"),
            std::string::npos)
      << summary.status().message();
  EXPECT_FALSE(fs::exists(out));
}

TEST(DetectorDatasetTest, BadOptionsWriteNothing) {
  const fs::path out = TempPath("dataset_bad");
  DatasetOptions options = SmallSet(1);
  options.images = 0;
  const Result<DatasetSummary> zero = WriteDetectorDataset(out, options);
  ASSERT_FALSE(zero.ok());
  EXPECT_EQ(zero.status().message(), "--images must be at least 1, got 0");
  EXPECT_FALSE(fs::exists(out));
  options = SmallSet(1);
  options.borrowed_footprint_fraction = 1.5;
  const Result<DatasetSummary> share = WriteDetectorDataset(out, options);
  ASSERT_FALSE(share.ok());
  EXPECT_EQ(share.status().message(), "--borrowed-footprints must be 0..1, got 1.500000");
  EXPECT_FALSE(fs::exists(out));
  options = SmallSet(1);
  options.desk_clock_fraction = -0.1;
  const Result<DatasetSummary> clocks = WriteDetectorDataset(out, options);
  ASSERT_FALSE(clocks.ok());
  EXPECT_EQ(clocks.status().message(), "--desk-clocks must be 0..1, got -0.100000");
  EXPECT_FALSE(fs::exists(out));
  // A directory holding something else is not overwritten.
  fs::create_directories(out);
  { std::ofstream(out / "notes.txt") << "mine"; }
  const Result<DatasetSummary> occupied = WriteDetectorDataset(out, SmallSet(1));
  ASSERT_FALSE(occupied.ok());
  EXPECT_EQ(*ReadFile(out / "notes.txt"), "mine");
}

}  // namespace
}  // namespace semchain::sim
