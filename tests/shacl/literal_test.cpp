// SPARQL operator semantics on literals (the lexical forms: tests/rdf/xsd_test.cpp).
#include "shacl/literal.hpp"

#include <gtest/gtest.h>

#include "vocab/w3c.hpp"

using namespace mospec::shacl;

namespace {

const std::string kXsd(mospec::vocab::xsd::ns);

Order cmp(std::string_view a, const std::string& ta, std::string_view b, const std::string& tb) {
  std::string da = kXsd + ta, db = kXsd + tb;
  return compare_literals({a, da, {}}, {b, db, {}});
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
