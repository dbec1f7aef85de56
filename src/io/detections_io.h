#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/status.h"
#include "sensors/detection.h"

// detections.jsonl (DESIGN.md §5.5): one JSON object per camera frame and line,
//   {"frame": "frames/000123", "stamp": 12.3, "detections": [
//     {"class": "door", "class_id": 0, "score": 0.97, "box": [x1, y1, x2, y2], "depth_m": 2.31}]}
// and a detector's ".names" file (one class name per line, in class-id order).
namespace semchain {

// Writes one line per frame, atomically. Numbers are written in their shortest exact form, so
// reading the file back gives the same values. Non-finite numbers are an error (JSON has none).
Status WriteDetectionsJsonl(const std::filesystem::path& path,
                            const std::vector<FrameDetections>& frames);

// One record of the file: the line of 'frame' (without newline) that WriteDetectionsJsonl writes.
// Non-finite numbers are an error.
Result<std::string> FormatDetectionsRecord(const FrameDetections& frame);

// Parses one record (one line); 'where' prefixes errors ("run/detections.jsonl:7", or a bag's
// topic and message number). Checks as ReadDetectionsJsonl.
Result<FrameDetections> ParseDetectionsRecord(const std::string& line, const std::string& where);

// Reads a detections.jsonl file; blank lines are skipped and unknown fields ignored. Every
// field of §5.5 is required; an error names file, line and field:
//   "run/detections.jsonl:7: detections[1].box: expected 4 numbers".
// Checks: score in [0, 1], x1 <= x2 and y1 <= y2, depth_m >= 0, all numbers finite.
Result<std::vector<FrameDetections>> ReadDetectionsJsonl(const std::filesystem::path& path);

// Reads class names, one per line with surrounding white space trimmed; blank lines at the end
// are ignored, a blank line before a name (it would shift the ids) or a repeated name is an error.
Result<std::vector<std::string>> ReadClassNames(const std::filesystem::path& path);

}  // namespace semchain
