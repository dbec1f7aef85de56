#pragma once

#include <sensor_msgs/CompressedImage.h>

#include <opencv2/core.hpp>

#include "core/status.h"

// sensor_msgs/CompressedImage as image_transport's plugins write them, the way robots record
// their cameras:
//   compressed_image_transport: 'format' "jpeg" or "png" (older), or "<encoding>; jpeg
//     compressed bgr8" / "<encoding>; png compressed bgr8" (the bytes hold the image converted
//     to the layout after "compressed"; mono images name none);
//   compressed_depth_image_transport: 'format' "<encoding>; compressedDepth [png]" (older:
//     "<encoding>; compressedDepth", or no ';' at all): a 12-byte header {int32 format
//     (0: inverse depth), float32 depthParam[2]} in the machine's byte order, then a PNG.
//     16UC1 depth is the 16-bit PNG of the millimetres; 32FC1 depth is quantized inverse depth:
//     each 16-bit value q stands for depthParam[0] / (q - depthParam[1]) metres, 0 for no
//     reading. The "rvl" codec is not read.
namespace semchain::ros1 {

// The colour image of 'msg' in RGB order (CV_8UC3); data that does not decode, or a format
// that names a compression other than jpeg or png, is an error.
Result<cv::Mat> ColorFromCompressedMsg(const sensor_msgs::CompressedImage& msg);

// The depth image of 'msg' as CV_16UC1 in units of 'depth_scale' metres (as DepthFromImageMsg):
// compressedDepth (16UC1 millimetres or 32FC1 inverse depth), or a plain 16-bit PNG of
// millimetres ("png", "16UC1; png compressed"). Anything else is an error naming the format.
Result<cv::Mat> DepthFromCompressedMsg(const sensor_msgs::CompressedImage& msg, double depth_scale);

}  // namespace semchain::ros1
