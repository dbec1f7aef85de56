// semchain vocab train --run RUN [--run RUN2 ...] --out VOCAB.bin [--k K] [--levels L]
//                      [--seed S] [--max-features N]
// semchain vocab query --vocab VOCAB.bin --map MAP --image IMG [--image IMG2 ...] [--top N]
//                      [--run RUN]
// The bag-of-words vocabulary of seed 000 §3.1 step 1 (DESIGN.md §3.7): trained from the ORB
// descriptors of runs' colour frames; `query` ranks MAP/keyframes.json's keyframes by their
// similarity to an image (step 3).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/command.h"
#include "bow/bow_vocabulary_io.h"
#include "bow/keyframe_recognizer.h"
#include "bow/run_features.h"
#include "core/atomic_file.h"
#include "core/progress_bar.h"
#include "io/rgbd_frame_io.h"

namespace semchain::app {
namespace {

namespace fs = std::filesystem;

// A progress callback that opens its bar on the first call.
std::function<void(std::size_t, std::size_t)> BarFor(const std::string& label,
                                                     std::optional<ProgressBar>* bar) {
  return [label, bar](std::size_t done, std::size_t total) {
    if (!*bar) bar->emplace(label, total);
    (*bar)->Update(done);
  };
}

struct TrainArgs {
  std::vector<std::string> runs;
  std::string out;
  bow::VocabularyOptions vocabulary;
  bow::OrbOptions orb;
};

Status RunTrain(const TrainArgs& args) {
  std::string invalid;
  if (!args.vocabulary.Validate(&invalid)) return Status::Error("--k/--levels: " + invalid);
  if (!args.orb.Validate(&invalid)) return Status::Error("--max-features: " + invalid);
  const fs::path out(args.out);
  SEMCHAIN_RETURN_IF_ERROR(
      EnsureWritableDirectory(out.has_parent_path() ? out.parent_path() : "."));
  std::vector<fs::path> images;
  for (const std::string& run : args.runs) {
    Result<std::vector<fs::path>> frames = bow::ListColorFrames(run);
    if (!frames.ok()) return frames.status();
    images.insert(images.end(), frames->begin(), frames->end());
  }
  const auto start = std::chrono::steady_clock::now();
  std::optional<ProgressBar> extract_bar;
  Result<std::vector<cv::Mat>> descriptors =
      bow::ExtractImageDescriptors(images, args.orb, BarFor("ORB features", &extract_bar));
  if (!descriptors.ok()) return descriptors.status();
  if (extract_bar) extract_bar->Finish();
  std::size_t total = 0;
  for (const cv::Mat& d : *descriptors) total += static_cast<std::size_t>(d.rows);
  std::optional<ProgressBar> train_bar;
  Result<bow::Vocabulary> vocabulary = bow::Vocabulary::Train(
      *descriptors, args.vocabulary, BarFor("k-majority vocabulary", &train_bar));
  if (!vocabulary.ok()) return vocabulary.status();
  if (train_bar) train_bar->Finish();
  SEMCHAIN_RETURN_IF_ERROR(bow::WriteVocabulary(out, *vocabulary));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%zu images, %zu ORB descriptors -> %d words (k %d, L %d) in %.1f s; wrote %s\n",
              images.size(), total, vocabulary->words(), args.vocabulary.branching,
              args.vocabulary.levels, seconds, out.string().c_str());
  return Status::Ok();
}

struct QueryArgs {
  std::string vocabulary;
  std::string map;
  std::vector<std::string> images;
  std::string run;
  int top = 5;
};

Status RunQuery(const QueryArgs& args) {
  if (args.top < 1) return Status::Error("--top must be at least 1");
  // The vocabulary first, so that a bad vocabulary file is the error reported.
  Result<bow::Vocabulary> vocabulary = bow::ReadVocabulary(args.vocabulary);
  if (!vocabulary.ok()) return vocabulary.status();
  Result<semantic::KeyframeDatabase> keyframes =
      semantic::ReadKeyframes(fs::path(args.map) / "keyframes.json");
  if (!keyframes.ok()) return keyframes.status();
  std::vector<cv::Mat> queries;
  for (const std::string& image : args.images) {
    Result<cv::Mat> rgb = ReadColorImage(image);
    if (!rgb.ok()) return rgb.status();
    queries.push_back(*rgb);
  }
  std::optional<ProgressBar> bar;
  Result<bow::KeyframeRecognizer> recognizer = bow::KeyframeRecognizer::Build(
      std::move(*vocabulary), std::move(*keyframes), {}, args.run, BarFor("keyframes", &bar));
  if (!recognizer.ok()) return recognizer.status();
  if (bar) bar->Finish();
  for (std::size_t q = 0; q < queries.size(); ++q) {
    std::printf("%s\n", args.images[q].c_str());
    int rank = 0;
    for (const bow::KeyframeMatch& match : recognizer->QueryImage(queries[q], args.top)) {
      const semantic::Keyframe& keyframe = recognizer->keyframe(match.keyframe);
      std::string objects;
      for (const semantic::KeyframeObject& o : keyframe.objects) {
        objects += " " + o.class_name + "#" + std::to_string(o.id);
      }
      std::printf("  %d. %s score %.4f pose %.3f %.3f %.3f objects:%s\n", ++rank,
                  keyframe.frame.c_str(), match.score, keyframe.pose.x, keyframe.pose.y,
                  keyframe.pose.theta, objects.empty() ? " none" : objects.c_str());
    }
    if (rank == 0) std::printf("  no keyframe shares a word with it\n");
  }
  return Status::Ok();
}

void AddTrain(CLI::App& vocab, int& exit_code) {
  CLI::App* command = vocab.add_subcommand(
      "train",
      "Train a k-majority ORB vocabulary (DBoW2-style tree, IDF weights) from runs' frames");
  auto args = std::make_shared<TrainArgs>();
  command->add_option("--run", args->runs, "Run directory with frames/*.png (repeatable)")
      ->required();
  command->add_option("--out", args->out, "Vocabulary file to write")->required();
  command->add_option("--k", args->vocabulary.branching, "Branching factor")->capture_default_str();
  command->add_option("--levels", args->vocabulary.levels, "Depth of the tree")
      ->capture_default_str();
  command->add_option("--seed", args->vocabulary.seed, "Seed of the k-means++ draws")
      ->capture_default_str();
  command->add_option("--max-features", args->orb.max_features, "ORB features per image")
      ->capture_default_str();
  command->callback([args, &exit_code] {
    const Status status = RunTrain(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

void AddQuery(CLI::App& vocab, int& exit_code) {
  CLI::App* command =
      vocab.add_subcommand("query", "Rank a map's keyframes by bag-of-words similarity to images");
  auto args = std::make_shared<QueryArgs>();
  command->add_option("--vocab", args->vocabulary, "Vocabulary file (vocab train)")->required();
  command->add_option("--map", args->map, "Map directory with keyframes.json")->required();
  command->add_option("--image", args->images, "Query image (repeatable)")->required();
  command->add_option("--run", args->run,
                      "Run directory of the keyframes' frames (default: "
                      "keyframes.json's run)");
  command->add_option("--top", args->top, "Keyframes to list per image")->capture_default_str();
  command->callback([args, &exit_code] {
    const Status status = RunQuery(*args);
    exit_code = status.ok() ? 0 : ReportError(status);
  });
}

}  // namespace

void AddVocabCommand(CLI::App& app, int& exit_code) {
  CLI::App* vocab = app.add_subcommand(
      "vocab", "Bag-of-words vocabulary: train from runs' frames, query a map's keyframes");
  vocab->require_subcommand(1);
  AddTrain(*vocab, exit_code);
  AddQuery(*vocab, exit_code);
}

}  // namespace semchain::app
