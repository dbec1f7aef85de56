#include "semantic/semantic_map_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "semantic/keyframes.h"

namespace semchain::semantic {
namespace {

namespace fs = std::filesystem;

fs::path Temp(const std::string& name) { return fs::path(testing::TempDir()) / name; }

SemanticMap TwoObjects() {
  SemanticMap map;
  map.classes = {"door", "cabinet"};
  map.objects = {{7, "door", {1.0, 2.5}, {{0.5, 2.5}, {1.5, 2.5}, {1.5, 2.6}}, 12, 0.93},
                 {3, "cabinet", {0.1 + 0.2, -4.0}, {}, 41, 1.0 / 3.0}};
  map.chains = {{0, {7, 3}, {{7, 3, 6.5}, {3, 7, 6.5}}}};
  map.neighbours = {{3, 7, 6.5}};
  return map;
}

TEST(SemanticMapIoTest, RoundTripsExactly) {
  const fs::path path = Temp("semantic.json");
  ASSERT_TRUE(WriteSemanticJson(path, TwoObjects()).ok());
  const Result<SemanticMap> read = ReadSemanticJson(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->classes, TwoObjects().classes);
  ASSERT_EQ(read->objects.size(), 2u);
  EXPECT_EQ(read->objects[1].center, Eigen::Vector2d(0.1 + 0.2, -4.0));
  EXPECT_EQ(read->objects[1].confidence, 1.0 / 3.0);
  EXPECT_EQ(read->objects[0].footprint.size(), 3u);
  EXPECT_EQ(read->chains[0].order, (std::vector<int>{7, 3}));
  EXPECT_EQ(read->chains[0].links[1].from, 3);
  EXPECT_EQ(read->neighbours[0].distance, 6.5);
}

std::string ErrorOf(const std::string& text) {
  const fs::path path = Temp("bad_semantic.json");
  std::ofstream(path) << text;
  const Result<SemanticMap> read = ReadSemanticJson(path);
  return read.ok() ? "" : read.status().message();
}

TEST(SemanticMapIoTest, BadFilesNameTheField) {
  std::string text = FormatSemanticJson(TwoObjects());
  EXPECT_EQ(ErrorOf(text), "");
  const auto replaced = [&text](const std::string& from, const std::string& to) {
    std::string copy = text;
    copy.replace(copy.find(from), from.size(), to);
    return copy;
  };
  EXPECT_NE(ErrorOf(replaced("\"observations\": 12", "\"observations\": \"x\""))
                .find("objects[0].observations: expected an integer"),
            std::string::npos);
  SemanticMap dangling = TwoObjects();
  dangling.chains[0].order[0] = 8;
  EXPECT_NE(ErrorOf(FormatSemanticJson(dangling))
                .find("chains[0].order: names an object that is not in \"objects\""),
            std::string::npos);
  EXPECT_NE(ErrorOf(replaced("\"class\": \"door\"", "\"class\": \"sofa\"")).find("not one of"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf("{\"version\": 1,\n \"classes\": [}").find("bad_semantic.json:2: not valid JSON"),
      std::string::npos);
  EXPECT_NE(ErrorOf("{\"version\": 2}").find("version: unsupported"), std::string::npos);
  // nlohmann throws out_of_range, not parse_error, on this (found by fuzz/semantic_json_fuzzer.cc).
  EXPECT_NE(ErrorOf("{\"version\": 1e999}").find("not valid JSON (a number out of range)"),
            std::string::npos);
}

TEST(KeyframesTest, RoundTrip) {
  KeyframeDatabase database;
  database.run = "/tmp/run";
  Keyframe keyframe{"frames/000012", 6.0, Pose2(1.0, 2.0, 0.5), {}};
  KeyframeObject object;
  object.id = 3;
  object.class_name = "cabinet";
  object.box[2] = 40.0;
  object.depth_m = 2.1;
  object.upstream = 7;
  object.downstream = 5;
  keyframe.objects.push_back(object);
  database.keyframes.push_back(keyframe);
  const fs::path path = Temp("keyframes.json");
  ASSERT_TRUE(WriteKeyframes(path, database).ok());
  const Result<KeyframeDatabase> read = ReadKeyframes(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  ASSERT_EQ(read->keyframes.size(), 1u);
  EXPECT_EQ(read->keyframes[0].frame, "frames/000012");
  EXPECT_DOUBLE_EQ(read->keyframes[0].pose.theta, 0.5);
  EXPECT_EQ(read->keyframes[0].objects[0].upstream, 7);
  EXPECT_DOUBLE_EQ(read->keyframes[0].objects[0].box[2], 40.0);
}

// The ROS node keeps the keyframes' images in the map folder and names it "."; a reader in
// another working directory must still find them, so a relative run is the file's folder's.
TEST(KeyframesTest, ARelativeRunIsTheFilesOwnFolder) {
  const fs::path folder = Temp("moved_map");
  fs::create_directories(folder);
  KeyframeDatabase database;
  database.keyframes.push_back(Keyframe{"frames/000001", 1.0, Pose2(), {}});
  for (const std::string run : {".", "images", "/abs/run", ""}) {
    database.run = run;
    ASSERT_TRUE(WriteKeyframes(folder / "keyframes.json", database).ok());
    const Result<KeyframeDatabase> read = ReadKeyframes(folder / "keyframes.json");
    ASSERT_TRUE(read.ok()) << read.status().message();
    const std::string expected = run == "."        ? folder.lexically_normal().string() + "/"
                                 : run == "images" ? (folder / "images").string()
                                                   : run;
    EXPECT_EQ(read->run, expected) << "run \"" << run << "\"";
  }
}

// Wrong types are errors, not exceptions (json::value threw on them, found by fuzzing).
TEST(KeyframesTest, WrongTypesAreErrors) {
  const auto error_of = [](const std::string& text) {
    const fs::path path = Temp("typed_keyframes.json");
    std::ofstream(path) << text;
    const Result<KeyframeDatabase> read = ReadKeyframes(path);
    return read.ok() ? std::string() : read.status().message();
  };
  const std::string object =
      R"({"id": 3, "class": "door", "box": [0, 0, 1, 1], "depth_m": 2, "upstream": UP})";
  const std::string file = R"({"version": 1, "run": "r", "keyframes": [{"frame": "f", )"
                           R"("stamp": 0, "pose": [0, 0, 0], "objects": [OBJECT]}]})";
  const auto with = [&](const std::string& upstream) {
    std::string text = file;
    std::string o = object;
    o.replace(o.find("UP"), 2, upstream);
    return text.replace(text.find("OBJECT"), 6, o);
  };
  EXPECT_EQ(error_of(with("7")), "");
  EXPECT_EQ(error_of(with("\"7\"")), Temp("typed_keyframes.json").string() +
                                         ": keyframes[0].objects[0]: upstream and downstream "
                                         "must be integers");
  EXPECT_NE(error_of(with("4294967296")).find("must be integers"), std::string::npos);
  EXPECT_NE(error_of(R"({"version": "1"})").find("version: expected 1"), std::string::npos);
  EXPECT_NE(error_of(R"({"version": 1e999})").find("not valid JSON"), std::string::npos);
}

}  // namespace
}  // namespace semchain::semantic
