#include "sim/detector_dataset.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "core/atomic_file.h"
#include "sensors/detection.h"
#include "sim/detection_model.h"
#include "sim/random_room.h"
#include "sim/run_directory.h"
#include "sim/scene.h"
#include "sim/texture.h"

namespace semchain::sim {
namespace fs = std::filesystem;
namespace {

constexpr Split kSplits[] = {Split::kTrain, Split::kVal, Split::kTest};

std::uint64_t Derive(std::uint64_t seed, std::int64_t a, std::int64_t b) {
  return static_cast<std::uint64_t>(HashToUnit(seed, a, b) * 0x1.0p53);
}

std::string ImageStem(int room, int k) {
  char stem[32];
  std::snprintf(stem, sizeof(stem), "r%05d_%02d", room, k);
  return stem;
}

// The object a frame is aimed at: one of the class whose turn it is (classes take turns over
// the frames, so that each is as frequent as the others), else any.
int TargetObject(const World& world, int image_index, std::uint64_t seed) {
  const auto classes = static_cast<int>(world.classes.size());
  const std::string& wanted = world.classes[image_index % classes];
  std::vector<int> candidates;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    if (world.objects[i].class_name == wanted) candidates.push_back(static_cast<int>(i));
  }
  if (candidates.empty()) {
    for (std::size_t i = 0; i < world.objects.size(); ++i)
      candidates.push_back(static_cast<int>(i));
  }
  const double pick = HashToUnit(seed, image_index, 0x7a);
  return candidates[std::min(
      candidates.size() - 1,
      static_cast<std::size_t>(pick * static_cast<double>(candidates.size())))];
}

struct RoomOutput {
  Split split = Split::kTrain;
  int images = 0;
  std::vector<int> instances;  // per class
};

class DatasetWriter {
 public:
  DatasetWriter(const fs::path& staging, const DatasetOptions& options)
      : staging_(staging), options_(options) {}

  Result<RoomOutput> WriteRoom(int room) const {
    RandomRoomOptions room_options;
    room_options.borrowed_footprint_fraction = options_.borrowed_footprint_fraction;
    room_options.desk_clock_fraction = options_.desk_clock_fraction;
    std::optional<World> random_room;
    if (!options_.world) random_room = RandomRoom(Derive(options_.seed, room, 1), room_options);
    const World& world = options_.world ? *options_.world : *random_room;
    RoomOutput output;
    output.split = SplitOfRoom(room, options_);
    output.instances.assign(DefaultClassNames().size(), 0);
    const Scene scene(world);
    const int first = room * options_.images_per_room;
    const int count = std::min(options_.images_per_room, options_.images - first);
    for (int k = 0; k < count; ++k) {
      const int index = first + k;
      std::optional<CameraView> view;
      for (int attempt = 0; attempt < 8 && !view; ++attempt) {
        const std::uint64_t view_seed = Derive(options_.seed, index, 2 + attempt);
        view = RandomCameraView(world, TargetObject(world, index + attempt, options_.seed),
                                options_.width, options_.height, view_seed);
      }
      if (!view) {
        // A given world's views are placed inside its first wall line, as a room's are.
        if (options_.world) {
          return Status::Error("--world " + world.name +
                               ": no free spot inside its outer wall to take image " +
                               std::to_string(index) + " from");
        }
        return Status::Error("room " + std::to_string(room) + ": no free spot to take frame " +
                             std::to_string(k) + " from");
      }
      const MountedCamera camera = MakeMountedCamera(view->camera);
      RenderOptions render = MakeRenderOptions(view->camera, Derive(options_.seed, index, 99));
      render.count_unoccluded = true;
      const RgbdImage image = RenderRgbd(scene, camera, view->robot_pose, render);
      const std::vector<TruthBox> boxes =
          TruthBoxes(world, image, options_.min_visible_fraction, options_.min_box_pixels);
      std::string labels;
      for (const TruthBox& box : boxes) {
        labels += LabelLine(box, options_.width, options_.height) + "\n";
        ++output.instances[box.class_id];
      }
      const std::string split = SplitName(output.split);
      const std::string stem = ImageStem(room, k);
      cv::Mat bgr;
      cv::cvtColor(image.rgb, bgr, cv::COLOR_RGB2BGR);
      std::vector<unsigned char> png;
      // Fixed compression so that the same image always gives the same bytes.
      if (!cv::imencode(".png", bgr, png, {cv::IMWRITE_PNG_COMPRESSION, 3})) {
        return Status::Error(stem + ": cannot encode PNG");
      }
      SEMCHAIN_RETURN_IF_ERROR(WriteFileAtomically(
          staging_ / "images" / split / (stem + ".png"),
          std::string_view(reinterpret_cast<const char*>(png.data()), png.size())));
      SEMCHAIN_RETURN_IF_ERROR(
          WriteFileAtomically(staging_ / "labels" / split / (stem + ".txt"), labels));
      ++output.images;
    }
    return output;
  }

 private:
  fs::path staging_;
  const DatasetOptions& options_;
};

std::string DataYaml(const fs::path& out) {
  std::string names;
  for (const std::string& name : DefaultClassNames()) names += (names.empty() ? "" : ", ") + name;
  return "# semchain dataset: YOLO detection data set (images/<split>/*.png, "
         "labels/<split>/*.txt)\n"
         "path: " +
         fs::absolute(out).lexically_normal().string() + "\n" +
         "train: images/train\nval: images/val\ntest: images/test\n" +
         "nc: " + std::to_string(DefaultClassNames().size()) + "\n" + "names: [" + names + "]\n";
}

std::string SummaryJson(const DatasetSummary& summary, const DatasetOptions& options) {
  nlohmann::ordered_json json;
  json["seed"] = options.seed;
  json["size"] = {options.width, options.height};
  json["borrowed_footprint_fraction"] = options.borrowed_footprint_fraction;
  json["desk_clock_fraction"] = options.desk_clock_fraction;
  if (options.world) json["world"] = options.world->name;
  for (const Split split : kSplits) {
    const int s = static_cast<int>(split);
    nlohmann::ordered_json& entry = json[SplitName(split)];
    entry["rooms"] = summary.rooms[s];
    entry["images"] = summary.images[s];
    for (std::size_t c = 0; c < summary.instances.size(); ++c) {
      entry["instances"][DefaultClassNames()[c]] = summary.instances[c][s];
    }
  }
  return json.dump(2) + "\n";
}

}  // namespace

Status DatasetOptions::Validate() const {
  if (images < 1)
    return Status::Error("--images must be at least 1, got " + std::to_string(images));
  if (images > 10'000'000) return Status::Error("--images: at most 10000000");
  if (width < 32 || height < 32 || width > 4096 || height > 4096) {
    return Status::Error("--size: each side must be 32..4096 pixels, got " + std::to_string(width) +
                         "x" + std::to_string(height));
  }
  if (images_per_room < 1) return Status::Error("--images-per-room must be at least 1");
  if (threads < 1 || threads > 256) return Status::Error("--threads must be 1..256");
  if (!(borrowed_footprint_fraction >= 0.0 && borrowed_footprint_fraction <= 1.0)) {
    return Status::Error("--borrowed-footprints must be 0..1, got " +
                         std::to_string(borrowed_footprint_fraction));
  }
  if (!(desk_clock_fraction >= 0.0 && desk_clock_fraction <= 1.0)) {
    return Status::Error("--desk-clocks must be 0..1, got " + std::to_string(desk_clock_fraction));
  }
  if (world) {
    const std::vector<std::string>& all = DefaultClassNames();
    const std::vector<std::string>& own = world->classes.empty() ? all : world->classes;
    if (own.size() > all.size() || !std::equal(own.begin(), own.end(), all.begin())) {
      return Status::Error("--world " + world->name +
                           ": its classes must be the first of the ten (door, cabinet, bucket, "
                           "chair, stool, table, sofa, computer, bed, clock), in that order");
    }
    if (world->objects.empty()) return Status::Error("--world " + world->name + ": no objects");
  }
  if (val_rooms_in_ten < 0 || test_rooms_in_ten < 0 || val_rooms_in_ten + test_rooms_in_ten > 9) {
    return Status::Error("val and test rooms must leave training rooms (at most 9 in 10)");
  }
  return Status::Ok();
}

std::vector<TruthBox> TruthBoxes(const World& world, const RgbdImage& image,
                                 double min_visible_fraction, int min_box_pixels) {
  std::vector<TruthBox> boxes;
  const std::vector<std::string>& classes =
      world.classes.empty() ? DefaultClassNames() : world.classes;
  const std::vector<ObjectVisibility> views = MeasureVisibility(image, world);
  for (std::size_t i = 0; i < views.size(); ++i) {
    const ObjectVisibility& view = views[i];
    if (view.pixels == 0) continue;
    const int w = view.u_max - view.u_min + 1, h = view.v_max - view.v_min + 1;
    if (view.VisibleFraction() < min_visible_fraction || std::min(w, h) < min_box_pixels) continue;
    const auto it = std::find(classes.begin(), classes.end(), world.objects[i].class_name);
    if (it == classes.end()) continue;
    TruthBox box;
    box.class_id = static_cast<int>(it - classes.begin());
    box.box[0] = view.u_min, box.box[1] = view.v_min;
    box.box[2] = view.u_max + 1.0, box.box[3] = view.v_max + 1.0;
    boxes.push_back(box);
  }
  return boxes;
}

std::string LabelLine(const TruthBox& box, int width, int height) {
  char line[96];
  std::snprintf(line, sizeof(line), "%d %.6f %.6f %.6f %.6f", box.class_id,
                0.5 * (box.box[0] + box.box[2]) / width, 0.5 * (box.box[1] + box.box[3]) / height,
                (box.box[2] - box.box[0]) / width, (box.box[3] - box.box[1]) / height);
  return line;
}

const char* SplitName(Split split) {
  switch (split) {
    case Split::kVal:
      return "val";
    case Split::kTest:
      return "test";
    default:
      return "train";
  }
}

Split SplitOfRoom(int room, const DatasetOptions& options) {
  if (options.world) return Split::kTest;
  const int slot = room % 10;
  if (slot < options.test_rooms_in_ten) return Split::kTest;
  if (slot < options.test_rooms_in_ten + options.val_rooms_in_ten) return Split::kVal;
  return Split::kTrain;
}

Result<DatasetSummary> WriteDetectorDataset(const fs::path& out, const DatasetOptions& options,
                                            const std::function<void(int)>& progress) {
  SEMCHAIN_RETURN_IF_ERROR(options.Validate());
  Result<fs::path> staging = BeginRunDirectory(out, "data.yaml");
  if (!staging.ok()) return staging.status();
  for (const char* kind : {"images", "labels"}) {
    for (const Split split : kSplits) {
      SEMCHAIN_RETURN_IF_ERROR(EnsureWritableDirectory(*staging / kind / SplitName(split)));
    }
  }
  const int rooms = (options.images + options.images_per_room - 1) / options.images_per_room;
  DatasetSummary summary;
  summary.instances.assign(DefaultClassNames().size(), {0, 0, 0});
  const DatasetWriter writer(*staging, options);
  std::atomic<int> next_room{0};
  std::mutex mutex;
  Status failure = Status::Ok();
  int done = 0;
  const auto work = [&] {
    for (int room = next_room++; room < rooms; room = next_room++) {
      Result<RoomOutput> output = writer.WriteRoom(room);
      const std::lock_guard<std::mutex> lock(mutex);
      if (!output.ok()) {
        if (failure.ok()) failure = output.status();
        next_room = rooms;  // stop the others
        return;
      }
      const int s = static_cast<int>(output->split);
      summary.images[s] += output->images;
      ++summary.rooms[s];
      for (std::size_t c = 0; c < output->instances.size(); ++c) {
        summary.instances[c][s] += output->instances[c];
      }
      done += output->images;
      if (progress) progress(done);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < std::min(options.threads, rooms); ++t) threads.emplace_back(work);
  work();
  for (std::thread& thread : threads) thread.join();
  if (failure.ok()) failure = WriteFileAtomically(*staging / "data.yaml", DataYaml(out));
  if (failure.ok())
    failure = WriteFileAtomically(*staging / "summary.json", SummaryJson(summary, options));
  if (failure.ok()) failure = FinishRunDirectory(*staging, out);
  if (!failure.ok()) {
    AbandonRunDirectory(*staging);
    return failure;
  }
  return summary;
}

}  // namespace semchain::sim
