#include "sim/world_drawing.h"

#include <gtest/gtest.h>

#include "drawing/canvas.h"
#include "sim/furnished_room.h"

namespace semchain::sim {
namespace {

cv::Vec3b At(drawing::TopDownCanvas& canvas, const Eigen::Vector2d& p) {
  const cv::Point2d px = canvas.ToPixel(p);
  return canvas.image().at<cv::Vec3b>(static_cast<int>(px.y), static_cast<int>(px.x));
}

cv::Vec3b Bgr(const drawing::Color& c) { return cv::Vec3b(c[2], c[1], c[0]); }

TEST(WorldDrawingTest, DrawsWallsObjectsAndObstacles) {
  const World world = FurnishedRoomWorld();
  Result<drawing::TopDownCanvas> canvas = drawing::TopDownCanvas::Create(WorldBounds(world), {});
  ASSERT_TRUE(canvas.ok());
  DrawWorld(world, *canvas);
  EXPECT_EQ(At(*canvas, {4.0, 0.0}), cv::Vec3b(0, 0, 0));        // the wall y = 0
  EXPECT_EQ(At(*canvas, {7.7, 3.5}), Bgr(ClassColor(1)));        // the cabinet's centre
  EXPECT_EQ(At(*canvas, {4.0, 2.2}), Bgr({150, 150, 150}));      // the column
  EXPECT_EQ(At(*canvas, {2.0, 4.0}), cv::Vec3b(255, 255, 255));  // free floor
  // The legend panel lists the classes.
  EXPECT_EQ(canvas->Compose().cols,
            canvas->image().cols + drawing::DrawingOptions().legend_width_px);
}

}  // namespace
}  // namespace semchain::sim
