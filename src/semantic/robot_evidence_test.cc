#include "semantic/robot_evidence.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/transforms.h"

namespace semchain::semantic {
namespace {

// A level camera 0.5 m up at the robot's centre, looking forward, before a wall 3 m away.
struct BoxFrame {
  MountedCamera camera;
  cv::Mat depth;
  BoxFrame() {
    camera.intrinsics = PinholeCamera::FromFov(160, 120, M_PI / 2);
    camera.robot_from_camera = RobotFromOpticalCamera(0.0, 0.0, 0.5, 0.0, 0.0);
    depth = cv::Mat(120, 160, CV_32FC1, cv::Scalar(3.0));
  }
  int Detections(const std::vector<Detection>& detections) const {
    return static_cast<int>(ComputeRobotEvidence({"f", 0.0, detections}, depth, DefaultClassNames(),
                                                 camera, SemanticMapOptions())
                                .detections.size());
  }
};

Detection NamedBox(const std::string& name, double x1, double x2, double depth,
                   double score = 0.8) {
  return {name, 0, score, {x1, 40.0, x2, 110.0}, depth};
}

TEST(RobotEvidenceTest, ABoxHalfInsideALargerOneOfItsClassIsOneObject) {
  // The detector's box of a whole bed and a second box on its left end, two thirds of it inside.
  const BoxFrame scene;
  EXPECT_EQ(
      scene.Detections({NamedBox("bed", 20, 140, 3.0, 0.55), NamedBox("bed", 0, 60, 3.0, 0.75)}),
      1);
  // Of another class it is another object.
  EXPECT_EQ(scene.Detections({NamedBox("bed", 20, 140, 3.0), NamedBox("sofa", 0, 60, 3.0)}), 2);
}

TEST(RobotEvidenceTest, TwoObjectsOfAClassSideBySideStayTwo) {
  // The boxes touch, or overlap by less than half the smaller (one partly hides the other).
  const BoxFrame wall;
  EXPECT_EQ(wall.Detections({NamedBox("chair", 10, 80, 3.0), NamedBox("chair", 80, 150, 3.0)}), 2);
  EXPECT_EQ(wall.Detections({NamedBox("chair", 10, 80, 3.0), NamedBox("chair", 60, 130, 3.0)}), 2);
}

}  // namespace
}  // namespace semchain::semantic
