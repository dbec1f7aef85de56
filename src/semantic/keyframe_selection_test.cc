#include "semantic/keyframe_selection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace semchain::semantic {
namespace {

KeyframeObject Object(int id, int upstream, int downstream) {
  KeyframeObject object;
  object.id = id;
  object.upstream = upstream;
  object.downstream = downstream;
  return object;
}

Keyframe Frame(const std::string& name, const Pose2& pose, std::vector<KeyframeObject> objects) {
  return {name, 0.0, pose, std::move(objects)};
}

std::vector<std::string> Names(const std::vector<Keyframe>& keyframes) {
  std::vector<std::string> names;
  for (const Keyframe& k : keyframes) names.push_back(k.frame);
  return names;
}

// A chain 1 – 2 – 3: frames along a drive past it, many of them from nearly the same pose.
std::vector<Keyframe> DrivePastAChain() {
  const KeyframeObject a = Object(1, -1, 2);
  const KeyframeObject b = Object(2, 1, 3);
  const KeyframeObject c = Object(3, 2, -1);
  return {
      Frame("f0", Pose2(0.0, 0, 0), {a}),       Frame("f1", Pose2(0.1, 0, 0), {a, b}),
      Frame("f2", Pose2(0.2, 0, 0), {a, b}),    Frame("f3", Pose2(0.3, 0, 0), {a, b, c}),
      Frame("f4", Pose2(0.4, 0, 0), {a, b, c}), Frame("f5", Pose2(1.5, 0, 0), {b, c}),
      Frame("f6", Pose2(1.6, 0, 0), {c}),       Frame("f7", Pose2(3.0, 0, 1.0), {a, b, c}),
  };
}

TEST(KeyframeSelectionTest, EveryObjectIsCoveredWithItsChainNeighbours) {
  KeyframeSelectionOptions options;
  options.views_per_object = 1;
  const std::vector<Keyframe> kept = SelectCoveringKeyframes(DrivePastAChain(), options);
  // One frame shows the whole chain, so it covers all three objects with their neighbours; the
  // first such frame is kept (ties keep the earlier).
  EXPECT_EQ(Names(kept), std::vector<std::string>({"f3"}));
}

TEST(KeyframeSelectionTest, ViewsComeFromDistinctPoses) {
  KeyframeSelectionOptions options;
  options.views_per_object = 3;
  const std::vector<Keyframe> kept = SelectCoveringKeyframes(DrivePastAChain(), options);
  // f3 and f4 are 0.1 m apart (one view); f7, 2.7 m on and turned, is a second; no third frame
  // shows the whole chain. Object 3's neighbourhood is itself and 2 (it ends the chain): f5
  // shows both and is its third view. A frame showing less of a neighbourhood than f3 does is
  // not a view of that object (f0, f1, f2, f6).
  EXPECT_EQ(Names(kept), std::vector<std::string>({"f3", "f5", "f7"}));
  // Turned by more than distinct_view_radians counts as another view at the same place.
  std::vector<Keyframe> frames = DrivePastAChain();
  frames[4].pose.theta = 0.5;
  EXPECT_EQ(Names(SelectCoveringKeyframes(frames, options)),
            std::vector<std::string>({"f3", "f4", "f7"}));
}

TEST(KeyframeSelectionTest, ObjectsOnlySeenAloneAreStillCovered) {
  // Object 9 (a chain of its own, or its neighbours never in the same frame) is seen only in f8.
  std::vector<Keyframe> frames = DrivePastAChain();
  frames.push_back(Frame("f8", Pose2(5, 5, 0), {Object(9, 4, 5)}));
  frames.push_back(Frame("f9", Pose2(5.05, 5, 0), {Object(9, 4, 5)}));
  const std::vector<Keyframe> kept = SelectCoveringKeyframes(frames, {});
  std::set<int> covered;
  for (const Keyframe& k : kept) {
    for (const KeyframeObject& o : k.objects) covered.insert(o.id);
  }
  EXPECT_EQ(covered, std::set<int>({1, 2, 3, 9}));
  const std::vector<std::string> names = Names(kept);
  EXPECT_EQ(std::count(names.begin(), names.end(), "f9"), 0);  // f8's view again
  EXPECT_LT(kept.size(), frames.size());
}

TEST(KeyframeSelectionTest, ZeroViewsKeepsEveryFrameAndBadOptionsAreRefused) {
  KeyframeSelectionOptions options;
  options.views_per_object = 0;
  EXPECT_EQ(SelectCoveringKeyframes(DrivePastAChain(), options).size(), 8u);
  EXPECT_TRUE(SelectCoveringKeyframes({}, {}).empty());
  std::string error;
  EXPECT_TRUE(options.Validate(&error));
  options.views_per_object = -1;
  EXPECT_FALSE(options.Validate(&error));
  EXPECT_NE(error.find("views_per_object"), std::string::npos);
}

}  // namespace
}  // namespace semchain::semantic
