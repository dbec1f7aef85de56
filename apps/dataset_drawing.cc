#include "apps/dataset_drawing.h"

#include <algorithm>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "detection/detection_drawing.h"
#include "detection/yolo_dataset.h"
#include "drawing/png.h"
#include "io/yolo_labels.h"

namespace semchain::app {
namespace fs = std::filesystem;
namespace {

// One frame with its label boxes drawn (BGR).
Result<cv::Mat> LabelledFrame(const fs::path& image_path, const fs::path& label_path,
                              const std::vector<std::string>& names) {
  const cv::Mat bgr = cv::imread(image_path.string(), cv::IMREAD_COLOR);
  if (bgr.empty()) return Status::Error(image_path.string() + ": cannot read the image");
  std::vector<YoloLabel> labels;
  if (fs::exists(label_path)) {
    Result<std::vector<YoloLabel>> read =
        ReadYoloLabels(label_path, static_cast<int>(names.size()));
    if (!read.ok()) return read.status();
    labels = std::move(*read);
  }
  std::vector<Detection> boxes;
  for (const YoloLabel& label : labels) {
    Detection box;
    box.class_id = label.class_id;
    box.class_name = names[label.class_id];
    box.score = -1.0;  // a truth box
    const std::array<double, 4> pixels = label.PixelBox(bgr.cols, bgr.rows);
    for (int i = 0; i < 4; ++i) box.box[i] = std::round(pixels[i]);
    boxes.push_back(box);
  }
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  cv::Mat drawn = detection::DrawDetections(rgb, boxes);
  cv::cvtColor(drawn, drawn, cv::COLOR_RGB2BGR);
  return drawn;
}

}  // namespace

Status DrawDatasetGrid(const fs::path& dataset, const std::string& split, int count, int columns,
                       const fs::path& out) {
  Result<detection::YoloDataset> data = detection::LoadYoloDataset(dataset / "data.yaml");
  if (!data.ok()) return data.status();
  Result<std::vector<fs::path>> files = detection::SplitImages(*data, split);
  if (!files.ok()) return files.status();
  count = std::min<int>(count, static_cast<int>(files->size()));
  columns = std::max(1, std::min(columns, count));
  std::vector<cv::Mat> tiles;
  for (int i = 0; i < count; ++i) {
    const fs::path& image = (*files)[static_cast<std::size_t>(i) * files->size() / count];
    Result<cv::Mat> tile = LabelledFrame(image, detection::LabelPathOf(image), data->names);
    if (!tile.ok()) return tile.status();
    if (!tiles.empty() && tile->size() != tiles.front().size()) {
      cv::resize(*tile, *tile, tiles.front().size());
    }
    tiles.push_back(*tile);
  }
  const int rows = (count + columns - 1) / columns, gap = 4;
  const cv::Size tile = tiles.front().size();
  cv::Mat grid(rows * tile.height + (rows - 1) * gap, columns * tile.width + (columns - 1) * gap,
               CV_8UC3, cv::Scalar(255, 255, 255));
  for (int i = 0; i < count; ++i) {
    const int x = (i % columns) * (tile.width + gap), y = (i / columns) * (tile.height + gap);
    tiles[i].copyTo(grid(cv::Rect(x, y, tile.width, tile.height)));
  }
  return drawing::WritePng(grid, out);
}

}  // namespace semchain::app
