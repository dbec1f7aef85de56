#include "bow/occlusion_inference.h"

#include <gtest/gtest.h>

#include "semantic/semantic_chain.h"

namespace semchain::bow {
namespace {

semantic::SemanticObject Object(int id, const std::string& name, double x, double y) {
  semantic::SemanticObject object;
  object.id = id;
  object.class_name = name;
  object.center = Eigen::Vector2d(x, y);
  return object;
}

// Seed 000 Fig. 21 as two rooms: room A's chain door 1 → cabinet 2 → bucket 3 → chair 4, room
// B's door 5 → chair 6 → cabinet 7 → stool 8 (each closed back to its door).
semantic::SemanticMap TwoRooms() {
  semantic::SemanticMap map;
  map.classes = DefaultClassNames();
  map.objects = {Object(1, "door", 1, 6),        Object(2, "cabinet", 3, 5.8),
                 Object(3, "bucket", 5.2, 5.8),  Object(4, "chair", 5.7, 4.6),
                 Object(5, "door", 10.8, 6),     Object(6, "chair", 11.7, 3.2),
                 Object(7, "cabinet", 6.2, 4.2), Object(8, "stool", 8.2, 5.7)};
  map.chains = {semantic::MakeChain(0, {1, 2, 3, 4}, map.objects),
                semantic::MakeChain(1, {5, 6, 7, 8}, map.objects)};
  return map;
}

Detection Seen(const std::string& name) {
  Detection detection;
  detection.class_name = name;
  return detection;
}

semantic::KeyframeObject InView(int id, const std::string& name) {
  semantic::KeyframeObject object;
  object.id = id;
  object.class_name = name;
  return object;
}

TEST(OcclusionInferenceTest, ClassVectorsAndTheirDifference) {
  // The paper's five classes, the first five of the default order.
  const std::vector<std::string> classes(DefaultClassNames().begin(),
                                         DefaultClassNames().begin() + 5);
  const std::vector<int> current = CountClasses({Seen("cabinet"), Seen("chair")}, classes);
  semantic::Keyframe keyframe;
  keyframe.objects = {InView(2, "cabinet"), InView(3, "bucket"), InView(4, "chair")};
  const std::vector<int> similar = CountClasses(keyframe, classes);
  // The paper's example (§4.2): (0,1,0,1,0) and (0,1,1,1,0) differ by the bucket.
  EXPECT_EQ(current, (std::vector<int>{0, 1, 0, 1, 0}));
  EXPECT_EQ(similar, (std::vector<int>{0, 1, 1, 1, 0}));
  EXPECT_EQ(ClassDifference(similar, current), (std::vector<int>{0, 0, 1, 0, 0}));
  // Other classes of the map come after the ten of seed 000; unknown names are not counted.
  semantic::SemanticMap map;
  map.classes = {"door", "plant"};
  EXPECT_EQ(CountVectorClasses(map).size(), 11u);
  EXPECT_EQ(CountVectorClasses(map).back(), "plant");
  EXPECT_EQ(
      CountClasses(std::vector<std::string>{"plant", "sofa", "fridge"}, CountVectorClasses(map)),
      (std::vector<int>{0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1}));
}

TEST(OcclusionInferenceTest, FindsTheHiddenBucketAndItsNeighbours) {
  const semantic::SemanticMap map = TwoRooms();
  semantic::Keyframe keyframe;
  keyframe.objects = {InView(2, "cabinet"), InView(3, "bucket"), InView(4, "chair")};
  const OcclusionInference result =
      InferOccludedObjects(map, keyframe, {Seen("cabinet"), Seen("chair")});
  ASSERT_EQ(result.occluded.size(), 1u) << result.reason;
  EXPECT_TRUE(result.reason.empty());
  const OccludedObject& bucket = result.occluded[0];
  EXPECT_EQ(bucket.id, 3);
  EXPECT_EQ(bucket.class_name, "bucket");
  EXPECT_EQ(bucket.upstream, 2);
  EXPECT_EQ(bucket.downstream, 4);
  EXPECT_NEAR(bucket.neighbours_distance,
              (Eigen::Vector2d(3, 5.8) - Eigen::Vector2d(5.7, 4.6)).norm(), 1e-12);
}

TEST(OcclusionInferenceTest, NeighboursNotSeenNowLeaveItUndecided) {
  const semantic::SemanticMap map = TwoRooms();
  semantic::Keyframe keyframe;
  keyframe.objects = {InView(2, "cabinet"), InView(3, "bucket"), InView(4, "chair")};
  // Only the cabinet is seen: the bucket's downstream chair is missing too.
  const OcclusionInference result = InferOccludedObjects(map, keyframe, {Seen("cabinet")});
  EXPECT_TRUE(result.occluded.empty());
  EXPECT_NE(result.reason.find("bucket: no chain node"), std::string::npos) << result.reason;
}

TEST(OcclusionInferenceTest, FallsBackToTheChainWhenTheKeyframeObjectDoesNotFit) {
  semantic::SemanticMap map = TwoRooms();
  // Room B's stool (8) sits between cabinet 7 and door 5. A keyframe whose stool is no node of
  // the map (id 99, e.g. a keyframe list from an older map) cannot decide by itself...
  semantic::Keyframe keyframe;
  keyframe.objects = {InView(99, "stool"), InView(3, "bucket")};
  const OcclusionInference result =
      InferOccludedObjects(map, keyframe, {Seen("cabinet"), Seen("door"), Seen("bucket")});
  // ... but the map's only stool has neighbours cabinet 7 and door 5, both seen now.
  ASSERT_EQ(result.occluded.size(), 1u) << result.reason;
  EXPECT_EQ(result.occluded[0].id, 8);
  EXPECT_EQ(result.occluded[0].upstream, 7);
  EXPECT_EQ(result.occluded[0].downstream, 5);
}

TEST(OcclusionInferenceTest, AmbiguousNodesAreReportedNotGuessed) {
  semantic::SemanticMap map = TwoRooms();
  // Room B gets a second bucket between cabinet 7 and chair... a chain 5 → 6 → 7 → 9 → 10.
  map.objects.push_back(Object(9, "bucket", 7.0, 5.0));
  map.objects.push_back(Object(10, "chair", 7.5, 5.5));
  map.chains[1] = semantic::MakeChain(1, {5, 6, 7, 9, 10}, map.objects);
  semantic::Keyframe keyframe;  // a keyframe whose own bucket is not in view now
  keyframe.objects = {InView(2, "cabinet"), InView(4, "chair"), InView(9, "bucket")};
  const OcclusionInference result =
      InferOccludedObjects(map, keyframe, {Seen("cabinet"), Seen("chair")});
  // Bucket 9 (between cabinet 7 and chair 10) fits from the keyframe itself.
  ASSERT_EQ(result.occluded.size(), 1u);
  EXPECT_EQ(result.occluded[0].id, 9);
  // Without a bucket in the keyframe's record both buckets of the map fit: no guess.
  keyframe.objects = {InView(2, "cabinet"), InView(4, "chair"), InView(11, "bucket")};
  const OcclusionInference ambiguous =
      InferOccludedObjects(map, keyframe, {Seen("cabinet"), Seen("chair")});
  EXPECT_TRUE(ambiguous.occluded.empty());
  EXPECT_NE(ambiguous.reason.find("bucket: 2 chain nodes fit (ids 3, 9)"), std::string::npos)
      << ambiguous.reason;
}

TEST(OcclusionInferenceTest, RankedUsesTheFirstKeyframeCoveringTheCurrentClasses) {
  const semantic::SemanticMap map = TwoRooms();
  semantic::Keyframe same;  // the most similar keyframe shows what is seen now and nothing more
  same.objects = {InView(2, "cabinet"), InView(4, "chair")};
  semantic::Keyframe other;  // the next one lacks the chair seen now
  other.objects = {InView(2, "cabinet"), InView(3, "bucket")};
  semantic::Keyframe covering;  // the third shows cabinet and chair and the bucket between them
  covering.objects = {InView(2, "cabinet"), InView(3, "bucket"), InView(4, "chair")};
  const std::vector<Detection> now = {Seen("cabinet"), Seen("chair")};
  const RankedOcclusionInference result =
      InferOccludedObjects(map, {&same, &other, &covering}, now);
  EXPECT_EQ(result.used, 2);
  ASSERT_EQ(result.inference.occluded.size(), 1u);
  EXPECT_EQ(result.inference.occluded[0].id, 3);
  // No keyframe covers: the most similar one is used and its inference says why it fails.
  const RankedOcclusionInference none = InferOccludedObjects(map, {&same, &other}, now);
  EXPECT_EQ(none.used, 0);
  EXPECT_TRUE(none.inference.occluded.empty());
  EXPECT_EQ(InferOccludedObjects(map, std::vector<const semantic::Keyframe*>{}, now).used, -1);
}

// A chain wraps from one end of a hall to the other: the west door between a bucket 20 m east
// and a stool at the west wall has both neighbours' classes in view, but the two are never in
// one frame, so the door is no candidate; the bay's cabinet between the same classes 2 m apart is.
semantic::SemanticMap Hall() {
  semantic::SemanticMap map;
  map.classes = DefaultClassNames();
  map.objects = {Object(1, "door", 0, 3), Object(2, "stool", 9, 5.8), Object(3, "cabinet", 10, 5.8),
                 Object(4, "bucket", 11, 5.8), Object(5, "bucket", 29, 0.2)};
  map.chains = {semantic::MakeChain(0, {5, 1, 2, 3, 4}, map.objects)};  // 4 links back to 5
  return map;
}

TEST(OcclusionInferenceTest, NeighboursTooFarApartForOneFrameDoNotFit) {
  const semantic::SemanticMap map = Hall();
  const std::vector<Detection> now = {Seen("stool"), Seen("bucket")};
  semantic::Keyframe west_end;  // a keyframe at the west door
  west_end.objects = {InView(1, "door"), InView(2, "stool"), InView(5, "bucket")};
  const OcclusionInference door = InferOccludedObjects(map, west_end, now);
  EXPECT_TRUE(door.occluded.empty());
  EXPECT_NE(door.reason.find("door: no chain node"), std::string::npos) << door.reason;
  semantic::Keyframe bay;
  bay.objects = {InView(2, "stool"), InView(3, "cabinet"), InView(4, "bucket")};
  const OcclusionInference cabinet = InferOccludedObjects(map, bay, now);
  ASSERT_EQ(cabinet.occluded.size(), 1u) << cabinet.reason;
  EXPECT_EQ(cabinet.occluded[0].id, 3);
  EXPECT_NEAR(cabinet.occluded[0].neighbours_distance, 2.0, 1e-12);
}

TEST(OcclusionInferenceTest, RankedPassesOverACoveringKeyframeThatNamesNothing) {
  const semantic::SemanticMap map = Hall();
  const std::vector<Detection> now = {Seen("stool"), Seen("bucket")};
  semantic::Keyframe west_end;  // more similar, covers the classes seen now, names nothing
  west_end.objects = {InView(1, "door"), InView(2, "stool"), InView(5, "bucket")};
  semantic::Keyframe bay;
  bay.objects = {InView(2, "stool"), InView(3, "cabinet"), InView(4, "bucket")};
  const RankedOcclusionInference result = InferOccludedObjects(map, {&west_end, &bay}, now);
  EXPECT_EQ(result.used, 1);
  ASSERT_EQ(result.inference.occluded.size(), 1u);
  EXPECT_EQ(result.inference.occluded[0].id, 3);
  // Alone, the covering keyframe that names nothing is used, and says why.
  const RankedOcclusionInference alone = InferOccludedObjects(map, {&west_end}, now);
  EXPECT_EQ(alone.used, 0);
  EXPECT_TRUE(alone.inference.occluded.empty());
  EXPECT_FALSE(alone.inference.reason.empty());
}

TEST(OcclusionInferenceTest, NothingMissingSaysSo) {
  const semantic::SemanticMap map = TwoRooms();
  semantic::Keyframe keyframe;
  keyframe.objects = {InView(2, "cabinet"), InView(4, "chair")};
  const OcclusionInference result =
      InferOccludedObjects(map, keyframe, {Seen("cabinet"), Seen("chair")});
  EXPECT_TRUE(result.occluded.empty());
  EXPECT_EQ(result.reason, "no class of the keyframe is missing in the current frame");
}

}  // namespace
}  // namespace semchain::bow
