#include "detection/yolo_detector.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "detection/testing/square_scene.h"

namespace semchain::detection {
namespace {

using ::testing::HasSubstr;
using testing::SceneSquares;
using testing::Square;
using testing::SquareClasses;
using testing::SquareImage;
using testing::TestModel;

// Boxes may differ from the drawn squares by the DFL's 1e-7 floor (about 0.005 px at stride 32)
// and float rounding, far below a pixel.
constexpr double kBoxTolerancePx = 0.02;

struct ModelCase {
  std::string model;
  HeadKind kind;
  cv::Size input;
};

void PrintTo(const ModelCase& c, std::ostream* os) {
  *os << c.model << " at " << c.input.width << "x" << c.input.height;
}

std::string CaseName(const ::testing::TestParamInfo<ModelCase>& info) {
  return std::string(info.param.kind == HeadKind::kRaw ? "Raw" : "Decoded") +
         std::to_string(info.param.input.width) + "x" + std::to_string(info.param.input.height);
}

class TinyModelTest : public ::testing::TestWithParam<ModelCase> {};

std::unique_ptr<YoloDetector> LoadTiny(const ModelCase& c) {
  YoloOptions options;
  options.input_width = c.input.width;
  options.input_height = c.input.height;
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel(c.model), SquareClasses(), options);
  EXPECT_TRUE(detector.ok()) << detector.status().message();
  return detector.ok() ? std::move(*detector) : nullptr;
}

// Every square is found once, with its class and its exact box.
void ExpectExactDetections(YoloDetector& detector, const std::vector<Square>& squares) {
  Result<std::vector<Detection>> found = detector.Detect(SquareImage(squares));
  ASSERT_TRUE(found.ok()) << found.status().message();
  ASSERT_EQ(found->size(), squares.size());
  for (const Square& square : squares) {
    const auto match = std::find_if(found->begin(), found->end(), [&](const Detection& d) {
      return d.class_id == square.class_id && std::abs(d.box[0] - square.rect.x) < 1.0 &&
             std::abs(d.box[1] - square.rect.y) < 1.0;
    });
    ASSERT_NE(match, found->end()) << "square at " << square.rect;
    EXPECT_EQ(match->class_name, SquareClasses()[square.class_id]);
    EXPECT_NEAR(match->box[0], square.rect.x, kBoxTolerancePx);
    EXPECT_NEAR(match->box[1], square.rect.y, kBoxTolerancePx);
    EXPECT_NEAR(match->box[2], square.rect.br().x, kBoxTolerancePx);
    EXPECT_NEAR(match->box[3], square.rect.br().y, kBoxTolerancePx);
    EXPECT_NEAR(match->score, 1.0 / (1.0 + std::exp(-10.0)), 1e-5);  // the model's +10 logit
    EXPECT_EQ(match->depth_m, 0.0);
  }
}

TEST_P(TinyModelTest, FindsEverySquareExactly) {
  const std::unique_ptr<YoloDetector> detector = LoadTiny(GetParam());
  ASSERT_NE(detector, nullptr);
  EXPECT_EQ(detector->head().kind, GetParam().kind);
  ExpectExactDetections(*detector, SceneSquares());
}

TEST_P(TinyModelTest, FindsSquaresAtTheBorderAndLargeOnesExactly) {
  const std::unique_ptr<YoloDetector> detector = LoadTiny(GetParam());
  ASSERT_NE(detector, nullptr);
  ExpectExactDetections(*detector, testing::BorderSquares());
}

TEST_P(TinyModelTest, FindsNothingOnAPlainImage) {
  const std::unique_ptr<YoloDetector> detector = LoadTiny(GetParam());
  ASSERT_NE(detector, nullptr);
  Result<std::vector<Detection>> found = detector->Detect(SquareImage({}));
  ASSERT_TRUE(found.ok()) << found.status().message();
  EXPECT_TRUE(found->empty());
}

INSTANTIATE_TEST_SUITE_P(
    RawAndDecodedAtTwoSizes, TinyModelTest,
    ::testing::Values(ModelCase{"tiny_squares_raw.onnx", HeadKind::kRaw, {640, 640}},
                      ModelCase{"tiny_squares_raw.onnx", HeadKind::kRaw, {320, 256}},
                      ModelCase{"tiny_squares_decoded.onnx", HeadKind::kDecoded, {640, 640}},
                      ModelCase{"tiny_squares_decoded.onnx", HeadKind::kDecoded, {320, 256}}),
    CaseName);

TEST(YoloDetectorTest, ThresholdFiltersByScore) {
  YoloOptions options;
  options.confidence_threshold = 0.99999;  // above sigmoid(10) = 0.999955
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel("tiny_squares_raw.onnx"), SquareClasses(), options);
  ASSERT_TRUE(detector.ok()) << detector.status().message();
  Result<std::vector<Detection>> found = (*detector)->Detect(SquareImage(SceneSquares()));
  ASSERT_TRUE(found.ok());
  EXPECT_TRUE(found->empty());
}

// OpenCV 4.6's own count of a graph's FLOPs crashes on a MatMul of two computed tensors (Gold-
// YOLO's attention has two): the cost counts it as 2·K·(output values) and the rest as OpenCV does.
TEST(YoloDetectorTest, CostCountsAMatMulOfComputedTensors) {
  Result<std::unique_ptr<YoloDetector>> plain =
      YoloDetector::Load(TestModel("tiny_squares_raw.onnx"), SquareClasses(), YoloOptions());
  Result<std::unique_ptr<YoloDetector>> attention =
      YoloDetector::Load(TestModel("tiny_squares_attention.onnx"), SquareClasses(), YoloOptions());
  ASSERT_TRUE(plain.ok()) << plain.status().message();
  ASSERT_TRUE(attention.ok()) << attention.status().message();
  const YoloDetector::Cost without = (*plain)->ModelCost();
  const YoloDetector::Cost with = (*attention)->ModelCost();
  EXPECT_GT(without.gflops, 0.0);
  EXPECT_EQ(with.parameters, without.parameters);  // the branch has no weights
  // The branch: the masks' channel means (a sum over 640 × 640 pixels for each of their C = 4
  // channels: three classes and their union) and their outer product, (4 × 1) @ (1 × 4): K = 1,
  // 16 values, 32 operations.
  const double added = (with.gflops - without.gflops) * 1e9;
  EXPECT_GE(added, 4.0 * 640 * 640 + 32.0 - 1.0);
  EXPECT_LE(added, 2.0 * (4.0 * 640 * 640) + 32.0);
  // And the branch feeds nothing: the same boxes.
  const cv::Mat image = SquareImage(SceneSquares());
  Result<std::vector<Detection>> a = (*plain)->Detect(image);
  Result<std::vector<Detection>> b = (*attention)->Detect(image);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->size(), b->size());
  for (std::size_t i = 0; i < a->size(); ++i) {
    EXPECT_EQ((*a)[i].class_id, (*b)[i].class_id);
    for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ((*a)[i].box[k], (*b)[i].box[k]);
  }
}

TEST(YoloDetectorTest, RejectsAnImageThatIsNotRgb) {
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel("tiny_squares_raw.onnx"), SquareClasses(), YoloOptions());
  ASSERT_TRUE(detector.ok());
  Result<std::vector<Detection>> found = (*detector)->Detect(cv::Mat(10, 10, CV_8UC1));
  ASSERT_FALSE(found.ok());
  EXPECT_EQ(found.status().message(), "the detector needs a non-empty 8-bit 3-channel RGB image");
}

TEST(YoloDetectorTest, AMissingModelIsOneClearError) {
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel("nothing.onnx"), SquareClasses(), YoloOptions());
  ASSERT_FALSE(detector.ok());
  EXPECT_EQ(detector.status().message(),
            TestModel("nothing.onnx").string() + ": no such model file");
}

TEST(YoloDetectorTest, AClassCountMismatchIsOneClearError) {
  const std::vector<std::string> five = {"door", "cabinet", "bucket", "chair", "stool"};
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel("tiny_squares_raw.onnx"), five, YoloOptions());
  ASSERT_FALSE(detector.ok());
  EXPECT_EQ(detector.status().message(),
            TestModel("tiny_squares_raw.onnx").string() +
                ": class-count mismatch: the model's output has 67 rows per anchor, which fits "
                "3 classes (raw head) or 63 classes (decoded head), but there are 5 class names");
}

TEST(YoloDetectorTest, AWrongOutputShapeIsOneClearError) {
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel("unflattened_head.onnx"), SquareClasses(), YoloOptions());
  ASSERT_FALSE(detector.ok());
  EXPECT_EQ(detector.status().message(),
            TestModel("unflattened_head.onnx").string() +
                ": the model's output is 1x67x80x80, expected 1 x (64 + classes) x anchors (raw "
                "head) or 1 x (4 + classes) x anchors (decoded head)");
}

TEST(YoloDetectorTest, AFileThatIsNoModelIsOneClearError) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "semchain_detector_test_not_a_model.onnx";
  std::ofstream(path) << "not an ONNX model\n";
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(path, SquareClasses(), YoloOptions());
  std::filesystem::remove(path);
  ASSERT_FALSE(detector.ok());
  // CheckOnnxGraph turns it away before OpenCV sees it.
  EXPECT_EQ(detector.status().message(),
            path.string() + ": not an ONNX model (malformed protobuf)");
}

TEST(YoloDetectorTest, ValidatesOptions) {
  YoloOptions options;
  options.input_width = 330;
  options.input_height = 640;
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel("tiny_squares_raw.onnx"), SquareClasses(), options);
  ASSERT_FALSE(detector.ok());
  EXPECT_EQ(detector.status().message(),
            "input size 330x640: width and height must be positive multiples of 32 (or both 0: the "
            "model's own)");
}

// 0 × 0 (the CLI's "auto") is the size the model was exported for, read from its graph.
TEST(YoloDetectorTest, AutoInputIsTheExportSize) {
  YoloOptions options;
  ASSERT_TRUE(ParseInputSize("auto", &options).ok());
  Result<std::unique_ptr<YoloDetector>> detector =
      YoloDetector::Load(TestModel("tiny_squares_raw.onnx"), SquareClasses(), options);
  ASSERT_TRUE(detector.ok()) << detector.status().message();
  EXPECT_EQ((*detector)->options().input_size(), cv::Size(640, 640));
  ASSERT_TRUE(ParseInputSize("320x256", &options).ok());
  detector = YoloDetector::Load(TestModel("tiny_squares_raw.onnx"), SquareClasses(), options);
  ASSERT_TRUE(detector.ok()) << detector.status().message();
  EXPECT_EQ((*detector)->options().input_size(), cv::Size(320, 256));
  EXPECT_NE(ParseInputSize("automatic", &options).message().find("or auto"), std::string::npos);
}

TEST(LoadYoloDetectorTest, ReadsTheNamesBesideTheModelAndReportsAMissingModelFirst) {
  Result<std::unique_ptr<YoloDetector>> detector =
      LoadYoloDetector(TestModel("tiny_squares_decoded.onnx"), {}, YoloOptions());
  ASSERT_TRUE(detector.ok()) << detector.status().message();
  EXPECT_EQ((*detector)->class_names(), SquareClasses());
  EXPECT_EQ((*detector)->head().kind, HeadKind::kDecoded);
  Result<std::unique_ptr<YoloDetector>> missing =
      LoadYoloDetector(TestModel("nothing.onnx"), {}, YoloOptions());
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().message(),
            TestModel("nothing.onnx").string() + ": no such model file");
}

TEST(LoadModelClassNamesTest, ReadsTheNamesBesideTheModelOrTheOverride) {
  Result<std::vector<std::string>> beside =
      LoadModelClassNames(TestModel("tiny_squares_raw.onnx"), {});
  ASSERT_TRUE(beside.ok()) << beside.status().message();
  EXPECT_EQ(*beside, SquareClasses());
  Result<std::vector<std::string>> missing = LoadModelClassNames(TestModel("nothing.onnx"), {});
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.status().message(), HasSubstr("nothing.names: no class-names file"));
  Result<std::vector<std::string>> other =
      LoadModelClassNames(TestModel("nothing.onnx"), TestModel("tiny_squares_decoded.names"));
  ASSERT_TRUE(other.ok()) << other.status().message();
  EXPECT_EQ(other->size(), 3u);
}

}  // namespace
}  // namespace semchain::detection
