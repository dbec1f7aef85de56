#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/status.h"

// A YOLO-format data set as ultralytics lays it out (DESIGN.md §5.6): data.yaml with `path`
// (the root; absent or relative: the yaml's folder, or relative to it), the splits `train`,
// `val` and `test` (image folders relative to the root), `nc` and `names`; labels lie beside
// the images with "images" replaced by "labels" in the path and the extension .txt.
namespace semchain::detection {

struct YoloDataset {
  std::filesystem::path root;
  std::vector<std::string> names;
  std::filesystem::path train, val, test;  // image folders; empty when data.yaml has none
};

// Reads 'data_yaml'; names missing or disagreeing with nc, or none of the three splits, is an
// error naming the file.
Result<YoloDataset> LoadYoloDataset(const std::filesystem::path& data_yaml);

// The images of 'split' (train, val or test), sorted; an error when the data set has no such
// split or its folder holds no image.
Result<std::vector<std::filesystem::path>> SplitImages(const YoloDataset& dataset,
                                                       const std::string& split);

// The label file of 'image' (…/images/<split>/x.png → …/labels/<split>/x.txt).
std::filesystem::path LabelPathOf(const std::filesystem::path& image);

}  // namespace semchain::detection
