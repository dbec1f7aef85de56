#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "drawing/canvas.h"

// Maps, trajectories and point sets drawn on a top-down canvas.
namespace semchain::drawing {

// Draws a greyscale image (row 0 at the top, e.g. an occupancy map) whose lower-left corner is
// at 'origin' and whose pixels are 'resolution' metres wide, under whatever is drawn later.
void DrawGreyImage(const cv::Mat& grey, const Eigen::Vector2d& origin, double resolution,
                   TopDownCanvas& canvas);

// Draws a trajectory as a line through its positions, a dot at its start and an arrow at its
// end pose, with a legend entry 'label'.
void DrawTrajectory(const std::vector<Pose2>& poses, const Color& color, const std::string& label,
                    TopDownCanvas& canvas);

// Draws points (e.g. laser returns in the world frame) as small dots.
void DrawPoints(const std::vector<Eigen::Vector2d>& points, const Color& color,
                const std::string& label, TopDownCanvas& canvas);

}  // namespace semchain::drawing
