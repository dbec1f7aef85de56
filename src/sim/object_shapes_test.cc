#include "sim/object_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "core/angles.h"
#include "core/rng.h"
#include "sensors/detection.h"
#include "sim/detection_model.h"
#include "sim/lidar.h"
#include "sim/rgbd_renderer.h"
#include "sim/scene.h"

namespace semchain::sim {
namespace {

// An object of 'class_name' built of parts at (x, y), its front (-y in its frame) facing the
// camera of a robot at the origin looking along +x when yaw is π/2.
Solid ClassObject(const std::string& class_name, double x, double y, double width, double depth,
                  double height, double base = 0.0, std::uint32_t seed = 5) {
  Solid solid;
  solid.class_name = class_name;
  solid.shape = ObjectShape::kParts;
  solid.footprint.center = {x, y};
  solid.footprint.yaw = -kPi / 2.0;  // front (-y of the object) towards -x: the camera
  solid.footprint.width = width;
  solid.footprint.depth = depth;
  solid.height = height;
  solid.base_height = base;
  solid.texture_seed = seed;
  const ClassLook look = DrawClassLook(class_name, seed);
  solid.color = look.color;
  solid.texture = look.texture;
  solid.parts = BuildClassParts(solid);
  return solid;
}

World Hall(std::vector<Solid> objects) {
  World world;
  world.walls = {{{-5, -5}, {15, -5}, {15, 5}, {-5, 5}, {-5, -5}}};
  world.wall_height = 2.5;
  world.objects = std::move(objects);
  return world;
}

bool Inside(const Footprint& inner, const Footprint& outer) {
  Footprint grown = outer;
  grown.width += 1e-9, grown.depth += 1e-9, grown.radius += 1e-9;
  if (inner.shape == Footprint::Shape::kBox) {
    for (const Eigen::Vector2d& corner : BoxCorners(inner)) {
      if (!FootprintContains(grown, corner)) return false;
    }
    return true;
  }
  for (int i = 0; i < 16; ++i) {
    const double a = 2.0 * kPi * i / 16;
    if (!FootprintContains(
            grown, inner.center + inner.radius * Eigen::Vector2d(std::cos(a), std::sin(a)))) {
      return false;
    }
  }
  return true;
}

TEST(ObjectShapesTest, EveryClassBuildsPartsInsideItsFootprintAndHeights) {
  Rng rng = MakeRng(3);
  for (const std::string& name : DefaultClassNames()) {
    ASSERT_TRUE(HasClassShape(name)) << name;
    const ClassSizeRange range = SizeRangeOf(name);
    for (int trial = 0; trial < 40; ++trial) {
      std::uniform_real_distribution<double> unit(0.0, 1.0);
      Solid solid;
      solid.class_name = name;
      solid.shape = ObjectShape::kParts;
      solid.texture_seed = static_cast<std::uint32_t>(rng());
      const double w = range.width_min + unit(rng) * (range.width_max - range.width_min);
      const double d = range.depth_min + unit(rng) * (range.depth_max - range.depth_min);
      if (range.round || (name == "stool" && trial % 2 == 0)) {
        solid.footprint.shape = Footprint::Shape::kCircle;
        solid.footprint.radius = 0.5 * w;
      } else {
        solid.footprint.width = w;
        solid.footprint.depth = d;
      }
      solid.footprint.center = {unit(rng) * 4.0, unit(rng) * 4.0};
      solid.footprint.yaw = kPi * (2.0 * unit(rng) - 1.0);
      solid.height = range.height_min + unit(rng) * (range.height_max - range.height_min);
      solid.base_height = range.base_min;
      const std::vector<Part> parts = BuildClassParts(solid);
      ASSERT_GE(parts.size(), 2u) << name;
      for (const Part& part : parts) {
        EXPECT_TRUE(Inside(part.footprint, solid.footprint)) << name << " trial " << trial;
        EXPECT_GE(part.bottom, solid.base_height - 1e-9) << name;
        EXPECT_LE(part.top, solid.base_height + solid.height + 1e-9) << name;
        EXPECT_LT(part.bottom, part.top) << name;
      }
    }
  }
  EXPECT_FALSE(HasClassShape("fridge"));
  EXPECT_TRUE(BuildClassParts(ClassObject("fridge", 0, 0, 1, 1, 1)).empty());
}

TEST(ObjectShapesTest, InstancesOfAClassLookDifferentUnlessTheSeedIsTheSame) {
  std::set<std::array<std::uint8_t, 3>> colors;
  for (std::uint32_t seed = 1; seed <= 20; ++seed)
    colors.insert(DrawClassLook("chair", seed).color);
  EXPECT_GE(colors.size(), 18u);
  EXPECT_EQ(DrawClassLook("sofa", 9).color, DrawClassLook("sofa", 9).color);
}

// The lidar at 0.19 m meets a table's four legs, not its top: its returns form four clusters
// of leg size at the legs' places.
TEST(ObjectShapesTest, LidarSeesATablesFourLegsNotItsTop) {
  const Solid table = ClassObject("table", 3.0, 0.0, 1.2, 0.8, 0.75);
  const Scene scene(Hall({table}));
  LidarSpec lidar;
  lidar.beams = 3600;
  lidar.noise_std = 0.0;
  Rng rng = MakeRng(1);
  // From four sides, so that every leg is seen by some scan.
  std::vector<Eigen::Vector2d> returns;
  for (const Pose2& pose : {Pose2(1.0, 0.0, 0.0), Pose2(5.0, 0.0, kPi), Pose2(3.0, -2.0, kPi / 2),
                            Pose2(3.0, 2.0, -kPi / 2)}) {
    const LaserScan scan = SimulateScan(scene, lidar, pose, 0.0, rng);
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      if (scan.ranges[i] >= lidar.max_range) continue;
      const double a = pose.theta + scan.angle_min + static_cast<double>(i) * scan.angle_increment;
      const Eigen::Vector2d p =
          pose.translation() + scan.ranges[i] * Eigen::Vector2d(std::cos(a), std::sin(a));
      if ((p - table.footprint.center).cwiseAbs().maxCoeff() < 0.7) returns.push_back(p);
    }
  }
  ASSERT_FALSE(returns.empty());
  std::vector<Eigen::Vector2d> legs;
  for (const Part& part : table.parts) {
    if (part.bottom < 0.19 && part.top > 0.19) legs.push_back(part.footprint.center);
  }
  ASSERT_EQ(legs.size(), 4u);
  std::vector<int> per_leg(4, 0);
  for (const Eigen::Vector2d& p : returns) {
    int nearest = 0;
    for (int k = 1; k < 4; ++k) {
      if ((p - legs[k]).norm() < (p - legs[nearest]).norm()) nearest = k;
    }
    EXPECT_LT((p - legs[nearest]).norm(), 0.06) << "a return away from every leg";
    ++per_leg[nearest];
  }
  for (int k = 0; k < 4; ++k) EXPECT_GT(per_leg[k], 0) << "leg " << k;
}

// The camera sees a table's top and, below it, the floor between the legs.
TEST(ObjectShapesTest, CameraSeesTheFloorBetweenATablesLegs) {
  const Solid table = ClassObject("table", 3.0, 0.0, 1.2, 0.8, 0.75);
  const Scene scene(Hall({table}));
  CameraSpec spec;
  spec.pitch_deg = 15.0;
  const MountedCamera camera = MakeMountedCamera(spec);
  const RgbdImage image = RenderRgbd(scene, camera, Pose2(1.0, 0.0, 0.0));
  const int u = camera.intrinsics.width / 2;  // the table's middle, between its front legs
  int top_rows = 0, floor_rows_below = 0;
  bool seen_top = false;
  for (int v = 0; v < camera.intrinsics.height; ++v) {
    const bool table_pixel = image.object_ids.at<std::int32_t>(v, u) == 0;
    if (table_pixel) {
      ++top_rows;
      seen_top = true;
    } else if (seen_top) {
      // Below the top: floor (or the far wall) behind the table, farther than its front edge.
      const double depth = 0.001 * image.depth.at<std::uint16_t>(v, u);
      if (depth > 2.6) ++floor_rows_below;
    }
  }
  EXPECT_GT(top_rows, 3);
  EXPECT_GT(floor_rows_below, 20);
}

// A clock is a disc: its mask fills π/4 of its bounding box and misses the box's corners.
TEST(ObjectShapesTest, ClockRendersAsADiscOnTheWall) {
  World world = Hall({ClassObject("clock", 4.97, 0.0, 0.4, 0.05, 0.4, 1.6)});
  world.walls.push_back({{5.0, -5.0}, {5.0, 5.0}});
  CameraSpec spec;
  spec.pitch_deg = -25.0;  // looking up at it
  const MountedCamera camera = MakeMountedCamera(spec);
  RenderOptions options;
  options.count_unoccluded = true;
  const RgbdImage image = RenderRgbd(Scene(world), camera, Pose2(2.5, 0.0, 0.0), options);
  const std::vector<ObjectVisibility> views = MeasureVisibility(image, world);
  const ObjectVisibility& clock = views[0];
  ASSERT_GT(clock.pixels, 200);
  const double box = (clock.u_max - clock.u_min + 1.0) * (clock.v_max - clock.v_min + 1.0);
  EXPECT_NEAR(clock.pixels / box, kPi / 4.0, 0.06);
  EXPECT_NE(image.object_ids.at<std::int32_t>(clock.v_min, clock.u_min), 0);
  EXPECT_NE(image.object_ids.at<std::int32_t>(clock.v_max, clock.u_max), 0);
  EXPECT_EQ(image.object_ids.at<std::int32_t>((clock.v_min + clock.v_max) / 2,
                                              (clock.u_min + clock.u_max) / 2),
            0);
  EXPECT_DOUBLE_EQ(clock.VisibleFraction(), 1.0);  // nothing in front of it
}

// A chair: legs up to the seat, the back above it at the rear; the lidar meets legs only.
TEST(ObjectShapesTest, ChairHasLegsSeatAndBack) {
  const Solid chair = ClassObject("chair", 0.0, 0.0, 0.5, 0.5, 0.9);
  int legs = 0, backs = 0, seats = 0;
  for (const Part& part : chair.parts) {
    if (part.bottom == 0.0 && part.top < 0.6) ++legs;
    if (part.top >= 0.9 - 0.011 && part.bottom > 0.3) ++backs;
    if (part.footprint.shape == Footprint::Shape::kBox && part.footprint.width >= 0.49 &&
        part.footprint.depth >= 0.49) {
      ++seats;
    }
  }
  EXPECT_EQ(legs, 4);
  EXPECT_GE(backs, 1);
  EXPECT_EQ(seats, 1);
}

// Occlusion: the truth box of a half-hidden object covers its visible part only, and what the
// renderer counts as its unoccluded silhouette is what it shows when alone.
TEST(ObjectShapesTest, UnoccludedSilhouetteMatchesTheObjectSeenAlone) {
  const Solid sofa = ClassObject("sofa", 4.0, 0.0, 1.8, 0.9, 0.85);
  Solid pillar;
  pillar.footprint.shape = Footprint::Shape::kCircle;
  pillar.footprint.center = {2.5, 0.3};
  pillar.footprint.radius = 0.25;
  pillar.height = 2.0;
  World both = Hall({sofa});
  both.obstacles = {pillar};
  RenderOptions options;
  options.count_unoccluded = true;
  const MountedCamera camera = MakeMountedCamera(CameraSpec{});
  const RgbdImage hidden = RenderRgbd(Scene(both), camera, Pose2(1.0, 0.0, 0.0), options);
  const RgbdImage alone = RenderRgbd(Scene(Hall({sofa})), camera, Pose2(1.0, 0.0, 0.0), options);
  const ObjectVisibility seen = MeasureVisibility(hidden, both)[0];
  const ObjectVisibility whole = MeasureVisibility(alone, Hall({sofa}))[0];
  EXPECT_EQ(hidden.unoccluded_pixels[0], whole.pixels);
  EXPECT_LT(seen.pixels, whole.pixels);
  EXPECT_NEAR(seen.VisibleFraction(), static_cast<double>(seen.pixels) / whole.pixels, 1e-12);
}

}  // namespace
}  // namespace semchain::sim
