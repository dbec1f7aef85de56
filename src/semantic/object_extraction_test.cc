#include "semantic/object_extraction.h"

#include <gtest/gtest.h>

namespace semchain::semantic {
namespace {

const GridGeometry kGeometry{80, 60, 0.05, Eigen::Vector2d(0.0, 0.0)};
const std::vector<std::string> kClasses = {"door", "cabinet", "bucket"};

// A horizontal face of 'length' cells starting at cell (x, y).
std::vector<Eigen::Vector2i> Face(int x, int y, int length) {
  std::vector<Eigen::Vector2i> cells;
  for (int i = 0; i < length; ++i) cells.emplace_back(x + i, y);
  return cells;
}

// Hand-made evidence: each frame, each face in 'faces' is one cabinet detection seen from the
// south (the camera at y = 0).
struct Scene {
  SemanticGrid grid{kGeometry, 3, SemanticGridOptions()};
  std::vector<DetectionObservation> observations;
  int frames = 0;

  void Frame(const std::vector<std::vector<Eigen::Vector2i>>& faces) {
    FrameEvidence evidence;
    evidence.hits.resize(3);
    evidence.viewer = Eigen::Vector2d(2.0, 0.0);
    for (const auto& face : faces) {
      for (const Eigen::Vector2i& cell : face) {
        evidence.hits[1].push_back({cell, kGeometry.CenterOf(cell)});
      }
      observations.push_back({frames, 1, 0.9, face});
    }
    grid.Update(evidence);
    ++frames;
  }
};

TEST(ObjectExtractionTest, SeparateFacesBecomeObjectsCompletedBehindTheirFront) {
  Scene scene;
  const auto left = Face(10, 20, 12);   // x 0.50–1.10, y 1.00–1.05
  const auto right = Face(40, 20, 12);  // x 2.00–2.60
  for (int i = 0; i < 4; ++i) scene.Frame({left, right});
  const ExtractedObjects result =
      ExtractObjects(scene.grid, scene.observations, kClasses, SemanticMapOptions());
  ASSERT_EQ(result.objects.size(), 2u);
  const SemanticObject& a = result.objects[0];
  EXPECT_EQ(a.class_name, "cabinet");
  EXPECT_EQ(a.observations, 4);
  EXPECT_GT(a.confidence, 0.9);
  // The face (cell centres at y = 1.025) is the front; the default cabinet prior is 0.4 m deep,
  // so the centre is 0.2 m behind it, away from the camera.
  EXPECT_NEAR(a.center.x(), 0.525 + 0.275, 0.02);
  EXPECT_NEAR(a.center.y(), 1.025 + 0.2, 0.03);
  EXPECT_NEAR(result.objects[1].center.x(), 2.025 + 0.275, 0.02);
  for (int id : result.observation_object) EXPECT_GE(id, 0);
}

TEST(ObjectExtractionTest, TouchingObjectsSeenTogetherAreSplit) {
  Scene scene;
  // Two cabinets side by side: one continuous face, but two detections in every frame.
  const auto left = Face(10, 20, 6);
  const auto right = Face(16, 20, 6);
  for (int i = 0; i < 4; ++i) scene.Frame({left, right});
  const ExtractedObjects result =
      ExtractObjects(scene.grid, scene.observations, kClasses, SemanticMapOptions());
  ASSERT_EQ(result.objects.size(), 2u);
  const double x0 = std::min(result.objects[0].center.x(), result.objects[1].center.x());
  const double x1 = std::max(result.objects[0].center.x(), result.objects[1].center.x());
  EXPECT_NEAR(x0, 0.5 + 0.15, 0.03);
  EXPECT_NEAR(x1, 0.8 + 0.15, 0.03);
}

// A real detector sees one cabinet in 40 frames and, in 3 of them, puts a second box of the
// class on part of it (a neighbour misnamed, or a part taken for a whole): one object, not two.
// Going by the count of such frames alone (min_split_share 0) splits it.
TEST(ObjectExtractionTest, ASecondBoxInAFewOfManyFramesDoesNotSplitAnObject) {
  Scene scene;
  const auto front = Face(10, 20, 12);  // x 0.50–1.10
  const auto part = Face(16, 20, 6);    // its right half
  for (int i = 0; i < 37; ++i) scene.Frame({front});
  for (int i = 0; i < 3; ++i) scene.Frame({front, part});
  const ExtractedObjects one =
      ExtractObjects(scene.grid, scene.observations, kClasses, SemanticMapOptions());
  ASSERT_EQ(one.objects.size(), 1u);
  EXPECT_NEAR(one.objects[0].center.x(), 0.525 + 0.275, 0.02);
  EXPECT_EQ(one.objects[0].observations, 40);

  SemanticMapOptions count_only;
  count_only.extraction.min_split_share = 0.0;
  EXPECT_EQ(ExtractObjects(scene.grid, scene.observations, kClasses, count_only).objects.size(),
            2u);
}

TEST(ObjectExtractionTest, FragmentsOfOneObjectAreJoinedAndRareOnesDropped) {
  Scene scene;
  // The front of a cabinet, and (in other frames) a short piece of it 3 cells beyond its end,
  // as when the image edge cuts it off.
  const auto front = Face(10, 20, 10);
  const auto piece = Face(23, 20, 2);
  for (int i = 0; i < 5; ++i) scene.Frame({front});
  for (int i = 0; i < 3; ++i) scene.Frame({piece});
  // Seen in two frames only: noise.
  const auto rare = Face(50, 40, 4);
  for (int i = 0; i < 2; ++i) scene.Frame({rare});
  const ExtractedObjects result =
      ExtractObjects(scene.grid, scene.observations, kClasses, SemanticMapOptions());
  ASSERT_EQ(result.objects.size(), 1u);
  EXPECT_EQ(result.objects[0].observations, 8);
  EXPECT_EQ(result.observation_object.back(), -1);
}

}  // namespace
}  // namespace semchain::semantic
