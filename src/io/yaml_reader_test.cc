#include "io/yaml_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace semchain::yaml {
namespace {

constexpr char kWorld[] = R"(name: two_rooms
walls:
  - [[0, 0], [12, 0]]
objects:
  - {class: door, x: 1.0, y: 0.05}
  - {class: bucket, x: 3.0, radius: 0.15}
  - {class: chair, x: +2, radius: abc}
robot:
  start: [1.0, 1.0, 0.0]
  lidar:
    height: 0.19
    beams: 360
    hieght: 3
  enabled: true
  note: ''
  empty:
)";

Node Load(const std::string& text = kWorld) {
  Result<Node> root = Node::LoadString(text, "world.yaml");
  EXPECT_TRUE(root.ok()) << root.status().message();
  return root.ok() ? *root : Node();
}

// Returns the error message of a failed result, or "" when it succeeded.
template <typename T>
std::string ErrorOf(const Result<T>& result) {
  return result.ok() ? "" : result.status().message();
}

TEST(YamlReaderTest, ReadsValuesAndPaths) {
  const Node root = Load();
  ASSERT_TRUE(root.IsMap());
  EXPECT_EQ(root.size(), 4u);
  EXPECT_EQ(root.Keys(), (std::vector<std::string>{"name", "walls", "objects", "robot"}));
  EXPECT_EQ(*root.Get("name")->AsString(), "two_rooms");
  const Node objects = *root.Get("objects");
  ASSERT_TRUE(objects.IsSequence());
  EXPECT_EQ(objects.size(), 3u);
  const Node bucket = objects.At(1);
  EXPECT_EQ(bucket.path(), "objects[1]");
  EXPECT_DOUBLE_EQ(*bucket.Get("radius")->AsDouble(), 0.15);
  EXPECT_DOUBLE_EQ(*objects.At(2).Get("x")->AsDouble(), 2.0);  // YAML allows a leading '+'
  const Node lidar = *root.Get("robot")->Get("lidar");
  EXPECT_EQ(lidar.path(), "robot.lidar");
  EXPECT_EQ(*lidar.Get("beams")->AsInt(), 360);
  EXPECT_EQ(lidar.Get("height")->Where(), "world.yaml:11: robot.lidar.height");
  EXPECT_TRUE(*root.Get("robot")->Get("enabled")->AsBool());
  EXPECT_EQ(*root.Get("robot")->Get("start")->AsDoubleList(3), (std::vector<double>{1, 1, 0}));
  EXPECT_EQ(root.Get("walls")->At(0).At(1).path(), "walls[0][1]");
}

TEST(YamlReaderTest, MissingKeyNamesMapLineAndPath) {
  const Node lidar = *Load().Get("robot")->Get("lidar");
  EXPECT_FALSE(lidar.Has("fov_deg"));
  EXPECT_EQ(ErrorOf(lidar.Get("fov_deg")), "world.yaml:11: robot.lidar.fov_deg: missing");
}

TEST(YamlReaderTest, NonNumbersAreRejectedWithTheirText) {
  const Node root = Load();
  EXPECT_EQ(ErrorOf(root.Get("objects")->At(2).Get("radius")->AsDouble()),
            "world.yaml:7: objects[2].radius: 'abc' is not a number");
  EXPECT_EQ(ErrorOf(root.Get("robot")->Get("note")->AsDouble()),
            "world.yaml:15: robot.note: '' is not a number");
  EXPECT_EQ(ErrorOf(root.Get("robot")->Get("empty")->AsDouble()),
            "world.yaml:16: robot.empty: expected a number, got nothing");
  EXPECT_EQ(ErrorOf(root.Get("robot")->AsDouble()),
            "world.yaml:9: robot: expected a number, got a map");
}

TEST(YamlReaderTest, StrictNumberParsing) {
  const Node root =
      Load("a: 1.5x\nb: nan\nc: .inf\nd: inf\ne: 1e999\nf: 2.5\ng: 0x10\nh: +-1\ni: -3\nj: 1e-3\n");
  for (const char* key : {"a", "b", "c", "d", "e", "g", "h"}) {
    const Result<double> value = root.Get(key)->AsDouble();
    EXPECT_FALSE(value.ok()) << key;
    EXPECT_NE(ErrorOf(value).find("is not a number"), std::string::npos) << key;
  }
  EXPECT_EQ(ErrorOf(root.Get("b")->AsDouble()), "world.yaml:2: b: 'nan' is not a number");
  EXPECT_DOUBLE_EQ(*root.Get("i")->AsDouble(), -3.0);
  EXPECT_DOUBLE_EQ(*root.Get("j")->AsDouble(), 1e-3);
  EXPECT_EQ(ErrorOf(root.Get("f")->AsInt()), "world.yaml:6: f: '2.5' is not an integer");
  EXPECT_EQ(*root.Get("i")->AsInt(), -3);
  const Node big = Load("n: 99999999999\n");
  EXPECT_EQ(ErrorOf(big.Get("n")->AsInt()), "world.yaml:1: n: '99999999999' is out of range");
}

TEST(YamlReaderTest, BooleansAndStrings) {
  const Node root = Load("a: yes\nb: FALSE\nc: [1]\n");
  EXPECT_EQ(ErrorOf(root.Get("a")->AsBool()),
            "world.yaml:1: a: 'yes' is not a boolean (use true or false)");
  EXPECT_FALSE(*root.Get("b")->AsBool());
  EXPECT_EQ(ErrorOf(root.Get("c")->AsString()),
            "world.yaml:3: c: expected a string, got a sequence");
}

TEST(YamlReaderTest, ListsCheckTypeSizeAndElements) {
  const Node root = Load("a: [1, 2]\nb: [1, x, 3]\nc: 4\n");
  EXPECT_EQ(ErrorOf(root.Get("a")->AsDoubleList(3)), "world.yaml:1: a: expected 3 numbers, got 2");
  EXPECT_EQ(root.Get("a")->AsDoubleList()->size(), 2u);
  EXPECT_EQ(ErrorOf(root.Get("b")->AsDoubleList()), "world.yaml:2: b[1]: 'x' is not a number");
  EXPECT_EQ(ErrorOf(root.Get("c")->AsDoubleList()),
            "world.yaml:3: c: expected a list of numbers, got '4'");
}

TEST(YamlReaderTest, CheckKeysReportsUnknownAndDuplicateKeys) {
  const Node lidar = *Load().Get("robot")->Get("lidar");
  const Status status = lidar.CheckKeys({"height", "beams", "fov_deg"});
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(),
            "world.yaml:13: robot.lidar.hieght: unknown key (allowed: height, beams, fov_deg)");
  EXPECT_TRUE(lidar.CheckKeys({"height", "beams", "hieght"}).ok());
  const Node duplicate = Load("a: 1\nb: 2\na: 3\n");
  EXPECT_EQ(duplicate.CheckKeys({"a", "b"}).message(), "world.yaml:3: a: duplicate key");
  EXPECT_EQ(Load("[1, 2]").CheckKeys({"a"}).message(),
            "world.yaml:1: expected a map, got a sequence");
}

TEST(YamlReaderTest, GetOnANonMapIsAnError) {
  const Node root = Load();
  EXPECT_EQ(ErrorOf(root.Get("walls")->Get("x")),
            "world.yaml:3: walls: expected a map, got a sequence");
}

TEST(YamlReaderTest, SyntaxErrorNamesFileAndLine) {
  const Result<Node> bad = Node::LoadString("a: 1\nb: [1, 2\nc: 3\n", "bad.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message().rfind("bad.yaml:", 0), 0u) << bad.status().message();
  const Result<Node> tab = Node::LoadString("a:\n  b: 1\n c: 2\n", "bad.yaml");
  ASSERT_FALSE(tab.ok());
  EXPECT_EQ(tab.status().message().rfind("bad.yaml:3: ", 0), 0u) << tab.status().message();
}

TEST(YamlReaderTest, LoadFileReadsAndReportsUnreadableFiles) {
  const std::filesystem::path dir = testing::TempDir();
  const std::filesystem::path path = dir / "yaml_reader_test.yaml";
  std::ofstream(path) << "x: 2.5\n";
  const Result<Node> root = Node::LoadFile(path);
  ASSERT_TRUE(root.ok());
  EXPECT_EQ(root->Get("x")->Where(), path.string() + ":1: x");
  const Result<Node> missing = Node::LoadFile(dir / "no_such_file.yaml");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("no_such_file.yaml"), std::string::npos);
}

TEST(YamlReaderTest, ReadOptionalKeepsDefaultsAndReportsErrors) {
  const Node lidar = *Load().Get("robot")->Get("lidar");
  double height = 1.0, range = 12.0;
  int beams = 0;
  bool flag = true;
  std::string name = "default";
  std::vector<double> list = {7.0};
  EXPECT_TRUE(ReadOptional(lidar, "height", &height).ok());
  EXPECT_TRUE(ReadOptional(lidar, "max_range", &range).ok());
  EXPECT_TRUE(ReadOptional(lidar, "beams", &beams).ok());
  EXPECT_TRUE(ReadOptional(lidar, "flag", &flag).ok());
  EXPECT_TRUE(ReadOptional(lidar, "name", &name).ok());
  EXPECT_TRUE(ReadOptional(lidar, "list", &list).ok());
  EXPECT_DOUBLE_EQ(height, 0.19);
  EXPECT_DOUBLE_EQ(range, 12.0);
  EXPECT_EQ(beams, 360);
  EXPECT_TRUE(flag);
  EXPECT_EQ(name, "default");
  EXPECT_EQ(list, std::vector<double>{7.0});
  EXPECT_EQ(ReadOptional(lidar, "hieght", &flag).message(),
            "world.yaml:13: robot.lidar.hieght: '3' is not a boolean (use true or false)");
  EXPECT_TRUE(flag);  // untouched on error
  EXPECT_TRUE(ReadOptional(Node(), "x", &height).ok());
}

}  // namespace
}  // namespace semchain::yaml
