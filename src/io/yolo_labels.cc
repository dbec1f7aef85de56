#include "io/yolo_labels.h"

#include <cmath>
#include <sstream>

#include "core/atomic_file.h"
#include "io/text_fields.h"

namespace semchain {

Result<std::vector<YoloLabel>> ParseYoloLabels(const std::string& text, const std::string& source,
                                               int class_count) {
  std::vector<YoloLabel> labels;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = source + ":" + std::to_string(number) + ": ";
    std::istringstream fields(line);
    std::string class_text;
    if (!(fields >> class_text)) continue;  // blank line
    YoloLabel label;
    int id = 0;
    if (!text::ParseInt(class_text, &id)) {
      return Status::Error(where + "class '" + class_text + "' is not an integer");
    }
    if (id < 0 || id >= class_count) {
      return Status::Error(where + "class " + class_text + " out of range (nc " +
                           std::to_string(class_count) + ")");
    }
    label.class_id = id;
    double* values[4] = {&label.cx, &label.cy, &label.w, &label.h};
    for (double* value : values) {
      std::string field;
      if (!(fields >> field)) return Status::Error(where + "expected 'class cx cy w h'");
      if (!text::ParseDouble(field, value) || !std::isfinite(*value)) {
        return Status::Error(where + "'" + field + "' is not a finite number");
      }
      if (*value < 0.0 || *value > 1.0) {
        return Status::Error(where + "'" + field + "' lies outside [0, 1]");
      }
    }
    std::string extra;
    if (fields >> extra)
      return Status::Error(where + "expected 'class cx cy w h', got more fields");
    constexpr double kSlack = 1e-6;  // rounding of the printed numbers
    if (label.w <= 0.0 || label.h <= 0.0 || label.cx - 0.5 * label.w < -kSlack ||
        label.cx + 0.5 * label.w > 1.0 + kSlack || label.cy - 0.5 * label.h < -kSlack ||
        label.cy + 0.5 * label.h > 1.0 + kSlack) {
      return Status::Error(where + "the box is empty or reaches outside the image");
    }
    labels.push_back(label);
  }
  return labels;
}

Result<std::vector<YoloLabel>> ReadYoloLabels(const std::filesystem::path& path, int class_count) {
  Result<std::string> text = ReadFile(path);
  if (!text.ok()) return text.status();
  return ParseYoloLabels(*text, path.string(), class_count);
}

}  // namespace semchain
