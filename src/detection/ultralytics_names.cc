#include "detection/ultralytics_names.h"

#include <cctype>
#include <cstdint>
#include <map>

namespace semchain::detection {
namespace {

// A reader of one Python literal; every error names the character where it stopped (1-based).
class LiteralReader {
 public:
  explicit LiteralReader(std::string_view text) : text_(text) {}

  Status Error(const std::string& what) const {
    return Status::Error("character " + std::to_string(pos_ + 1) + ": " + what);
  }

  void SkipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }

  // Skips space, then consumes 'c' if it is next.
  bool Take(char c) {
    SkipSpace();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }

  bool AtEnd() {
    SkipSpace();
    return pos_ == text_.size();
  }

  Result<long> Integer() {
    SkipSpace();
    const std::size_t start = pos_;
    long value = 0;
    while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) {
      if (value > 1000000) return Error("class id too large");
      value = value * 10 + (text_[pos_++] - '0');
    }
    if (pos_ == start) return Error("expected a class id (a non-negative integer)");
    return value;
  }

  Result<std::string> String() {
    SkipSpace();
    if (pos_ >= text_.size() || (text_[pos_] != '\'' && text_[pos_] != '"')) {
      return Error("expected a quoted class name");
    }
    const char quote = text_[pos_++];
    std::string value;
    while (pos_ < text_.size() && text_[pos_] != quote) {
      if (text_[pos_] != '\\') {
        value += text_[pos_++];
        continue;
      }
      SEMCHAIN_RETURN_IF_ERROR(Escape(&value));
    }
    if (pos_ >= text_.size()) return Error("unterminated string");
    ++pos_;
    return value;
  }

 private:
  // One escape sequence at pos_ (the backslash), appended to 'value'.
  Status Escape(std::string* value) {
    if (pos_ + 1 >= text_.size()) return Error("unterminated string");
    const char kind = text_[pos_ + 1];
    const std::map<char, char> simple = {{'\\', '\\'}, {'\'', '\''}, {'"', '"'},
                                         {'n', '\n'},  {'t', '\t'},  {'r', '\r'}};
    if (const auto it = simple.find(kind); it != simple.end()) {
      *value += it->second;
      pos_ += 2;
      return Status::Ok();
    }
    const std::size_t digits = kind == 'x' ? 2 : kind == 'u' ? 4 : kind == 'U' ? 8 : 0;
    if (digits == 0) return Error(std::string("unknown escape \\") + kind);
    if (pos_ + 2 + digits > text_.size()) return Error("truncated escape");
    std::uint32_t code = 0;
    for (std::size_t i = 0; i < digits; ++i) {
      const char c = text_[pos_ + 2 + i];
      if (!std::isxdigit(static_cast<unsigned char>(c))) return Error("bad hexadecimal escape");
      code = code * 16 + static_cast<std::uint32_t>(std::isdigit(static_cast<unsigned char>(c))
                                                        ? c - '0'
                                                        : std::tolower(c) - 'a' + 10);
    }
    if (code > 0x10ffff) return Error("escape beyond Unicode");
    AppendUtf8(code, value);
    pos_ += 2 + digits;
    return Status::Ok();
  }

  static void AppendUtf8(std::uint32_t code, std::string* out) {
    const auto byte = [](std::uint32_t b) { return static_cast<char>(b); };
    if (code < 0x80) {
      *out += byte(code);
    } else if (code < 0x800) {
      *out += byte(0xc0 | (code >> 6));
      *out += byte(0x80 | (code & 0x3f));
    } else if (code < 0x10000) {
      *out += byte(0xe0 | (code >> 12));
      *out += byte(0x80 | ((code >> 6) & 0x3f));
      *out += byte(0x80 | (code & 0x3f));
    } else {
      *out += byte(0xf0 | (code >> 18));
      *out += byte(0x80 | ((code >> 12) & 0x3f));
      *out += byte(0x80 | ((code >> 6) & 0x3f));
      *out += byte(0x80 | (code & 0x3f));
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

Result<std::vector<std::string>> ParseList(LiteralReader& reader) {
  std::vector<std::string> names;
  while (!reader.Take(']')) {
    if (!names.empty() && !reader.Take(',')) return reader.Error("expected ',' or ']'");
    if (reader.Take(']')) break;  // a trailing comma
    Result<std::string> name = reader.String();
    if (!name.ok()) return name.status();
    names.push_back(std::move(*name));
  }
  return names;
}

Result<std::vector<std::string>> ParseDict(LiteralReader& reader) {
  std::map<long, std::string> by_id;
  while (!reader.Take('}')) {
    if (!by_id.empty() && !reader.Take(',')) return reader.Error("expected ',' or '}'");
    if (reader.Take('}')) break;  // a trailing comma
    Result<long> id = reader.Integer();
    if (!id.ok()) return id.status();
    if (!reader.Take(':')) return reader.Error("expected ':'");
    Result<std::string> name = reader.String();
    if (!name.ok()) return name.status();
    if (!by_id.emplace(*id, std::move(*name)).second) {
      return reader.Error("class id " + std::to_string(*id) + " given twice");
    }
  }
  std::vector<std::string> names;
  for (auto& [id, name] : by_id) {
    if (id != static_cast<long>(names.size())) {
      return Status::Error("class ids are not 0 to " + std::to_string(by_id.size() - 1) + " (id " +
                           std::to_string(names.size()) + " is missing)");
    }
    names.push_back(std::move(name));
  }
  return names;
}

}  // namespace

Result<std::vector<std::string>> ParseUltralyticsNames(std::string_view text) {
  LiteralReader reader(text);
  Result<std::vector<std::string>> names = std::vector<std::string>();
  if (reader.Take('{')) {
    names = ParseDict(reader);
  } else if (reader.Take('[')) {
    names = ParseList(reader);
  } else {
    return reader.Error("expected a dict {0: 'name', ...} or a list ['name', ...]");
  }
  if (!names.ok()) return names;
  if (!reader.AtEnd()) return reader.Error("unexpected text after the names");
  if (names->empty()) return Status::Error("no class names");
  return names;
}

}  // namespace semchain::detection
