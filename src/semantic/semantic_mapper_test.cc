#include "semantic/semantic_mapper.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/transforms.h"
#include "semantic/semantic_chain.h"

namespace semchain::semantic {
namespace {

// A level camera 0.5 m up and 0.1 m ahead of the robot centre, looking forward.
MountedCamera ForwardCamera() {
  MountedCamera camera;
  camera.intrinsics = PinholeCamera::FromFov(160, 120, M_PI / 2);
  camera.robot_from_camera = RobotFromOpticalCamera(0.1, 0.0, 0.5, 0.0, 0.0);
  return camera;
}

// A wall 2 m ahead with a cabinet 1.5 m ahead in the middle of the image.
cv::Mat Depth() {
  cv::Mat depth(120, 160, CV_32FC1, cv::Scalar(2.0));
  depth(cv::Rect(60, 30, 40, 80)).setTo(1.5);
  return depth;
}

FrameDetections Frame(int i) {
  return {"frames/" + std::to_string(i), 0.5 * i, {{"cabinet", 1, 0.9, {60, 30, 100, 110}, 1.5}}};
}

const GridGeometry kLattice{0, 0, 0.05, Eigen::Vector2d::Zero()};

std::vector<Pose2> Poses(double shift) {
  std::vector<Pose2> poses;
  for (int i = 0; i < 8; ++i) {
    // The second half of the run moves by 'shift' (a loop closing late).
    const double late = i >= 4 ? shift : 0.0;
    poses.emplace_back(1.0 + 0.1 * i + late, 1.0 + late, 0.05 * i + late);
  }
  return poses;
}

void ExpectSameGrid(const SemanticMapper& a, const SemanticMapper& b) {
  mapping::MapImage map;
  map.width = 120;
  map.height = 120;
  map.resolution = 0.05;
  map.origin = Eigen::Vector3d(-1.0, -1.0, 0.0);
  const SemanticGrid ga = a.grid().Crop(GeometryOf(map));
  const SemanticGrid gb = b.grid().Crop(GeometryOf(map));
  for (int c = 0; c < ga.class_count(); ++c) {
    EXPECT_EQ(cv::norm(ga.log_odds(c), gb.log_odds(c), cv::NORM_INF), 0.0) << "class " << c;
  }
}

// Re-posing the frames that moved gives the grid that mapping them on the new poses gives,
// whether only the touched cells are rebuilt or the whole grid.
TEST(SemanticMapperTest, ReposedFramesEqualFramesMappedOnTheNewPoses) {
  for (const double fraction : {0.9, 0.1}) {
    SemanticMapperOptions options;
    options.full_rebuild_fraction = fraction;
    SemanticMapper live(kLattice, DefaultClassNames(), ForwardCamera(), SemanticMapOptions(),
                        options);
    SemanticMapper batch(kLattice, DefaultClassNames(), ForwardCamera(), SemanticMapOptions(),
                         options);
    const std::vector<Pose2> before = Poses(0.0);
    const std::vector<Pose2> after = Poses(0.3);
    for (int i = 0; i < 8; ++i) {
      live.AddFrame(Frame(i), before[i], Depth());
      batch.AddFrame(Frame(i), after[i], Depth());
    }
    EXPECT_EQ(live.Repose(after), 4);
    EXPECT_EQ(live.statistics().reprojections, 1);
    EXPECT_EQ(live.statistics().incremental_reprojections, fraction > 0.5 ? 1 : 0);
    ExpectSameGrid(live, batch);
    // Within the tolerance nothing moves; exactly, everything that moved does.
    std::vector<Pose2> nudged = after;
    nudged[1].x += 0.01;
    EXPECT_EQ(live.Repose(nudged), 0);
    EXPECT_EQ(live.Repose(nudged, /*exact=*/true), 1);
  }
}

// The grid grows with the evidence: frames far from the first map's extent keep their cells.
TEST(SemanticMapperTest, GridGrowsWithTheEvidence) {
  SemanticMapper mapper(kLattice, DefaultClassNames(), ForwardCamera(), SemanticMapOptions());
  mapper.AddFrame(Frame(0), Pose2(-20.0, 30.0, 0.0), Depth());
  // The cabinet's face: 1.5 m ahead of the camera, 0.1 m ahead of the robot.
  const Eigen::Vector2i cabinet = kLattice.CellOf(Eigen::Vector2d(-18.39, 30.0));
  EXPECT_TRUE(mapper.grid().Contains(cabinet));
  EXPECT_GT(mapper.grid().LogOdds(1, cabinet), 0.0f);
}

}  // namespace
}  // namespace semchain::semantic
