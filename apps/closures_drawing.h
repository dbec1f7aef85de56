#pragma once

#include <filesystem>

#include "core/status.h"
#include "eval/closure_metrics.h"

namespace semchain::app {

// Draws the precision–recall curves of `semchain bench closures` and writes them as a PNG,
// atomically: one curve a stage (the matcher's score alone, after verification, after the back
// end), a point a score threshold (named where the curve moved since the last one named), recall
// on x and precision on y, both 0..1. Thresholds where a stage has no precision (nothing
// labelled accepted) are left out of its curve.
Status WritePrecisionRecallPng(const eval::ClosureTable& table, const std::string& title,
                               const std::filesystem::path& path);

}  // namespace semchain::app
