// Bag-of-words speed (DESIGN.md §6; seed 000 §3.1): one query over 10 000 keyframes, training
// a k = 10, L = 4 vocabulary on the frames of a mapping run, describing an image (ORB, then the
// TF-IDF transform). The frames come from a simulated mapping run of two_similar_rooms (seed 1,
// 320 frames); the 10 000 keyframes are synthesized from them: keyframe i is a seeded random
// 80 % of frame (i mod 320)'s descriptors, so their words are distributed as real ones.
//   build/bench/bow_bench
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <random>
#include <vector>

#include "bow/bow_database.h"
#include "bow/bow_vocabulary.h"
#include "bow/run_features.h"
#include "core/rng.h"
#include "io/rgbd_frame_io.h"
#include "sim/simulator.h"
#include "sim/world_io.h"

namespace semchain::bow {
namespace {

namespace fs = std::filesystem;

// The mapping run's frames, simulated once per process.
struct BenchData {
  fs::path run;
  std::vector<fs::path> images;
  std::vector<cv::Mat> descriptors;
  Vocabulary vocabulary;
};

const BenchData& Data() {
  static const BenchData data = [] {
    BenchData d;
    d.run = fs::temp_directory_path() / ("semchain_bow_bench_" + std::to_string(::getpid()));
    const auto world =
        sim::LoadWorld(fs::path(SEMCHAIN_SOURCE_DIR) / "worlds" / "two_similar_rooms.yaml");
    if (!world.ok()) std::abort();
    sim::SimulationOptions options;
    options.seed = 1;
    options.show_progress = false;
    if (!sim::Simulate(*world, options, d.run).ok()) std::abort();
    auto images = ListColorFrames(d.run);
    if (!images.ok()) std::abort();
    d.images = *images;
    auto descriptors = ExtractImageDescriptors(d.images, OrbOptions());
    if (!descriptors.ok()) std::abort();
    d.descriptors = *descriptors;
    VocabularyOptions vocabulary;
    vocabulary.seed = 1;
    auto trained = Vocabulary::Train(d.descriptors, vocabulary);
    if (!trained.ok()) std::abort();
    d.vocabulary = *trained;
    std::atexit([] { fs::remove_all(Data().run); });
    return d;
  }();
  return data;
}

void BM_TrainVocabulary(benchmark::State& state) {
  const BenchData& data = Data();
  VocabularyOptions options;
  options.branching = static_cast<int>(state.range(0));
  options.levels = static_cast<int>(state.range(1));
  options.seed = 1;
  std::size_t descriptors = 0;
  for (const cv::Mat& d : data.descriptors) descriptors += static_cast<std::size_t>(d.rows);
  int words = 0;
  for (auto _ : state) {
    auto vocabulary = Vocabulary::Train(data.descriptors, options);
    words = vocabulary->words();
  }
  state.counters["images"] = static_cast<double>(data.descriptors.size());
  state.counters["descriptors"] = static_cast<double>(descriptors);
  state.counters["words"] = words;
}
BENCHMARK(BM_TrainVocabulary)
    ->Args({10, 4})
    ->Args({10, 3})
    ->Unit(benchmark::kSecond)
    ->Iterations(2);

// One top-1 query (Arg: 10 000 keyframes), cycling through the real frames as queries.
void BM_QueryKeyframes(benchmark::State& state) {
  const BenchData& data = Data();
  const int keyframes = static_cast<int>(state.range(0));
  BowDatabase database(data.vocabulary.words(), 2);
  Rng rng = MakeRng(1, 7);
  for (int i = 0; i < keyframes; ++i) {
    const cv::Mat& frame = data.descriptors[static_cast<std::size_t>(i) % data.descriptors.size()];
    std::vector<int> rows(static_cast<std::size_t>(frame.rows));
    std::iota(rows.begin(), rows.end(), 0);
    std::shuffle(rows.begin(), rows.end(), rng);
    cv::Mat subset;
    for (std::size_t r = 0; r < rows.size() * 4 / 5; ++r) subset.push_back(frame.row(rows[r]));
    FeatureVector features;
    BowVector vector = data.vocabulary.Transform(subset, 2, &features);
    database.Add(std::move(vector), std::move(features));
  }
  std::vector<BowVector> queries;
  for (const cv::Mat& d : data.descriptors) queries.push_back(data.vocabulary.Transform(d));
  std::size_t q = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(database.Query(queries[q], 1));
    q = (q + 1) % queries.size();
  }
  state.counters["keyframes"] = keyframes;
}
BENCHMARK(BM_QueryKeyframes)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

// Describing one frame: its ~450 descriptors to a TF-IDF vector (k = 10, L = 4).
void BM_TransformImage(benchmark::State& state) {
  const BenchData& data = Data();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(data.vocabulary.Transform(data.descriptors[i]));
    i = (i + 1) % data.descriptors.size();
  }
}
BENCHMARK(BM_TransformImage)->Unit(benchmark::kMicrosecond);

// ORB on one 320 × 240 frame (OpenCV).
void BM_OrbDescriptors(benchmark::State& state) {
  const BenchData& data = Data();
  std::vector<cv::Mat> images;
  for (std::size_t i = 0; i < 20; ++i) images.push_back(*ReadColorImage(data.images[i * 10]));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ExtractOrbDescriptors(images[i], OrbOptions()));
    i = (i + 1) % images.size();
  }
}
BENCHMARK(BM_OrbDescriptors)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace semchain::bow

BENCHMARK_MAIN();
