#include "detection/class_map.h"

#include <gtest/gtest.h>

#include "detection/class_nms.h"
#include "sensors/detection.h"

namespace semchain::detection {
namespace {

const std::vector<std::string> kModelClasses = {"person", "chair", "couch", "tv", "laptop"};

Result<ClassMap> Parse(const std::string& text) {
  Result<yaml::Node> root = yaml::Node::LoadString(text, "map.yaml");
  if (!root.ok()) return root.status();
  return ParseClassMap(*root, kModelClasses);
}

std::string ErrorOf(const std::string& text) {
  const Result<ClassMap> map = Parse(text);
  return map.ok() ? "no error" : map.status().message();
}

int Semchain(const std::string& name) {
  const std::vector<std::string>& names = DefaultClassNames();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

TEST(ClassMapTest, MapsMergesAndDropsModelClasses) {
  const Result<ClassMap> map = Parse("chair: chair\ncouch: sofa\ntv: computer\nlaptop: computer\n");
  ASSERT_TRUE(map.ok()) << map.status().message();
  EXPECT_EQ(map->classes, DefaultClassNames());
  EXPECT_EQ(map->target, (std::vector<int>{-1, Semchain("chair"), Semchain("sofa"),
                                           Semchain("computer"), Semchain("computer")}));
}

TEST(ClassMapTest, NamesTheFileLineAndKeyOfAnError) {
  EXPECT_EQ(ErrorOf("chair: chair\ntv: television\n"),
            "map.yaml:2: tv: 'television' is not a semchain class (door, cabinet, bucket, chair, "
            "stool, table, sofa, computer, bed, clock)");
  EXPECT_EQ(ErrorOf("chair: chair\nsofa: sofa\n"),
            "map.yaml:2: sofa: not a class of the model (its 5 classes: person, chair, couch, tv, "
            "laptop)");
  EXPECT_EQ(ErrorOf("tv: computer\ntv: computer\n"), "map.yaml:2: tv: duplicate key");
  EXPECT_EQ(ErrorOf("tv: [computer]\n"), "map.yaml:1: tv: expected a string, got a sequence");
  EXPECT_EQ(ErrorOf("- tv\n"),
            "map.yaml:1: expected a map of 'model class: semchain class' entries");
  EXPECT_EQ(ErrorOf("{}\n"), "map.yaml:1: maps no class");
}

TEST(ClassMapTest, TheShippedCocoMapFitsCocosClasses) {
  const std::vector<std::string> coco_subset = {"person", "chair",  "couch", "bed", "dining table",
                                                "tv",     "laptop", "clock", "book"};
  Result<ClassMap> map = LoadClassMap(
      std::filesystem::path(SEMCHAIN_SOURCE_DIR) / "config/classes/coco.yaml", coco_subset);
  ASSERT_TRUE(map.ok()) << map.status().message();
  EXPECT_EQ(map->target, (std::vector<int>{-1, Semchain("chair"), Semchain("sofa"), Semchain("bed"),
                                           Semchain("table"), Semchain("computer"),
                                           Semchain("computer"), Semchain("clock"), -1}));
}

// Two boxes on one object, one called tv and one laptop by the model: mapped, they are both
// computers, and the class-wise NMS after the map keeps the better one. Unmapped, the two
// classes keep both. A person is dropped.
TEST(ClassMapTest, MergedClassesSuppressEachOtherInTheNmsAfterTheMap) {
  const Result<ClassMap> map = Parse("tv: computer\nlaptop: computer\nchair: chair\n");
  ASSERT_TRUE(map.ok()) << map.status().message();
  const std::vector<Candidate> candidates = {{cv::Rect2d(10, 10, 100, 80), 3, 0.6f},
                                             {cv::Rect2d(12, 11, 98, 80), 4, 0.7f},
                                             {cv::Rect2d(12, 11, 98, 80), 0, 0.9f},
                                             {cv::Rect2d(300, 10, 50, 90), 1, 0.5f}};
  EXPECT_EQ(ClassWiseNms(candidates, 0.45, 100).size(), 4u);
  const std::vector<Candidate> mapped = MapCandidates(candidates, *map);
  ASSERT_EQ(mapped.size(), 3u);  // the person is gone
  const std::vector<int> kept = ClassWiseNms(mapped, 0.45, 100);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(mapped[static_cast<std::size_t>(kept[0])].class_id, Semchain("computer"));
  EXPECT_FLOAT_EQ(mapped[static_cast<std::size_t>(kept[0])].score, 0.7f);  // the laptop's box
  EXPECT_EQ(mapped[static_cast<std::size_t>(kept[1])].class_id, Semchain("chair"));
}

}  // namespace
}  // namespace semchain::detection
