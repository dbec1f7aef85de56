#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/status.h"

// Helpers for whitespace-separated text formats (CARMEN logs, relation files): strict number
// parsing and shortest round-trip number formatting.
namespace semchain::text {

// Splits 'line' at spaces, tabs and carriage returns; empty fields are dropped.
std::vector<std::string_view> SplitFields(std::string_view line);

// Parses all of 'text' as a double ("1.5x" and "" fail; a leading '+' is allowed). "nan" and
// "inf" parse: callers decide whether non-finite values are allowed.
bool ParseDouble(std::string_view text, double* value);
// Parses all of 'text' as a decimal int.
bool ParseInt(std::string_view text, int* value);

// The shortest text that parses back to exactly 'value' ("1.4", "81.91", "1134864643.12418").
std::string FormatDouble(double value);
// Appends FormatDouble(value) to 'out'.
void AppendDouble(double value, std::string* out);

// Reads the fields of one record in order; every error is one line
// "<prefix>: <what went wrong>", where the prefix names file, line and record type.
class FieldReader {
 public:
  FieldReader(std::string_view line, std::string prefix);

  std::size_t remaining() const { return fields_.size() - next_; }
  // An error with this reader's prefix.
  Status Error(const std::string& message) const;

  // The next field as a finite double; 'name' (and 'index' when >= 0) names it in errors,
  // e.g. "range 17: 'nan' is not finite".
  Status Double(std::string_view name, double* value, int index = -1);
  Status Int(std::string_view name, int* value);
  // A count: an int >= 0.
  Status Count(std::string_view name, int* value);
  Status Word(std::string_view name, std::string* value);
  // All remaining fields joined by single spaces.
  std::string Rest();
  // Fails when fields are left over.
  Status End() const;

 private:
  Status Missing(std::string_view name, int index) const;
  std::string FieldName(std::string_view name, int index) const;

  std::vector<std::string_view> fields_;
  std::size_t next_ = 0;
  std::string prefix_;
};

}  // namespace semchain::text
