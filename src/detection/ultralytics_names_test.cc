#include "detection/ultralytics_names.h"

#include <gtest/gtest.h>

namespace semchain::detection {
namespace {

using Names = std::vector<std::string>;

std::string ErrorOf(std::string_view text) {
  const Result<Names> names = ParseUltralyticsNames(text);
  return names.ok() ? "no error" : names.status().message();
}

TEST(ParseUltralyticsNamesTest, ReadsTheDictTheExporterWrites) {
  const Result<Names> names =
      ParseUltralyticsNames("{0: 'person', 1: 'bicycle', 2: 'dining table'}");
  ASSERT_TRUE(names.ok()) << names.status().message();
  EXPECT_EQ(*names, (Names{"person", "bicycle", "dining table"}));
}

TEST(ParseUltralyticsNamesTest, OrdersByIdAndReadsPythonsQuotesAndEscapes) {
  // repr() quotes a name holding ' with ", and escapes what it must.
  const Result<Names> names =
      ParseUltralyticsNames("{1: \"men's shoe\", 0: 'a\\\\b\\'c', 2: 'caf\\xe9', 3: '\\u00fc',}");
  ASSERT_TRUE(names.ok()) << names.status().message();
  EXPECT_EQ(*names, (Names{"a\\b'c", "men's shoe", "caf\xc3\xa9", "\xc3\xbc"}));
}

TEST(ParseUltralyticsNamesTest, ReadsAList) {
  const Result<Names> names = ParseUltralyticsNames(" ['door', 'chair'] ");
  ASSERT_TRUE(names.ok()) << names.status().message();
  EXPECT_EQ(*names, (Names{"door", "chair"}));
}

TEST(ParseUltralyticsNamesTest, SaysWhatIsWrongAndWhere) {
  EXPECT_EQ(ErrorOf("person, bicycle"),
            "character 1: expected a dict {0: 'name', ...} or a list ['name', ...]");
  EXPECT_EQ(ErrorOf("{0 'person'}"), "character 4: expected ':'");
  EXPECT_EQ(ErrorOf("{0: person}"), "character 5: expected a quoted class name");
  EXPECT_EQ(ErrorOf("{0: 'person}"), "character 13: unterminated string");
  EXPECT_EQ(ErrorOf("{0: 'a', 0: 'b'}"), "character 16: class id 0 given twice");
  EXPECT_EQ(ErrorOf("{1: 'a'}"), "class ids are not 0 to 0 (id 0 is missing)");
  EXPECT_EQ(ErrorOf("{0: 'a'} x"), "character 10: unexpected text after the names");
  EXPECT_EQ(ErrorOf("{0: 'a\\q'}"), "character 7: unknown escape \\q");
  EXPECT_EQ(ErrorOf("{}"), "no class names");
  EXPECT_EQ(ErrorOf("{-1: 'a'}"), "character 2: expected a class id (a non-negative integer)");
}

}  // namespace
}  // namespace semchain::detection
