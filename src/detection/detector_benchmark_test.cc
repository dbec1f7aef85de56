#include "detection/detector_benchmark.h"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "detection/testing/square_scene.h"
#include "detection/yolo_detector.h"

namespace semchain::detection {
namespace {
namespace fs = std::filesystem;
using testing::Square;
using testing::SquareClasses;
using testing::SquareImage;

std::string LabelText(const std::vector<Square>& squares, double width, double height) {
  std::string text;
  for (const Square& s : squares) {
    char line[96];
    std::snprintf(line, sizeof(line), "%d %.6f %.6f %.6f %.6f\n", s.class_id,
                  (s.rect.x + 0.5 * s.rect.width) / width,
                  (s.rect.y + 0.5 * s.rect.height) / height, s.rect.width / width,
                  s.rect.height / height);
    text += line;
  }
  return text;
}

// A data set of two square scenes in its test split.
fs::path SquaresDataset(const std::string& name, const std::string& extra_label_line = "") {
  const fs::path root = fs::path(::testing::TempDir()) / name;
  fs::remove_all(root);
  fs::create_directories(root / "images/test");
  fs::create_directories(root / "labels/test");
  const std::vector<std::vector<Square>> scenes = {testing::SceneSquares(),
                                                   testing::BorderSquares()};
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    cv::Mat bgr;
    cv::cvtColor(SquareImage(scenes[i]), bgr, cv::COLOR_RGB2BGR);
    const std::string stem = "scene" + std::to_string(i);
    cv::imwrite((root / "images/test" / (stem + ".png")).string(), bgr);
    std::ofstream(root / "labels/test" / (stem + ".txt"))
        << LabelText(scenes[i], 640.0, 480.0) << (i == 1 ? extra_label_line : "");
  }
  std::ofstream(root / "data.yaml") << "path: " << root.string()
                                    << "\ntest: images/test\nnc: 3\n"
                                       "names: [red_square, green_square, blue_square]\n";
  return root;
}

std::unique_ptr<YoloDetector> SquaresModel() {
  YoloOptions options;
  options.confidence_threshold = 0.001;  // evaluation keeps low scores (ultralytics val)
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(testing::TestModel("tiny_squares_raw.onnx"), SquareClasses(), options);
  EXPECT_TRUE(detector.ok()) << detector.status().message();
  return detector.ok() ? std::move(*detector) : nullptr;
}

TEST(DetectorBenchmarkTest, ExactModelScoresFullMapOnItsSquares) {
  const Result<YoloDataset> dataset = LoadYoloDataset(SquaresDataset("squares_ok") / "data.yaml");
  ASSERT_TRUE(dataset.ok()) << dataset.status().message();
  std::unique_ptr<YoloDetector> detector = SquaresModel();
  ASSERT_NE(detector, nullptr);
  const Result<DetectorBenchmark> result = BenchmarkDetector(*detector, *dataset, "test");
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_EQ(result->images, 2);
  EXPECT_EQ(result->truths, 8);
  EXPECT_GT(result->accuracy.map50, 0.99);
  EXPECT_GT(result->accuracy.recall, 0.99);
  EXPECT_GT(result->mean_ms, 0.0);
  // Every square named by its own class, none missed, nothing where there is no square.
  const ConfusionMatrix& confusion = result->confusion;
  ASSERT_EQ(confusion.class_count(), 3);
  int named_right = 0;
  for (int t = 0; t < 3; ++t) {
    named_right += confusion.Count(t, t);
    EXPECT_EQ(confusion.Count(t, 3), 0) << "class " << t << " missed";
    EXPECT_EQ(confusion.Unpaired(t), 0) << "class " << t;
  }
  EXPECT_EQ(named_right, 8);
}

TEST(DetectorBenchmarkTest, BadDataSetsAreErrors) {
  const fs::path root = SquaresDataset("squares_bad", "7 0.5 0.5 0.1 0.1\n");
  const Result<YoloDataset> dataset = LoadYoloDataset(root / "data.yaml");
  ASSERT_TRUE(dataset.ok());
  std::unique_ptr<YoloDetector> detector = SquaresModel();
  ASSERT_NE(detector, nullptr);
  const Result<DetectorBenchmark> out_of_range = BenchmarkDetector(*detector, *dataset, "test");
  ASSERT_FALSE(out_of_range.ok());
  EXPECT_EQ(out_of_range.status().message(),
            (root / "labels/test/scene1.txt").string() + ":5: class 7 out of range (nc 3)");
  const Result<DetectorBenchmark> no_split = BenchmarkDetector(*detector, *dataset, "val");
  ASSERT_FALSE(no_split.ok());
  EXPECT_EQ(no_split.status().message(), "the data set has no val split");
  std::ofstream(root / "none.yaml") << "names: [a, b]\nnc: 2\n";
  EXPECT_EQ(LoadYoloDataset(root / "none.yaml").status().message(),
            (root / "none.yaml").string() + ": no split (train, val or test) is given");
  std::ofstream(root / "nc.yaml") << "names: [a, b]\nnc: 3\ntest: images/test\n";
  EXPECT_NE(LoadYoloDataset(root / "nc.yaml").status().message().find("nc is 3 but names lists 2"),
            std::string::npos);
  std::ofstream(root / "other.yaml") << "names: [a, b, c]\ntest: images/test\n";
  EXPECT_NE(BenchmarkDetector(*detector, *LoadYoloDataset(root / "other.yaml"), "test")
                .status()
                .message()
                .find("are not the data set's"),
            std::string::npos);
}

}  // namespace
}  // namespace semchain::detection
