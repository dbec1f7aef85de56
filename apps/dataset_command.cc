// semchain dataset --out DIR --images N --seed S [--size WxH] [--images-per-room K] [--threads T]
//                  [--borrowed-footprints F] [--desk-clocks F] [--world W.yaml]
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "apps/command.h"
#include "core/progress_bar.h"
#include "sensors/detection.h"
#include "sim/detector_dataset.h"

namespace semchain::app {
namespace {

struct DatasetArgs {
  std::string out;
  int images = 0;
  std::uint64_t seed = 0;
  std::string size = "320x256";
  int images_per_room = 10;
  int threads = 2;
  double borrowed_footprints = 0.0;
  double desk_clocks = 0.0;
  std::string world;  // views of this world, not random rooms
};

Status ParseSize(const std::string& text, int* width, int* height) {
  char extra = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", width, height, &extra) != 2) {
    return Status::Error("--size: expected WIDTHxHEIGHT (e.g. 320x256), got '" + text + "'");
  }
  return Status::Ok();
}

Status RunDataset(const DatasetArgs& args) {
  sim::DatasetOptions options;
  options.images = args.images;
  options.seed = args.seed;
  options.images_per_room = args.images_per_room;
  options.threads = args.threads;
  options.borrowed_footprint_fraction = args.borrowed_footprints;
  options.desk_clock_fraction = args.desk_clocks;
  if (!args.world.empty()) {
    Result<sim::World> world = sim::LoadWorld(args.world);
    if (!world.ok()) return world.status();
    options.world = std::move(*world);
  }
  SEMCHAIN_RETURN_IF_ERROR(ParseSize(args.size, &options.width, &options.height));
  SEMCHAIN_RETURN_IF_ERROR(options.Validate());
  ProgressBar bar("dataset", static_cast<std::size_t>(options.images));
  Result<sim::DatasetSummary> summary = sim::WriteDetectorDataset(
      args.out, options, [&bar](int done) { bar.Update(static_cast<std::size_t>(done)); });
  if (!summary.ok()) return summary.status();
  bar.Finish();
  std::printf("wrote %s: %d / %d / %d images (train / val / test) from %d / %d / %d rooms\n",
              args.out.c_str(), summary->images[0], summary->images[1], summary->images[2],
              summary->rooms[0], summary->rooms[1], summary->rooms[2]);
  std::printf("%-10s %7s %7s %7s\n", "class", "train", "val", "test");
  for (std::size_t c = 0; c < summary->instances.size(); ++c) {
    std::printf("%-10s %7d %7d %7d\n", DefaultClassNames()[c].c_str(), summary->instances[c][0],
                summary->instances[c][1], summary->instances[c][2]);
  }
  return Status::Ok();
}

}  // namespace

void AddDatasetCommand(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand(
      "dataset",
      "Render randomized furnished rooms into a YOLO-format detector data set (DESIGN.md "
      "section 5.6): images/{train,val,test}/*.png, labels/{train,val,test}/*.txt "
      "('class cx cy w h', normalised), data.yaml; splits from disjoint rooms");
  auto args = std::make_shared<DatasetArgs>();
  command->add_option("--out", args->out, "Data set directory to write (replaces an earlier one)")
      ->required();
  command->add_option("--images", args->images, "Number of images (at least 1)")->required();
  command
      ->add_option("--seed", args->seed,
                   "Seed of the rooms and views; the same seed gives "
                   "the same bytes")
      ->capture_default_str();
  command->add_option("--size", args->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  command
      ->add_option("--images-per-room", args->images_per_room,
                   "Frames taken in each random room (rooms go wholly to one split)")
      ->capture_default_str();
  command
      ->add_option("--threads", args->threads,
                   "Rendering threads (the output does not "
                   "depend on them)")
      ->capture_default_str();
  command
      ->add_option("--borrowed-footprints", args->borrowed_footprints,
                   "Share (0..1) of furniture given the footprint size of another class of its "
                   "size group (a sofa the size of a bed, a cabinet the size of a table), so that "
                   "a detector cannot name objects by their size")
      ->capture_default_str();
  command
      ->add_option("--desk-clocks", args->desk_clocks,
                   "Share (0..1) of clocks that stand on a table as desk clocks instead of "
                   "hanging on a wall")
      ->capture_default_str();
  command->add_option("--world", args->world,
                      "Views of this world (YAML) instead of random rooms, all in the test split: "
                      "how a detector does on its furniture (semchain bench detector --split "
                      "test)");
  command->callback([args, &exit_code] {
    const Status status = RunDataset(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

}  // namespace semchain::app
