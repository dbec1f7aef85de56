#include "io/text_fields.h"

#include <array>
#include <charconv>
#include <cmath>
#include <system_error>
#include <utility>

namespace semchain::text {

std::vector<std::string_view> SplitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  constexpr std::string_view kSpace = " \t\r\n";
  std::size_t begin = line.find_first_not_of(kSpace);
  while (begin != std::string_view::npos) {
    const std::size_t end = line.find_first_of(kSpace, begin);
    fields.push_back(line.substr(begin, end == std::string_view::npos ? end : end - begin));
    begin = line.find_first_not_of(kSpace, end);
  }
  return fields;
}

bool ParseDouble(std::string_view text, double* value) {
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    if (!text.empty() && text.front() == '-') return false;  // "+-1"
  }
  if (text.empty()) return false;
  const auto [ptr, error] = std::from_chars(text.data(), text.data() + text.size(), *value);
  return error == std::errc() && ptr == text.data() + text.size();
}

bool ParseInt(std::string_view text, int* value) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [ptr, error] = std::from_chars(text.data(), text.data() + text.size(), *value);
  return error == std::errc() && ptr == text.data() + text.size();
}

void AppendDouble(double value, std::string* out) {
  std::array<char, 32> buffer;  // the shortest form of any double fits in 24 characters
  const auto [ptr, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  SEMCHAIN_CHECK(error == std::errc());
  out->append(buffer.data(), ptr);
}

std::string FormatDouble(double value) {
  std::string text;
  AppendDouble(value, &text);
  return text;
}

FieldReader::FieldReader(std::string_view line, std::string prefix)
    : fields_(SplitFields(line)), prefix_(std::move(prefix)) {}

Status FieldReader::Error(const std::string& message) const {
  return Status::Error(prefix_ + ": " + message);
}

std::string FieldReader::FieldName(std::string_view name, int index) const {
  std::string text(name);
  if (index >= 0) text.append(1, ' ').append(std::to_string(index));
  return text;
}

Status FieldReader::Missing(std::string_view name, int index) const {
  return Error("truncated line: missing " + FieldName(name, index));
}

Status FieldReader::Double(std::string_view name, double* value, int index) {
  if (remaining() == 0) return Missing(name, index);
  const std::string_view field = fields_[next_++];
  if (!ParseDouble(field, value)) {
    return Error(FieldName(name, index) + ": '" + std::string(field) + "' is not a number");
  }
  if (!std::isfinite(*value)) {
    return Error(FieldName(name, index) + ": '" + std::string(field) + "' is not finite");
  }
  return Status::Ok();
}

Status FieldReader::Int(std::string_view name, int* value) {
  if (remaining() == 0) return Missing(name, -1);
  const std::string_view field = fields_[next_++];
  if (!ParseInt(field, value)) {
    return Error(std::string(name) + ": '" + std::string(field) + "' is not an integer");
  }
  return Status::Ok();
}

Status FieldReader::Count(std::string_view name, int* value) {
  SEMCHAIN_RETURN_IF_ERROR(Int(name, value));
  if (*value < 0) return Error(std::string(name) + ": " + std::to_string(*value) + " < 0");
  return Status::Ok();
}

Status FieldReader::Word(std::string_view name, std::string* value) {
  if (remaining() == 0) return Missing(name, -1);
  *value = std::string(fields_[next_++]);
  return Status::Ok();
}

std::string FieldReader::Rest() {
  std::string rest;
  for (; next_ < fields_.size(); ++next_) {
    if (!rest.empty()) rest += ' ';
    rest += fields_[next_];
  }
  return rest;
}

Status FieldReader::End() const {
  if (remaining() == 0) return Status::Ok();
  return Error(std::to_string(remaining()) + " unexpected extra field(s), first '" +
               std::string(fields_[next_]) + "'");
}

}  // namespace semchain::text
