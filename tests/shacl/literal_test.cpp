#include "shacl/literal.hpp"

#include <gtest/gtest.h>

using namespace mospec::shacl;

namespace {

const std::string kXsd = "http://www.w3.org/2001/XMLSchema#";

bool ok(std::string_view lexical, const std::string& type) {
  return well_formed(lexical, classify_datatype(kXsd + type));
}

Order cmp(std::string_view a, const std::string& ta, std::string_view b, const std::string& tb) {
  std::string da = kXsd + ta, db = kXsd + tb;
  return compare_literals({a, da, {}}, {b, db, {}});
}

TEST(Literal, IntegerFamilyLexicalSpaceAndRanges) {
  EXPECT_TRUE(ok("42", "integer"));
  EXPECT_TRUE(ok("-0", "integer"));
  EXPECT_TRUE(ok("+7", "integer"));
  EXPECT_FALSE(ok("4.0", "integer"));
  EXPECT_FALSE(ok("", "integer"));
  EXPECT_FALSE(ok(" 1", "integer"));
  EXPECT_TRUE(ok("127", "byte"));
  EXPECT_FALSE(ok("300", "byte"));
  EXPECT_FALSE(ok("c", "byte"));
  EXPECT_FALSE(ok("-1", "nonNegativeInteger"));
  EXPECT_FALSE(ok("0", "positiveInteger"));
  EXPECT_TRUE(ok("18446744073709551615", "unsignedLong"));
  EXPECT_FALSE(ok("18446744073709551616", "unsignedLong"));
}

TEST(Literal, OtherDatatypes) {
  EXPECT_TRUE(ok("1.5", "decimal"));
  EXPECT_TRUE(ok(".5", "decimal"));
  EXPECT_FALSE(ok("1e3", "decimal"));
  EXPECT_TRUE(ok("1e3", "double"));
  EXPECT_TRUE(ok("-INF", "float"));
  EXPECT_TRUE(ok("NaN", "double"));
  EXPECT_FALSE(ok("nan", "double"));
  EXPECT_TRUE(ok("true", "boolean"));
  EXPECT_TRUE(ok("0", "boolean"));
  EXPECT_FALSE(ok("yes", "boolean"));
  EXPECT_TRUE(ok("2002-10-10T12:00:00-05:00", "dateTime"));
  EXPECT_TRUE(ok("2002-10-10T12:00:00.5Z", "dateTime"));
  EXPECT_FALSE(ok("2002-02-30T12:00:00", "dateTime"));
  EXPECT_FALSE(ok("2002-10-10", "dateTime"));
  EXPECT_TRUE(ok("2000-02-29", "date"));
  EXPECT_FALSE(ok("2001-02-29", "date"));
  EXPECT_TRUE(ok("23:59:59", "time"));
  EXPECT_TRUE(ok("anything at all", "string"));
  EXPECT_TRUE(ok("anything", "unknownType"));
}

TEST(Literal, NumericComparisonIsByValueAcrossTypes) {
  EXPECT_EQ(cmp("4", "integer", "4.0", "decimal"), Order::Equal);
  EXPECT_EQ(cmp("4", "integer", "40", "integer"), Order::Less);
  EXPECT_EQ(cmp("-5", "integer", "-40", "integer"), Order::Greater);
  EXPECT_EQ(cmp("1.5", "decimal", "1e0", "double"), Order::Greater);
  EXPECT_EQ(cmp("NaN", "double", "1", "integer"), Order::Incomparable);
  // Exact for long decimals, where doubles would round them equal.
  EXPECT_EQ(cmp("12345678901234567890.1", "decimal", "12345678901234567890.2", "decimal"),
            Order::Less);
}

TEST(Literal, MixedKindsAreIncomparable) {
  EXPECT_EQ(cmp("4", "integer", "4", "string"), Order::Incomparable);
  EXPECT_EQ(cmp("abc", "integer", "4", "integer"), Order::Incomparable);
  std::string s = kXsd + "string";
  EXPECT_EQ(compare_literals({"a", s, "en"}, {"b", s, "en"}), Order::Incomparable);
  EXPECT_EQ(cmp("a", "string", "b", "string"), Order::Less);
  EXPECT_EQ(cmp("false", "boolean", "true", "boolean"), Order::Less);
}

TEST(Literal, DateTimesFollowTheFourteenHourRule) {
  EXPECT_EQ(cmp("2002-10-10T12:00:00-05:00", "dateTime", "2002-10-10T17:00:00Z", "dateTime"),
            Order::Equal);
  EXPECT_EQ(cmp("2002-10-10T12:00:00-05:00", "dateTime", "2002-10-10T12:00:01-05:00", "dateTime"),
            Order::Less);
  // Within 14 hours of a zoned value, a value without zone is indeterminate.
  EXPECT_EQ(cmp("2002-10-10T12:00:00", "dateTime", "2002-10-10T12:00:01-05:00", "dateTime"),
            Order::Incomparable);
  EXPECT_EQ(cmp("2002-10-10T12:00:00", "dateTime", "2002-10-09T12:00:00-05:00", "dateTime"),
            Order::Greater);
  EXPECT_EQ(cmp("2002-10-09", "date", "2002-10-10", "date"), Order::Less);
}

TEST(Literal, LengthCountsCodePointsAndLangMatchesIsCaseInsensitive) {
  EXPECT_EQ(utf8_length("abc"), 3u);
  EXPECT_EQ(utf8_length("\xc3\xa9t\xc3\xa9"), 3u);
  EXPECT_TRUE(lang_matches("en-US", "en"));
  EXPECT_TRUE(lang_matches("EN", "en"));
  EXPECT_FALSE(lang_matches("eng", "en"));
  EXPECT_TRUE(lang_matches("de", "*"));
  EXPECT_FALSE(lang_matches("", "*"));
}

}  // namespace
