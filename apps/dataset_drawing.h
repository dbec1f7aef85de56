#pragma once

#include <filesystem>
#include <string>

#include "core/status.h"

namespace semchain::app {

// A grid of frames of a YOLO data set (data.yaml beside images/ and labels/) with their label
// boxes drawn and named: 'count' frames of 'split' spread evenly over its sorted file names,
// 'columns' to a row, written as PNG to 'out'.
Status DrawDatasetGrid(const std::filesystem::path& dataset, const std::string& split, int count,
                       int columns, const std::filesystem::path& out);

}  // namespace semchain::app
