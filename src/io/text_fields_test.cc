#include "io/text_fields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace semchain::text {
namespace {

TEST(TextFieldsTest, SplitsOnAnyWhiteSpace) {
  EXPECT_EQ(SplitFields("  a \tbb  c\r"), (std::vector<std::string_view>{"a", "bb", "c"}));
  EXPECT_TRUE(SplitFields(" \t ").empty());
}

TEST(TextFieldsTest, ParsesNumbersStrictly) {
  double value = 0.0;
  EXPECT_TRUE(ParseDouble("81.91", &value));
  EXPECT_EQ(value, 81.91);
  EXPECT_TRUE(ParseDouble("+.5", &value));
  EXPECT_EQ(value, 0.5);
  EXPECT_TRUE(ParseDouble("6.20016e-05", &value));
  EXPECT_EQ(value, 6.20016e-05);
  EXPECT_TRUE(ParseDouble("nan", &value));  // parsed; callers reject non-finite values
  EXPECT_TRUE(std::isnan(value));
  for (const char* bad : {"", "+", "1.5x", "x1", "1 2", "+-1", "--1", "0x10"}) {
    EXPECT_FALSE(ParseDouble(bad, &value)) << bad;
  }
  int count = 0;
  EXPECT_TRUE(ParseInt("361", &count));
  EXPECT_EQ(count, 361);
  EXPECT_TRUE(ParseInt("-3", &count));
  EXPECT_EQ(count, -3);
  for (const char* bad : {"", "1.0", "3x", "99999999999", "+-1"}) {
    EXPECT_FALSE(ParseInt(bad, &count)) << bad;
  }
}

TEST(TextFieldsTest, FormatsTheShortestExactForm) {
  EXPECT_EQ(FormatDouble(1.4), "1.4");
  EXPECT_EQ(FormatDouble(0.0), "0");
  EXPECT_EQ(FormatDouble(1134864629.895182), "1134864629.895182");
  for (const double v :
       {0.1 + 0.2, 1.0 / 3.0, -2.255213, 1e-300, 6.02e23, std::numeric_limits<double>::max()}) {
    double back = 0.0;
    ASSERT_TRUE(ParseDouble(FormatDouble(v), &back));
    EXPECT_EQ(back, v);
  }
}

TEST(TextFieldsTest, FieldReaderNamesTheFailingField) {
  FieldReader fields("3 nan x", "log.clf:7: FLASER");
  int count = 0;
  double value = 0.0;
  EXPECT_TRUE(fields.Count("number of ranges", &count).ok());
  EXPECT_EQ(fields.Double("range", &value, 0).message(),
            "log.clf:7: FLASER: range 0: 'nan' is not finite");
  EXPECT_EQ(fields.Double("range", &value, 1).message(),
            "log.clf:7: FLASER: range 1: 'x' is not a number");
  EXPECT_EQ(fields.Double("range", &value, 2).message(),
            "log.clf:7: FLASER: truncated line: missing range 2");
  FieldReader negative("-1", "f:1: X");
  EXPECT_EQ(negative.Count("count", &count).message(), "f:1: X: count: -1 < 0");
}

}  // namespace
}  // namespace semchain::text
