// XSD lexical forms and values (rdf/xsd.hpp): the one reader that SHACL,
// SPARQL and lowering share.
#include "rdf/xsd.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "vocab/w3c.hpp"

namespace mospec::rdf::xsd {
namespace {

const std::string kXsd(vocab::xsd::ns);

bool ok(std::string_view lexical, const std::string& type) {
  return well_formed(lexical, classify(kXsd + type));
}

TEST(Xsd, ClassifiesDatatypeIris) {
  EXPECT_EQ(classify(kXsd + "int").kind, Kind::Integer);
  EXPECT_EQ(classify(kXsd + "int").min, "-2147483648");
  EXPECT_EQ(classify(kXsd + "integer").max, "");
  EXPECT_EQ(classify(kXsd + "dateTimeStamp").kind, Kind::DateTimeStamp);
  EXPECT_EQ(classify(vocab::rdf::langString).kind, Kind::LangString);
  EXPECT_EQ(classify("http://example.org/int").kind, Kind::Other);
  EXPECT_EQ(classify(kXsd + "gYear").kind, Kind::Other);
}

TEST(Xsd, IntegerFamilyLexicalSpaceAndRanges) {
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

TEST(Xsd, OtherDatatypes) {
  EXPECT_TRUE(ok("1.5", "decimal"));
  EXPECT_TRUE(ok(".5", "decimal"));
  EXPECT_FALSE(ok("1e3", "decimal"));
  EXPECT_TRUE(ok("1e3", "double"));
  EXPECT_TRUE(ok("-INF", "float"));
  EXPECT_TRUE(ok("NaN", "double"));
  EXPECT_FALSE(ok("nan", "double"));
  EXPECT_FALSE(ok("0x10", "double"));
  EXPECT_TRUE(ok("true", "boolean"));
  EXPECT_TRUE(ok("0", "boolean"));
  EXPECT_FALSE(ok("yes", "boolean"));
  EXPECT_TRUE(ok("2002-10-10T12:00:00-05:00", "dateTime"));
  EXPECT_TRUE(ok("2002-10-10T12:00:00.5Z", "dateTime"));
  EXPECT_FALSE(ok("2002-02-30T12:00:00", "dateTime"));
  EXPECT_FALSE(ok("2002-10-10T12:00:60Z", "dateTime"));
  EXPECT_FALSE(ok("2002-10-10", "dateTime"));
  EXPECT_FALSE(ok("2002-10-10T12:00:00", "dateTimeStamp"));
  EXPECT_TRUE(ok("2000-02-29", "date"));
  EXPECT_FALSE(ok("2001-02-29", "date"));
  EXPECT_TRUE(ok("23:59:59", "time"));
  EXPECT_TRUE(ok("24:00:00", "time"));
  EXPECT_FALSE(ok("24:00:01", "time"));
  EXPECT_TRUE(ok("anything at all", "string"));
  EXPECT_TRUE(ok("anything", "unknownType"));
}

TEST(Xsd, DecimalsCompareExactly) {
  auto d = [](std::string_view s) { return *parse_decimal(s); };
  EXPECT_EQ(compare(d("12345678901234567890.1"), d("12345678901234567890.2")), -1);
  EXPECT_EQ(compare(d("-0.0"), d("+0")), 0);
  EXPECT_EQ(compare(d("007.50"), d("7.5")), 0);
  EXPECT_EQ(compare(d("-2"), d("-10")), 1);
  EXPECT_FALSE(parse_decimal("1.5", false));
}

TEST(Xsd, FloatingValues) {
  EXPECT_EQ(*to_double("+1.5e2"), 150.0);
  EXPECT_EQ(*to_double(".5"), 0.5);
  EXPECT_EQ(*to_double("-INF"), -HUGE_VAL);
  EXPECT_TRUE(std::isnan(*to_double("NaN")));
  EXPECT_EQ(*to_double("1e400"), HUGE_VAL);  // beyond the range: rounds to infinity
  EXPECT_EQ(*to_double("1e-400"), 0.0);
  EXPECT_TRUE(std::signbit(*to_double("-0")));
  EXPECT_FALSE(to_double("1e"));
  EXPECT_FALSE(to_double("inf"));
  EXPECT_EQ(*to_long_double("1e4000"), 1e4000L);
}

TEST(Xsd, InstantsAreSecondsSinceTheEpochInUtc) {
  auto seconds = [](std::string_view s, Kind k) { return parse_instant(s, k)->seconds; };
  EXPECT_EQ(seconds("1970-01-01T00:00:00Z", Kind::DateTime), 0);
  EXPECT_EQ(seconds("1970-01-02T01:00:00+01:00", Kind::DateTime), 86400);
  EXPECT_EQ(seconds("1970-01-02", Kind::Date), 86400);
  EXPECT_EQ(seconds("01:00:00Z", Kind::Time), 3600);
  EXPECT_FALSE(parse_instant("1970-01-01T00:00:00", Kind::DateTime)->has_zone);
  EXPECT_FALSE(parse_instant("1970-01-01", Kind::DateTime));
  EXPECT_FALSE(parse_instant("1970-01-01", Kind::Integer));
}

// What lowering reads as a model's number.
TEST(Xsd, ModelNumbers) {
  EXPECT_EQ(number("0.25", kXsd + "double"), 0.25);
  EXPECT_EQ(number("+3", kXsd + "integer"), 3.0);
  EXPECT_EQ(number("1.5", kXsd + "decimal"), 1.5);
  // JSON-LD's toRdf writes a JSON number under a decimal coercion as a canonical double.
  EXPECT_EQ(number("1.0E-3", kXsd + "decimal"), 1e-3);
  EXPECT_FALSE(number("1e-3", kXsd + "decimal"));  // not the canonical form, not a decimal
  EXPECT_EQ(number("2.5", kXsd + "string"), 2.5);  // a number written as a string
  EXPECT_FALSE(number("300", kXsd + "byte"));      // out of the type's range
  EXPECT_FALSE(number("1", kXsd + "boolean"));
  EXPECT_FALSE(number("1", "http://example.org/number"));
  EXPECT_FALSE(number("one", kXsd + "double"));
}

}  // namespace
}  // namespace mospec::rdf::xsd
