// The detector on models exported as ultralytics exports them (testdata/ultralytics_*.onnx,
// written by tools/make_ultralytics_export.py: a narrow YOLOv8 with random weights and COCO's 80
// class names, once with the raw head, once as `yolo export format=onnx` writes it, once in
// half precision).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "detection/detection_metrics.h"
#include "detection/testing/square_scene.h"
#include "detection/yolo_detector.h"
#include "sensors/detection.h"

namespace semchain::detection {
namespace {

using ::testing::HasSubstr;
using testing::TestModel;

// Loads a test model at a confidence threshold of 0.1 (random weights score low); 'nms' 1
// suppresses nothing.
std::unique_ptr<YoloDetector> Load(const std::string& model, const std::filesystem::path& map = {},
                                   double nms = YoloOptions().nms_iou_threshold) {
  YoloOptions options;
  options.confidence_threshold = 0.1;
  options.nms_iou_threshold = nms;
  Result<std::unique_ptr<YoloDetector>> detector =
      LoadYoloDetector(TestModel(model), {}, options, map);
  EXPECT_TRUE(detector.ok()) << detector.status().message();
  return detector.ok() ? std::move(*detector) : nullptr;
}

// A noise image of the models' 160 × 128 input size: random weights see something everywhere.
cv::Mat NoiseImage(int seed) {
  cv::Mat rgb(128, 160, CV_8UC3);
  cv::RNG(static_cast<std::uint64_t>(seed)).fill(rgb, cv::RNG::UNIFORM, 0, 256);
  return rgb;
}

std::vector<Detection> DetectOn(YoloDetector& detector, const cv::Mat& rgb) {
  Result<std::vector<Detection>> found = detector.Detect(rgb);
  EXPECT_TRUE(found.ok()) << found.status().message();
  return found.ok() ? *found : std::vector<Detection>();
}

// The default export runs unchanged (its decoding cut in memory) and gives exactly the boxes,
// classes and scores of the raw-head export of the same weights.
TEST(UltralyticsExportTest, TheDefaultExportGivesTheRawExportsDetections) {
  const std::unique_ptr<YoloDetector> raw = Load("ultralytics_raw.onnx");
  const std::unique_ptr<YoloDetector> decoded = Load("ultralytics_decoded.onnx");
  ASSERT_TRUE(raw && decoded);
  EXPECT_FALSE(raw->decoding_removed());
  EXPECT_TRUE(decoded->decoding_removed());
  EXPECT_EQ(decoded->head().kind, HeadKind::kRaw);
  EXPECT_EQ(decoded->options().input_size(), cv::Size(160, 128));
  int total = 0;
  for (int seed = 1; seed <= 3; ++seed) {
    const std::vector<Detection> a = DetectOn(*raw, NoiseImage(seed));
    const std::vector<Detection> b = DetectOn(*decoded, NoiseImage(seed));
    ASSERT_EQ(a.size(), b.size()) << "seed " << seed;
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].class_name, b[i].class_name);
      EXPECT_NEAR(a[i].score, b[i].score, 1e-6);
      for (int k = 0; k < 4; ++k) EXPECT_NEAR(a[i].box[k], b[i].box[k], 1e-4);
    }
    total += static_cast<int>(a.size());
  }
  EXPECT_GE(total, 10);  // the comparison compares something
}

// Without a .names file beside the model (nor --classes) the names come from the metadata
// ultralytics' exporter writes.
TEST(UltralyticsExportTest, ClassNamesComeFromTheModelsMetadata) {
  ASSERT_FALSE(std::filesystem::exists(TestModel("ultralytics_decoded.names")));
  const std::unique_ptr<YoloDetector> decoded = Load("ultralytics_decoded.onnx");
  ASSERT_TRUE(decoded);
  const std::vector<std::string>& names = decoded->class_names();
  ASSERT_EQ(names.size(), 80u);
  EXPECT_EQ(names[0], "person");
  EXPECT_EQ(names[60], "dining table");
  EXPECT_EQ(names[79], "toothbrush");
  // --classes still wins over the metadata.
  Result<std::unique_ptr<YoloDetector>> renamed = LoadYoloDetector(
      TestModel("ultralytics_decoded.onnx"), TestModel("ultralytics_raw.names"), YoloOptions());
  ASSERT_TRUE(renamed.ok()) << renamed.status().message();
  EXPECT_EQ((*renamed)->class_names(), names);
}

TEST(UltralyticsExportTest, AModelWithoutAnyClassNamesIsOneClearError) {
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel("ultralytics_raw.onnx"), {}, YoloOptions());
  ASSERT_FALSE(detector.ok());
  EXPECT_EQ(detector.status().message(),
            TestModel("ultralytics_raw.onnx").string() +
                ": no class names (no .names file beside the model, no --classes FILE, and no "
                "'names' in the model's metadata)");
}

TEST(UltralyticsExportTest, AClassCountMismatchSaysTheHeadsClassCount) {
  const std::vector<std::string> five = {"door", "cabinet", "bucket", "chair", "stool"};
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel("ultralytics_decoded.onnx"), five, YoloOptions());
  ASSERT_FALSE(detector.ok());
  EXPECT_EQ(detector.status().message(),
            TestModel("ultralytics_decoded.onnx").string() +
                ": class-count mismatch: the model's head has 80 classes, but there are 5 class "
                "names");
}

// The half-precision export loads (OpenCV 4.6 refuses FLOAT16 tensors; they are converted) and
// finds what the single-precision one finds, up to the weights' rounding to 11 bits.
TEST(UltralyticsExportTest, TheHalfPrecisionExportFindsWhatTheSingleFinds) {
  const std::unique_ptr<YoloDetector> single = Load("ultralytics_decoded.onnx");
  const std::unique_ptr<YoloDetector> half = Load("ultralytics_decoded_fp16.onnx");
  ASSERT_TRUE(single && half);
  EXPECT_EQ(half->class_names(), single->class_names());
  int matched = 0;
  for (int seed = 1; seed <= 3; ++seed) {
    const std::vector<Detection> a = DetectOn(*single, NoiseImage(seed));
    const std::vector<Detection> b = DetectOn(*half, NoiseImage(seed));
    for (const Detection& d : a) {
      if (d.score < 0.15) continue;  // near the threshold the rounding may tip it either way
      const auto same = std::find_if(b.begin(), b.end(), [&](const Detection& e) {
        return e.class_id == d.class_id && BoxIou(BoxOf(d), BoxOf(e)) > 0.95 &&
               std::abs(e.score - d.score) < 0.02;
      });
      EXPECT_NE(same, b.end()) << "seed " << seed << ": " << d.class_name << " at "
                               << ::testing::PrintToString(BoxOf(d));
      ++matched;
    }
  }
  EXPECT_GE(matched, 5);
}

std::filesystem::path WriteMap(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

bool SameDetection(const Detection& a, const Detection& b) {
  return BoxOf(a) == BoxOf(b) && a.score == b.score;
}

// A class map turns the model's classes into semchain's: the mapped ones keep their boxes and
// scores under their new class and the others are dropped (seen with an NMS that suppresses
// nothing), and two model classes mapped to one class are suppressed together by the NMS. The
// map names the two classes the model finds most.
TEST(UltralyticsExportTest, AClassMapRenamesMergesAndDrops) {
  const cv::Mat image = NoiseImage(1);
  const std::unique_ptr<YoloDetector> plain = Load("ultralytics_decoded.onnx");
  const std::unique_ptr<YoloDetector> every = Load("ultralytics_decoded.onnx", {}, 1.0);
  ASSERT_TRUE(plain && every);
  const std::vector<Detection> model = DetectOn(*plain, image);
  const std::vector<Detection> candidates = DetectOn(*every, image);
  std::map<std::string, int> counts;
  for (const Detection& d : model) ++counts[d.class_name];
  ASSERT_GE(counts.size(), 3u);
  std::vector<std::pair<int, std::string>> by_count;
  for (const auto& [name, count] : counts) by_count.push_back({-count, name});
  std::sort(by_count.begin(), by_count.end());
  const std::string first = by_count[0].second, second = by_count[1].second;
  const auto named = [&](const Detection& d) {
    return d.class_name == first || d.class_name == second;
  };
  const std::filesystem::path map = WriteMap("semchain_ultralytics_map.yaml",
                                             "'" + first + "': chair\n'" + second + "': chair\n");
  const std::unique_ptr<YoloDetector> mapped = Load("ultralytics_decoded.onnx", map);
  const std::unique_ptr<YoloDetector> mapped_every = Load("ultralytics_decoded.onnx", map, 1.0);
  std::filesystem::remove(map);
  ASSERT_TRUE(mapped && mapped_every);
  EXPECT_EQ(mapped->class_names(), DefaultClassNames());
  EXPECT_EQ(mapped->model_class_names(), plain->class_names());
  // Without suppression: exactly the model's candidates of the two classes, as chairs.
  const std::vector<Detection> chair_candidates = DetectOn(*mapped_every, image);
  EXPECT_EQ(chair_candidates.size(),
            static_cast<std::size_t>(std::count_if(candidates.begin(), candidates.end(), named)));
  for (const Detection& chair : chair_candidates) {
    EXPECT_EQ(chair.class_name, "chair");
    EXPECT_EQ(chair.class_id, 3);
    EXPECT_TRUE(std::any_of(candidates.begin(), candidates.end(), [&](const Detection& d) {
      return named(d) && SameDetection(d, chair);
    })) << ::testing::PrintToString(BoxOf(chair));
  }
  // With it: fewer boxes than the two classes keep apart, as the two are one class now.
  const std::vector<Detection> chairs = DetectOn(*mapped, image);
  for (const Detection& chair : chairs) {
    EXPECT_TRUE(std::any_of(chair_candidates.begin(), chair_candidates.end(),
                            [&](const Detection& d) { return SameDetection(d, chair); }));
  }
  EXPECT_GT(chairs.size(), 0u);
  EXPECT_LT(chairs.size(), static_cast<std::size_t>(counts[first] + counts[second]));
}

TEST(UltralyticsExportTest, AClassMapNamingAnUnknownClassIsOneClearError) {
  const std::filesystem::path map =
      WriteMap("semchain_ultralytics_bad_map.yaml", "tv: computer\nlaptop: television\n");
  Result<std::unique_ptr<YoloDetector>> detector =
      LoadYoloDetector(TestModel("ultralytics_decoded.onnx"), {}, YoloOptions(), map);
  std::filesystem::remove(map);
  ASSERT_FALSE(detector.ok());
  EXPECT_EQ(detector.status().message(),
            map.string() +
                ":2: laptop: 'television' is not a semchain class (door, cabinet, bucket, chair, "
                "stool, table, sofa, computer, bed, clock)");
}

TEST(UltralyticsExportTest, TheShippedCocoMapFitsTheExportsClasses) {
  const std::unique_ptr<YoloDetector> detector =
      Load("ultralytics_decoded.onnx",
           std::filesystem::path(SEMCHAIN_SOURCE_DIR) / "config/classes/coco.yaml");
  ASSERT_TRUE(detector);
  EXPECT_EQ(detector->class_names(), DefaultClassNames());
  for (const Detection& d : DetectOn(*detector, NoiseImage(2))) {
    EXPECT_THAT((std::vector<std::string>{"chair", "sofa", "bed", "table", "computer", "clock"}),
                ::testing::Contains(d.class_name));
  }
}

// A hand-made model (no YOLOv8 head in its graph) with a map: the tiny squares model's red and
// green squares both become chairs, blue ones are dropped.
TEST(ClassMapDetectorTest, MapsTheTinySquaresModelsClassesExactly) {
  const std::filesystem::path map =
      WriteMap("semchain_squares_map.yaml", "red_square: chair\ngreen_square: chair\n");
  Result<std::unique_ptr<YoloDetector>> detector =
      LoadYoloDetector(TestModel("tiny_squares_raw.onnx"), {}, YoloOptions(), map);
  std::filesystem::remove(map);
  ASSERT_TRUE(detector.ok()) << detector.status().message();
  const std::vector<testing::Square> squares = testing::SceneSquares();
  const std::vector<Detection> found = DetectOn(**detector, testing::SquareImage(squares));
  ASSERT_EQ(found.size(), 3u);  // two red squares and a green one; the blue one is dropped
  for (const Detection& d : found) {
    EXPECT_EQ(d.class_name, "chair");
    const auto square = std::find_if(squares.begin(), squares.end(), [&](const auto& s) {
      return std::abs(s.rect.x - d.box[0]) < 0.05 && std::abs(s.rect.y - d.box[1]) < 0.05;
    });
    ASSERT_NE(square, squares.end());
    EXPECT_NE(square->class_id, 2);
  }
}

}  // namespace
}  // namespace semchain::detection
