#include "localization/decision_gate.h"

#include <gtest/gtest.h>

namespace semchain::localization {
namespace {

// An empty free map: the gate only asks the pre-localizer whether hypotheses stand out and
// whether two poses are distinct places.
mapping::MapImage EmptyMap() {
  mapping::MapImage map;
  map.resolution = 0.05;
  map.width = 20;
  map.height = 20;
  map.cells.assign(400, 0);
  return map;
}

PoseCandidate Hypothesis(double x, double y, int agreeing, double laser) {
  PoseCandidate candidate;
  candidate.pose = Pose2(x, y, 0.0);
  candidate.agreeing = agreeing;
  candidate.laser_score = laser;
  return candidate;
}

// The default gate, but every pre-localization at the leading place confirms it (the hypotheses
// below explain no mapped object by name, and the odometry does not turn).
const DecisionGateOptions kEveryFrameConfirms = [] {
  DecisionGateOptions options;
  options.confirmation_turn = 0.0;
  return options;
}();

class DecisionGateTest : public ::testing::Test {
 protected:
  DecisionGateTest() : prelocalizer_(semantic::SemanticMap(), EmptyMap(), {}) {}

  PreLocalizer prelocalizer_;
  // Look-alike offices 6 m apart: the right one (x = 2) and another (x = 8).
  const std::vector<PoseCandidate> tied_ = {Hypothesis(2, 1, 2, 0.9), Hypothesis(8, 1, 2, 0.88)};
  const std::vector<PoseCandidate> other_alone_ = {Hypothesis(8, 1, 2, 0.9)};
  const std::vector<PoseCandidate> right_with_more_ = {Hypothesis(2, 1, 3, 0.9),
                                                       Hypothesis(8, 1, 2, 0.9)};
};

TEST_F(DecisionGateTest, APlaceMustStandOutTwice) {
  DecisionGate gate(prelocalizer_, {2, false, 1.0, 0.55, 0.0});
  const Pose2 odometry(0.0, 0.0, 0.0);
  EXPECT_FALSE(gate.Update(other_alone_, odometry));
  EXPECT_TRUE(gate.Update(other_alone_, odometry));
  // A place explaining more, or a look-alike tie, starts the count again.
  EXPECT_FALSE(gate.Update(right_with_more_, odometry));
  EXPECT_FALSE(gate.Update(tied_, odometry));
  EXPECT_FALSE(gate.Update(right_with_more_, odometry));
  EXPECT_TRUE(gate.Update(right_with_more_, odometry));
  // The place is compared where odometry carries it: the robot turned a quarter turn in place,
  // the hypothesis turned with it.
  DecisionGate turning(prelocalizer_, {2, false, 1.0, 0.55, 0.0});
  EXPECT_FALSE(turning.Update({Hypothesis(8, 1, 2, 0.9)}, Pose2(0.0, 0.0, 0.0)));
  PoseCandidate turned = Hypothesis(8, 1, 2, 0.9);
  turned.pose.theta = 1.5;
  EXPECT_TRUE(turning.Update({turned}, Pose2(0.0, 0.0, 1.5)));
  // With one confirmation each pre-localization decides on its own.
  DecisionGate single(prelocalizer_, {1, false, 1.0, 0.55, 0.0});
  EXPECT_TRUE(single.Update(other_alone_, odometry));
}

// lab_loop seed 2, trial 13: the right place stood out with a near-perfect laser fit; in the next
// frames its pair was placed too far off and a lone look-alike with a poor fit stood out instead,
// or no pair fitted at all. Neither is evidence against the first.
TEST_F(DecisionGateTest, AWeakerLonePlaceOrNoHypothesisDoesNotInterruptTheCount) {
  DecisionGate gate(prelocalizer_, {2, false, 1.0, 0.55, 0.0});
  const Pose2 odometry(0.0, 0.0, 0.0);
  const std::vector<PoseCandidate> right = {Hypothesis(2, 1, 2, 0.98)};
  EXPECT_FALSE(gate.Update(right, odometry));
  EXPECT_FALSE(gate.Update({Hypothesis(8, 1, 2, 0.38)}, odometry));  // worse fit
  EXPECT_FALSE(gate.Update({}, odometry));
  EXPECT_FALSE(gate.Update({Hypothesis(5, 4, 1, 0.99)}, odometry));  // fewer objects
  EXPECT_TRUE(gate.Update(right, odometry));
  // A lone place with a better fit, or explaining more, takes the lead and counts from one.
  DecisionGate better(prelocalizer_, {2, false, 1.0, 0.55, 0.0});
  EXPECT_FALSE(better.Update(right, odometry));
  EXPECT_FALSE(better.Update({Hypothesis(8, 1, 2, 0.99)}, odometry));
  EXPECT_FALSE(better.Update(right, odometry));  // weaker than the new leader now
  EXPECT_TRUE(better.Update({Hypothesis(8, 1, 2, 0.99)}, odometry));
}

TEST_F(DecisionGateTest, AfterATieOnlyMoreObjectsDecide) {
  DecisionGate gate(prelocalizer_, {1, true, 1.0, 0.55, 0.0});
  const Pose2 odometry(0.0, 0.0, 0.0);
  EXPECT_FALSE(gate.Update(tied_, odometry));
  // The look-alike office alone, explaining the same two objects: the right one was left out,
  // not ruled out.
  EXPECT_FALSE(gate.Update(other_alone_, odometry));
  EXPECT_FALSE(gate.Update(other_alone_, odometry));
  // A third object only the right office explains decides.
  EXPECT_TRUE(gate.Update(right_with_more_, odometry));
  // An object the bag of words names hidden there is evidence the tie did not have.
  DecisionGate bow(prelocalizer_, {1, true, 1.0, 0.55, 0.0});
  EXPECT_FALSE(bow.Update(tied_, odometry));
  EXPECT_FALSE(bow.Update(other_alone_, odometry));
  EXPECT_TRUE(bow.Update(other_alone_, odometry, 1));
  // Without the rule the lone look-alike decides.
  DecisionGate plain(prelocalizer_, {1, false, 1.0, 0.55, 0.0});
  EXPECT_FALSE(plain.Update(tied_, odometry));
  EXPECT_TRUE(plain.Update(other_alone_, odometry));
}

TEST_F(DecisionGateTest, TheTieIsForgottenAfterTheRobotMoved) {
  DecisionGate gate(prelocalizer_, {1, true, 1.0, 0.55, 0.0});
  EXPECT_FALSE(gate.Update(tied_, Pose2(0.0, 0.0, 0.0)));
  EXPECT_FALSE(gate.Update(other_alone_, Pose2(0.9, 0.0, 0.0)));
  EXPECT_TRUE(gate.Update(other_alone_, Pose2(1.1, 0.0, 0.0)));
  // Reset forgets it too.
  EXPECT_FALSE(gate.Update(tied_, Pose2(0.0, 0.0, 0.0)));
  gate.Reset();
  EXPECT_TRUE(gate.Update(other_alone_, Pose2(0.0, 0.0, 0.0)));
}

// office_floor seed 13 (development), trial 2: a stool, a bucket and a sofa fitted a look-alike
// office 13 m away, the scan fitting it poorly (0.34, then 0.43 after the laser's refinement),
// and it stood out twice before the right office, explaining five objects, appeared. seed 7,
// trial 26: the right office placed 0.54 m off fitted 0.33 and a lone look-alike explaining two
// of its four objects stood out twice.
TEST_F(DecisionGateTest, APoorlyFittingPlaceDecidesNothingAndOutranksPlacesExplainingFewer) {
  const Pose2 odometry(0.0, 0.0, 0.0);
  const std::vector<PoseCandidate> poor = {Hypothesis(8, 1, 3, 0.43)};
  DecisionGate gate(prelocalizer_, kEveryFrameConfirms);
  EXPECT_FALSE(gate.Update(poor, odometry));
  EXPECT_FALSE(gate.Update(poor, odometry));
  // A place elsewhere that fits well but explains fewer objects is not decided over it...
  const std::vector<PoseCandidate> fewer = {Hypothesis(2, 1, 2, 0.9)};
  EXPECT_FALSE(gate.Update(fewer, odometry));
  EXPECT_FALSE(gate.Update(fewer, odometry));
  // ... one explaining as many is.
  const std::vector<PoseCandidate> as_many = {Hypothesis(2, 1, 3, 0.9)};
  EXPECT_FALSE(gate.Update(as_many, odometry));
  EXPECT_TRUE(gate.Update(as_many, odometry));
  // The poor fit is forgotten with the rest of the turn's evidence.
  DecisionGate forgetting(prelocalizer_, kEveryFrameConfirms);
  EXPECT_FALSE(forgetting.Update(poor, odometry));
  EXPECT_FALSE(forgetting.Update(fewer, Pose2(1.5, 0.0, 0.0)));
  EXPECT_TRUE(forgetting.Update(fewer, Pose2(1.5, 0.0, 0.0)));
  // Without the laser's condition the poor place is decided, as before.
  DecisionGate without(prelocalizer_, {2, true, 1.0, 0.0, 0.0});
  EXPECT_FALSE(without.Update(poor, odometry));
  EXPECT_TRUE(without.Update(poor, odometry));
}

// office_floor seed 16 (development), trial 12: a table, a computer and a cabinet fitted an
// office 19 m away, and the same three, seen again 0.2 s later, confirmed it.
TEST_F(DecisionGateTest, OnlyANewObjectOrANewViewConfirms) {
  PoseCandidate three = Hypothesis(8, 1, 3, 0.7);
  three.matches = {{0, 73}, {1, 87}, {2, 26}};
  DecisionGate gate(prelocalizer_, {});
  EXPECT_FALSE(gate.Update({three}, Pose2(0.0, 0.0, 0.0)));
  // The same objects again, the robot turned 0.16 rad: nothing new.
  PoseCandidate again = three;
  again.pose.theta = 0.16;
  EXPECT_FALSE(gate.Update({again}, Pose2(0.0, 0.0, 0.16)));
  EXPECT_FALSE(gate.Update({again}, Pose2(0.0, 0.0, 0.16)));
  // An object the place did not explain before confirms it...
  PoseCandidate more = again;
  more.matches.push_back({3, 12});
  EXPECT_TRUE(gate.Update({more}, Pose2(0.0, 0.0, 0.16)));
  // ... as does the same objects seen after half a camera view of turning.
  DecisionGate turning(prelocalizer_, {});
  EXPECT_FALSE(turning.Update({three}, Pose2(0.0, 0.0, 0.0)));
  PoseCandidate turned = three;
  turned.pose.theta = 0.3;
  EXPECT_FALSE(turning.Update({turned}, Pose2(0.0, 0.0, 0.3)));
  turned.pose.theta = 0.55;
  EXPECT_TRUE(turning.Update({turned}, Pose2(0.0, 0.0, 0.55)));
}

}  // namespace
}  // namespace semchain::localization
