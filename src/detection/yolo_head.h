#pragma once

#include <array>
#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

#include "core/status.h"

// The output of a YOLOv8 detection head, 1 × rows × N for N anchors over the strides 8, 16
// and 32 (row-major per stride, anchor centres at ((i + 0.5) s, (j + 0.5) s) input pixels):
//   raw head      rows = 64 + nc: per side (left, top, right, bottom) 16 DFL logits, then the
//                 class logits (before the sigmoid); what semchain asks users to export;
//   decoded head  rows = 4 + nc: cx, cy, w, h in input pixels, then the class scores.
namespace semchain::detection {

inline constexpr int kRegMax = 16;  // DFL bins per side: distances 0..15 strides
inline constexpr std::array<int, 3> kStrides = {8, 16, 32};

enum class HeadKind { kRaw, kDecoded };

struct HeadLayout {
  HeadKind kind = HeadKind::kRaw;
  int classes = 0;
  int anchors = 0;
  int rows() const { return (kind == HeadKind::kRaw ? 4 * kRegMax : 4) + classes; }
};

struct Anchor {
  float x = 0.0f, y = 0.0f;  // centre in input pixels
  float stride = 0.0f;
};

// The anchors of an input of 'input' pixels (both sides multiples of 32), in output order.
std::vector<Anchor> MakeAnchors(cv::Size input);

// Which head 'output' (as cv::dnn returns it) is, for a model of 'class_count' classes run at
// 'input'. A shape that is not 1 × (64 + nc | 4 + nc) × anchors is an error that says what was
// expected; a row count that would fit another class count is reported as a class-count
// mismatch.
Result<HeadLayout> IdentifyHead(const cv::Mat& output, int class_count, cv::Size input);

// The expected bin (0..15) under the softmax of the 16 logits logits[0], logits[step], ...:
// YOLOv8's distribution focal loss decoding, in strides.
double DflDistance(const float* logits, std::ptrdiff_t step);

// A detection in input pixels before NMS.
struct Candidate {
  cv::Rect2d box;  // pixel-edge coordinates of the network input
  int class_id = -1;
  float score = 0.0f;
};

// The anchors whose best class scores at least 'confidence_threshold' (after the sigmoid for a
// raw head), each with its best class and its box. 'anchors' is MakeAnchors(input).
std::vector<Candidate> DecodeHead(const cv::Mat& output, const HeadLayout& layout,
                                  const std::vector<Anchor>& anchors, double confidence_threshold);

}  // namespace semchain::detection
