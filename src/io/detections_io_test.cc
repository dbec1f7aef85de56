#include "io/detections_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace semchain {
namespace {

std::filesystem::path WriteText(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::path(testing::TempDir()) / name;
  std::ofstream(path) << text;
  return path;
}

template <typename T>
std::string ErrorOf(const Result<T>& result) {
  return result.ok() ? "" : result.status().message();
}

std::vector<FrameDetections> TwoFrames() {
  Detection door{"door", 0, 0.97, {10.5, 20.0, 110.25, 230.0}, 2.31};
  Detection bucket{"bucket", 2, 1.0 / 3.0, {0.0, 0.0, 1.0, 1.0}, 0.1 + 0.2};
  return {{"frames/000123", 12.3, {door, bucket}}, {"frames/000124", 12.4, {}}};
}

TEST(DetectionsIoTest, OneRecordRoundTripsAsTheFileLine) {
  const FrameDetections frame = TwoFrames().front();
  const Result<std::string> line = FormatDetectionsRecord(frame);
  ASSERT_TRUE(line.ok()) << line.status().message();
  EXPECT_EQ(line->find('\n'), std::string::npos);
  const Result<FrameDetections> parsed = ParseDetectionsRecord(*line, "/semchain/detections #1");
  ASSERT_TRUE(parsed.ok()) << parsed.status().message();
  EXPECT_EQ(parsed->frame, frame.frame);
  EXPECT_EQ(parsed->stamp, frame.stamp);
  ASSERT_EQ(parsed->detections.size(), 2u);
  EXPECT_EQ(parsed->detections[1].score, 1.0 / 3.0);
  EXPECT_EQ(ErrorOf(ParseDetectionsRecord(R"({"frame": "f", "stamp": 1})", "topic #3")),
            "topic #3: detections: missing");
  FrameDetections bad = frame;
  bad.stamp = std::nan("");
  EXPECT_FALSE(FormatDetectionsRecord(bad).ok());
}

TEST(DetectionsIoTest, RoundTripsExactly) {
  const std::filesystem::path path = std::filesystem::path(testing::TempDir()) / "d.jsonl";
  const std::vector<FrameDetections> frames = TwoFrames();
  ASSERT_TRUE(WriteDetectionsJsonl(path, frames).ok());
  const Result<std::vector<FrameDetections>> read = ReadDetectionsJsonl(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  ASSERT_EQ(read->size(), 2u);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    EXPECT_EQ((*read)[f].frame, frames[f].frame);
    EXPECT_EQ((*read)[f].stamp, frames[f].stamp);
    ASSERT_EQ((*read)[f].detections.size(), frames[f].detections.size());
    for (std::size_t i = 0; i < frames[f].detections.size(); ++i) {
      const Detection& a = frames[f].detections[i];
      const Detection& b = (*read)[f].detections[i];
      EXPECT_EQ(a.class_name, b.class_name);
      EXPECT_EQ(a.class_id, b.class_id);
      EXPECT_EQ(a.score, b.score);
      EXPECT_EQ(a.depth_m, b.depth_m);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(a.box[k], b.box[k]);
    }
  }
  // One line per frame, in the layout of DESIGN.md §5.5.
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(
      first.rfind(R"({"frame":"frames/000123","stamp":12.3,"detections":[{"class":"door",)"
                  R"("class_id":0,"score":0.97,"box":[10.5,20.0,110.25,230.0],"depth_m":2.31})",
                  0),
      0u)
      << first;
}

TEST(DetectionsIoTest, ReadsTheDesignExample) {
  const std::filesystem::path path = WriteText(
      "example.jsonl",
      R"({"frame": "frames/000123", "stamp": 12.3, "detections": [)"
      R"({"class": "door", "class_id": 0, "score": 0.97, "box": [1, 2, 3, 4], "depth_m": 2.31}]})"
      "\n\n");
  const Result<std::vector<FrameDetections>> read = ReadDetectionsJsonl(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  ASSERT_EQ(read->size(), 1u);
  EXPECT_EQ((*read)[0].detections[0].class_name, "door");
  EXPECT_DOUBLE_EQ((*read)[0].detections[0].box[3], 4.0);
  EXPECT_DOUBLE_EQ((*read)[0].detections[0].depth_m, 2.31);
}

TEST(DetectionsIoTest, ErrorsNameFileLineAndField) {
  const std::string ok = R"({"frame": "f", "stamp": 1, "detections": []})";
  const std::string det = R"("class": "door", "class_id": 0, "score": 0.5, "depth_m": 1)";
  struct Case {
    std::string line;
    std::string message;
  };
  const Case cases[] = {
      {R"({"stamp": 1, "detections": []})", "frame: missing"},
      {R"({"frame": "f", "stamp": "x", "detections": []})", "stamp: expected a number, got \"x\""},
      {R"({"frame": "f", "stamp": 1, "detections": {}})", "detections: expected a list, got {}"},
      {R"({"frame": "f", "stamp": 1, "detections": [{)" + det + R"(, "box": [1, 2, 3]}]})",
       "detections[0].box: expected 4 numbers [x1, y1, x2, y2], got [1,2,3]"},
      {R"({"frame": "f", "stamp": 1, "detections": [{)" + det + R"(, "box": [3, 2, 1, 4]}]})",
       "detections[0].box: expected x1 <= x2 and y1 <= y2, got [3,2,1,4]"},
      {R"({"frame": "f", "stamp": 1, "detections": [{"class": "door", "box": [1,2,3,4]}]})",
       "detections[0].class_id: missing"},
      {R"({"frame": "f", "stamp": 1, "detections": [{"class": "door", "class_id": 0,)"
       R"( "score": 1.5, "box": [1,2,3,4], "depth_m": 1}]})",
       "detections[0].score: not in [0, 1]"},
      {"[1, 2]", "expected a JSON object per line"},
  };
  for (const Case& c : cases) {
    const std::filesystem::path path = WriteText("bad.jsonl", ok + "\n" + c.line + "\n");
    EXPECT_EQ(ErrorOf(ReadDetectionsJsonl(path)), path.string() + ":2: " + c.message) << c.line;
  }
  const std::filesystem::path broken = WriteText("broken.jsonl", ok + "\n" + ok + "\n{\"frame\"\n");
  EXPECT_EQ(ErrorOf(ReadDetectionsJsonl(broken)).rfind(broken.string() + ":3: invalid JSON", 0),
            0u);
  EXPECT_FALSE(ReadDetectionsJsonl(broken.string() + ".missing").ok());
}

TEST(DetectionsIoTest, RefusesToWriteNonFiniteNumbers) {
  std::vector<FrameDetections> frames = TwoFrames();
  frames[0].detections[1].depth_m = std::nan("");
  const std::filesystem::path path = std::filesystem::path(testing::TempDir()) / "nan.jsonl";
  const Status status = WriteDetectionsJsonl(path, frames);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), path.string() + ": frame 'frames/000123': non-finite number");
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(DetectionsIoTest, ReadsClassNames) {
  const Result<std::vector<std::string>> names =
      ReadClassNames(WriteText("m.names", "door\r\ncabinet\n  bucket \nchair\nstool\n\n"));
  ASSERT_TRUE(names.ok()) << names.status().message();
  EXPECT_EQ(*names, (std::vector<std::string>{"door", "cabinet", "bucket", "chair", "stool"}));
  const std::filesystem::path gap = WriteText("gap.names", "door\n\ncabinet\n");
  EXPECT_EQ(ErrorOf(ReadClassNames(gap)),
            gap.string() + ":2: blank line before the last class name (it would shift class ids)");
  const std::filesystem::path twice = WriteText("twice.names", "door\nchair\ndoor\n");
  EXPECT_EQ(ErrorOf(ReadClassNames(twice)), twice.string() + ":3: class 'door' repeated");
  const std::filesystem::path empty = WriteText("empty.names", "\n");
  EXPECT_EQ(ErrorOf(ReadClassNames(empty)), empty.string() + ": no class names");
}

}  // namespace
}  // namespace semchain
