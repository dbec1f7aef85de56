#include "detection/yolo_head.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.h"

namespace semchain::detection {
namespace {

std::string ShapeText(const cv::Mat& output) {
  if (output.dims == 0) return "empty";
  std::string text = std::to_string(output.size[0]);
  for (int d = 1; d < output.dims; ++d) text.append("x").append(std::to_string(output.size[d]));
  return text;
}

int ExpectedAnchors(cv::Size input) {
  int count = 0;
  for (int stride : kStrides) count += (input.width / stride) * (input.height / stride);
  return count;
}

float Sigmoid(float logit) { return 1.0f / (1.0f + std::exp(-logit)); }

// The box of anchor 'a' of a raw head: distances left, top, right, bottom in strides around
// the anchor centre (ultralytics' dist2bbox).
cv::Rect2d RawBox(const float* data, std::ptrdiff_t n, std::ptrdiff_t a, const Anchor& anchor) {
  double d[4];
  for (int side = 0; side < 4; ++side) {
    d[side] = anchor.stride * DflDistance(data + side * kRegMax * n + a, n);
  }
  return cv::Rect2d(anchor.x - d[0], anchor.y - d[1], d[0] + d[2], d[1] + d[3]);
}

cv::Rect2d DecodedBox(const float* data, std::ptrdiff_t n, std::ptrdiff_t a) {
  const double cx = data[a], cy = data[n + a], w = data[2 * n + a], h = data[3 * n + a];
  return cv::Rect2d(cx - 0.5 * w, cy - 0.5 * h, w, h);
}

}  // namespace

std::vector<Anchor> MakeAnchors(cv::Size input) {
  std::vector<Anchor> anchors;
  anchors.reserve(ExpectedAnchors(input));
  for (int stride : kStrides) {
    for (int j = 0; j < input.height / stride; ++j) {
      for (int i = 0; i < input.width / stride; ++i) {
        anchors.push_back({float((i + 0.5) * stride), float((j + 0.5) * stride), float(stride)});
      }
    }
  }
  return anchors;
}

Result<HeadLayout> IdentifyHead(const cv::Mat& output, int class_count, cv::Size input) {
  const std::string expected =
      "expected 1 x (64 + classes) x anchors (raw head) or 1 x (4 + "
      "classes) x anchors (decoded head)";
  if (output.type() != CV_32F || output.dims != 3 || output.size[0] != 1) {
    return Status::Error("the model's output is " + ShapeText(output) + ", " + expected);
  }
  HeadLayout layout;
  layout.classes = class_count;
  layout.anchors = output.size[2];
  const int rows = output.size[1];
  if (rows == 4 * kRegMax + class_count) {
    layout.kind = HeadKind::kRaw;
  } else if (rows == 4 + class_count) {
    layout.kind = HeadKind::kDecoded;
  } else {
    const int raw = rows - 4 * kRegMax, decoded = rows - 4;
    if (rows == ExpectedAnchors(input)) {
      return Status::Error("the model's output is " + ShapeText(output) +
                           ", anchors before rows (transposed); " + expected);
    }
    return Status::Error("class-count mismatch: the model's output has " + std::to_string(rows) +
                         " rows per anchor, which fits " +
                         (raw > 0 ? std::to_string(raw) + " classes (raw head) or " : "") +
                         std::to_string(decoded) + " classes (decoded head), but there are " +
                         std::to_string(class_count) + " class names");
  }
  if (layout.anchors != ExpectedAnchors(input)) {
    return Status::Error("the model's output is " + ShapeText(output) + ": " +
                         std::to_string(layout.anchors) + " anchors, but strides 8, 16, 32 at " +
                         std::to_string(input.width) + "x" + std::to_string(input.height) +
                         " give " + std::to_string(ExpectedAnchors(input)));
  }
  return layout;
}

double DflDistance(const float* logits, std::ptrdiff_t step) {
  float top = logits[0];
  for (int k = 1; k < kRegMax; ++k) top = std::max(top, logits[k * step]);
  double sum = 0.0, weighted = 0.0;
  for (int k = 0; k < kRegMax; ++k) {
    const double w = std::exp(double(logits[k * step]) - top);
    sum += w;
    weighted += k * w;
  }
  return weighted / sum;
}

std::vector<Candidate> DecodeHead(const cv::Mat& output, const HeadLayout& layout,
                                  const std::vector<Anchor>& anchors, double confidence_threshold) {
  SEMCHAIN_CHECK(output.isContinuous() && int(anchors.size()) == layout.anchors);
  const float* data = output.ptr<float>();
  const std::ptrdiff_t n = layout.anchors;
  const bool raw = layout.kind == HeadKind::kRaw;
  const float* classes = data + (raw ? 4 * kRegMax : 4) * n;
  std::vector<Candidate> candidates;
  for (std::ptrdiff_t a = 0; a < n; ++a) {
    int best = 0;
    for (int c = 1; c < layout.classes; ++c) {
      if (classes[c * n + a] > classes[best * n + a]) best = c;
    }
    const float value = classes[best * n + a];
    const float score = raw ? Sigmoid(value) : value;
    if (!(score >= confidence_threshold)) continue;  // also drops NaN
    const cv::Rect2d box = raw ? RawBox(data, n, a, anchors[a]) : DecodedBox(data, n, a);
    candidates.push_back({box, best, score});
  }
  return candidates;
}

}  // namespace semchain::detection
