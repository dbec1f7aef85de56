#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "sensors/camera.h"

// The depth of a detection from the depth frame aligned with its colour frame: the depth the
// simulator reports for an object (the median depth of its visible pixels, see
// sim/detection_model.h), which the semantic mapper gates the box's pixels around. A box also
// holds what is behind and below the object: the wall behind a chair's back, the floor between
// a table's legs.
namespace semchain::detection {

enum class BoxDepthMethod {
  // The nearest surface in the box that fills a good part of it, the floor left out. An open
  // object (table, chair, stool: legs and a top) fills less of its box than the wall behind it,
  // so a median over the box lands on the wall; the object is the nearest large surface.
  kNearestSurface,
  // The median depth of the box's central part: right for solid objects (cabinet, door, sofa)
  // and 0.7–1.2 m too far for open ones (measured on furnished_flat's simulated frames).
  kCoreMedian,
};

struct BoxDepthOptions {
  BoxDepthMethod method = BoxDepthMethod::kNearestSurface;
  // kCoreMedian: the central part of the box whose pixels count, as a fraction of its width and
  // height.
  double core_fraction = 0.5;
  // kNearestSurface: the fraction of the box's width and height cut on each side (the box edges
  // jitter onto the neighbours).
  double trim_fraction = 0.1;
  // kNearestSurface: pixels lower than this above the floor (metres, through the camera's
  // mounting) are floor; without a mounting none is.
  double floor_height = 0.05;
  // kNearestSurface: sorted depths further apart than this (metres) belong to different
  // surfaces; a surface (its depths contiguous) counts when it holds at least
  // 'min_surface_fraction' of the box's pixels above the floor.
  double surface_gap = 0.05;
  double min_surface_fraction = 0.15;
  // At least this fraction of the pixels used (the core, or the trimmed box) must have a depth
  // reading, or the box has no depth (the simulator likewise reports only objects most of
  // whose pixels are measured).
  double min_valid_fraction = 0.5;

  bool Validate(std::string* error) const;
};

// The depth (metres) of the detection 'box' ([x1, y1, x2, y2], pixel-edge coordinates) in
// 'depth_m' (CV_32FC1, valid depths finite and > 0) by options.method; 'camera' (may be null)
// tells which pixels are floor. At least the pixel under the box centre is used. std::nullopt
// when the box lies outside the image or too few of its pixels have a depth. Of an even count
// the upper median is taken.
std::optional<double> BoxDepth(const cv::Mat& depth_m, const double box[4],
                               const MountedCamera* camera, const BoxDepthOptions& options);

}  // namespace semchain::detection
