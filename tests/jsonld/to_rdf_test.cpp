#include "jsonld/to_rdf.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "json/json.hpp"
#include "jsonld/loader.hpp"
#include "rdf/nquads.hpp"
#include "support/diagnostics.hpp"

using mospec::jsonld::Options;
using mospec::jsonld::RdfDirection;
namespace json = mospec::json;
namespace rdf = mospec::rdf;

namespace {

constexpr std::string_view kXsd = "http://www.w3.org/2001/XMLSchema#";
constexpr std::string_view kRdf = "http://www.w3.org/1999/02/22-rdf-syntax-ns#";

// Converts an already expanded document (so these tests exercise to_rdf alone).
rdf::Dataset convert(std::string_view expanded, const Options& options = {}) {
  rdf::Dataset out;
  mospec::jsonld::to_rdf(json::parse(expanded, 1, "t.jsonld"), out, options);
  return out;
}

struct Lit {
  std::string lexical, datatype, language;
};

// The object literal of the single quad with predicate `p`.
Lit literal_of(const rdf::Dataset& d, std::string_view p) {
  const rdf::TermTable& t = d.terms();
  rdf::TermId pid = t.find_iri(p);
  if (pid.is_any()) return {"<no predicate>", "", ""};
  auto hits = d.match(rdf::TermId::any(), pid, rdf::TermId::any());
  if (hits.size() != 1) return {"<" + std::to_string(hits.size()) + " quads>", "", ""};
  const rdf::Term& o = t[d.quads()[hits[0]].object];
  if (o.kind != rdf::TermKind::Literal) return {"<not a literal>", "", ""};
  return {std::string(o.value), std::string(t[o.datatype].value), std::string(o.language)};
}

std::string xsd(std::string_view local) {
  return std::string(kXsd) + std::string(local);
}

// The xsd:double canonical form JSON-LD gives a number: "%.15E" with the
// mantissa's trailing zeros dropped (one kept after the point) and the
// exponent without sign padding or leading zeros.
std::string canonical_double(double v) {
  char printed[64];
  std::snprintf(printed, sizeof printed, "%.15E", v);
  const std::string text = printed;
  const size_t e = text.find('E');
  std::string mantissa = text.substr(0, e);
  while (mantissa.back() == '0' && mantissa[mantissa.size() - 2] != '.') mantissa.pop_back();
  return mantissa + "E" + std::to_string(std::stoi(text.substr(e + 1)));
}

rdf::Dataset one_value(std::string_view value_object, const Options& options = {}) {
  return convert(R"([{"@id": "http://ex/s", "http://ex/p": [)" + std::string(value_object) + "]}]",
                 options);
}

TEST(ToRdf, NativeNumbers) {
  struct Case {
    std::string json, lexical, datatype;
  } cases[] = {
      {"1.1", "1.1E0", xsd("double")},
      {"5.3", "5.3E0", xsd("double")},
      {"1e21", "1.0E21", xsd("double")},
      {"0.1", "1.0E-1", xsd("double")},
      {"-123.456", "-1.23456E2", xsd("double")},
      // Rounded to 15 fractional digits, as toExponential(15) does.
      {"0.0922959556", "9.229595559999999E-2", xsd("double")},
      // An exact tie at the 16th digit rounds up, as ECMAScript does (printf
      // would round it to even).
      {"1234567890123456.5", "1.234567890123457E15", xsd("double")},
      {"-1234567890123456.5", "-1.234567890123457E15", xsd("double")},
      {"4503599627370494.5", "4.503599627370495E15", xsd("double")},
      // A 17th significant digit of 5 that is not an exact tie: correctly
      // rounded, whichever way.
      {"943.3567736415966", "9.433567736415966E2", xsd("double")},
      {"215.48195374356305", "2.154819537435631E2", xsd("double")},
      {"289.30587844175875", "2.893058784417588E2", xsd("double")},
      // 17 significant digits 9.9999999999999997E-305 (sixteen nines and a
      // 7): the carry runs through all of them into the exponent.
      {"1e-304", "1.0E-304", xsd("double")},
      {"-1e-304", "-1.0E-304", xsd("double")},
      {"0.9999999999999999", "9.999999999999999E-1", xsd("double")},
      {"5", "5", xsd("integer")},
      {"-0", "0", xsd("integer")},
      {"1e20", "100000000000000000000", xsd("integer")},
      {"true", "true", xsd("boolean")},
  };
  for (const Case& c : cases) {
    rdf::Dataset d = one_value(R"({"@value": )" + c.json + "}");
    Lit l = literal_of(d, "http://ex/p");
    EXPECT_EQ(l.lexical, c.lexical) << c.json;
    EXPECT_EQ(l.datatype, c.datatype) << c.json;
  }
}

// Over the whole range of doubles (random bit patterns: subnormals, huge and
// tiny magnitudes), the canonical xsd:double form is the correctly rounded
// "%.15E" with trailing zeros trimmed: how double_lexical reads a number's
// digits must not change them. (An exact tie, where ECMAScript and printf
// round differently, has probability ~0 here; NativeNumbers covers ties.)
TEST(ToRdf, DoubleFormMatchesCorrectRoundingOverTheRange) {
  std::mt19937_64 rng(13);
  int checked = 0;
  for (int i = 0; i < 4000; ++i) {
    const uint64_t bits = rng();
    double v = 0;
    std::memcpy(&v, &bits, sizeof v);
    if (!std::isfinite(v) || v == 0 || (std::trunc(v) == v && std::fabs(v) < 1e21)) continue;
    char json[64];
    std::snprintf(json, sizeof json, "%.17g", v);
    const std::string expected = canonical_double(v);
    rdf::Dataset d = one_value(std::string(R"({"@value": )") + json + "}");
    ASSERT_EQ(literal_of(d, "http://ex/p").lexical, expected) << json;
    ++checked;
  }
  EXPECT_GT(checked, 3000);
}

// Numbers as models write them (a few significant digits, magnitudes from
// 1e-14 to 1e15) often have 17 correctly rounded digits ending in 5, where the
// 16-digit form depends on which side of that boundary the exact value lies:
// it must still be the correctly rounded "%.15E" (exact ties, where printf
// rounds to even and ECMAScript up, are left to NativeNumbers).
TEST(ToRdf, DoubleFormOfShortDecimalsRoundsFromTheExactValue) {
  std::mt19937_64 rng(29);
  int boundaries = 0;
  for (int i = 0; i < 6000; ++i) {
    const int digits = 1 + static_cast<int>(rng() % 17);
    const int exponent = -14 + static_cast<int>(rng() % 30);
    char json[64];
    std::snprintf(json, sizeof json, "%.*e", digits - 1,
                  static_cast<double>(rng() % 1000000007) / 1e9 * 9 + 1);
    std::string text = json;
    text = text.substr(0, text.find('e')) + "e" + std::to_string(exponent);
    const double v = std::strtod(text.c_str(), nullptr);
    if (std::trunc(v) == v) continue;
    char wide[96];
    std::snprintf(wide, sizeof wide, "%.40e", v);
    const std::string w = wide;  // "d.dddd...e-XX": significant digit k >= 2 at w[k]
    if (w[17] == '5') {
      if (w.find_first_not_of('0', 18) == w.find('e')) continue;  // an exact tie
      ++boundaries;
    }
    const std::string expected = canonical_double(v);
    rdf::Dataset d = one_value(std::string(R"({"@value": )") + text + "}");
    ASSERT_EQ(literal_of(d, "http://ex/p").lexical, expected) << text;
  }
  EXPECT_GT(boundaries, 100);
}

TEST(ToRdf, TypedValuesKeepOrCanonicaliseTheirForm) {
  // A JSON number typed xsd:double is canonicalised, even when integral...
  Lit l =
      literal_of(one_value(R"({"@value": 5, "@type": ")" + xsd("double") + "\"}"), "http://ex/p");
  EXPECT_EQ(l.lexical, "5.0E0");
  EXPECT_EQ(l.datatype, xsd("double"));
  // ...but a JSON string typed xsd:double keeps its lexical form.
  l = literal_of(one_value(R"({"@value": "80.5", "@type": ")" + xsd("double") + "\"}"),
                 "http://ex/p");
  EXPECT_EQ(l.lexical, "80.5");
  EXPECT_EQ(l.datatype, xsd("double"));
  // A fractional number typed with another datatype gets the double form, keeping the type.
  l = literal_of(one_value(R"({"@value": 2.5, "@type": "http://ex/t"})"), "http://ex/p");
  EXPECT_EQ(l.lexical, "2.5E0");
  EXPECT_EQ(l.datatype, "http://ex/t");
  l = literal_of(one_value(R"({"@value": "x", "@language": "en-US"})"), "http://ex/p");
  EXPECT_EQ(l.lexical, "x");
  EXPECT_EQ(l.datatype, std::string(kRdf) + "langString");
  EXPECT_EQ(l.language, "en-US");
}

TEST(ToRdf, JsonLiteralsAreCanonical) {
  Lit l = literal_of(one_value(R"({"@value": {"b": [1.0, 2.5], "a": "x"}, "@type": "@json"})"),
                     "http://ex/p");
  EXPECT_EQ(l.lexical, R"({"a":"x","b":[1,2.5]})");
  EXPECT_EQ(l.datatype, std::string(kRdf) + "JSON");
}

TEST(ToRdf, IllFormedTermsAreDropped) {
  rdf::Dataset d = convert(R"([
    {"@id": "relative", "http://ex/p": [{"@value": "a"}]},
    {"@id": "http://ex/s", "http://ex/a b": [{"@value": "b"}],
     "_:bp": [{"@value": "c"}], "http://ex/q": [{"@id": "http://ex/o o"}],
     "http://ex/l": [{"@value": "d", "@language": "not a tag"}],
     "@type": ["http://ex/T", "rel"]}
  ])");
  ASSERT_EQ(d.size(), 1u) << rdf::to_nquads(d);
  EXPECT_EQ(d.terms()[d.quads()[0].object].value, "http://ex/T");
}

TEST(ToRdf, GeneralizedRdfKeepsBlankPredicates) {
  Options options;
  options.produce_generalized_rdf = true;
  rdf::Dataset d = convert(R"([{"@id": "http://ex/s", "_:bp": [{"@value": "c"}]}])", options);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d.terms()[d.quads()[0].predicate].kind, rdf::TermKind::Blank);
}

TEST(ToRdf, ListsAndNamedGraphs) {
  rdf::Dataset d = convert(R"([{"@id": "http://ex/g", "@graph": [
    {"@id": "http://ex/s", "http://ex/p": [{"@list": [{"@value": 1}, {"@id": "http://ex/o"}]}],
     "http://ex/e": [{"@list": []}]}]}])");
  EXPECT_EQ(d.size(), 6u) << rdf::to_nquads(d);
  rdf::TermId g = d.terms().find_iri("http://ex/g");
  ASSERT_FALSE(g.is_any());
  for (const rdf::Quad& q : d.quads()) EXPECT_EQ(q.graph, g);
  rdf::TermId nil = d.terms().find_iri(std::string(kRdf) + "nil");
  EXPECT_EQ(
      d.match(d.terms().find_iri("http://ex/s"), d.terms().find_iri("http://ex/e"), nil).size(),
      1u);
}

TEST(ToRdf, RdfDirectionModes) {
  const std::string value = R"({"@value": "x", "@language": "en-US", "@direction": "rtl"})";
  Lit plain = literal_of(one_value(value), "http://ex/p");
  EXPECT_EQ(plain.datatype, std::string(kRdf) + "langString");

  Options i18n;
  i18n.rdf_direction = RdfDirection::I18nDatatype;
  Lit l = literal_of(one_value(value, i18n), "http://ex/p");
  EXPECT_EQ(l.lexical, "x");
  EXPECT_EQ(l.datatype, "https://www.w3.org/ns/i18n#en-us_rtl");
  EXPECT_EQ(l.language, "");

  Options compound;
  compound.rdf_direction = RdfDirection::CompoundLiteral;
  rdf::Dataset d = one_value(value, compound);
  EXPECT_EQ(d.size(), 4u) << rdf::to_nquads(d);
  EXPECT_EQ(literal_of(d, std::string(kRdf) + "value").lexical, "x");
  EXPECT_EQ(literal_of(d, std::string(kRdf) + "language").lexical, "en-us");
  EXPECT_EQ(literal_of(d, std::string(kRdf) + "direction").lexical, "rtl");
}

TEST(ToRdf, DocumentsNeverShareBlankNodes) {
  rdf::Dataset d;
  auto doc = json::parse(R"([{"@id": "_:b0", "http://ex/p": [{"@id": "_:b1"}]}])");
  mospec::jsonld::to_rdf(doc, d, {});
  mospec::jsonld::to_rdf(doc, d, {});
  ASSERT_EQ(d.size(), 2u);
  const rdf::Quad& a = d.quads()[0];
  const rdf::Quad& b = d.quads()[1];
  EXPECT_NE(a.subject, b.subject);
  EXPECT_NE(a.object, b.object);
  EXPECT_NE(a.subject, a.object);
}

// A document's own labels may be the very labels handed out fresh ("_:b1"
// is relabeled b0, "_:b0" b1): every mention keeps naming its own node.
TEST(ToRdf, DocumentLabelsThatLookFreshKeepTheirNodes) {
  rdf::Dataset d = convert(R"([
    {"@id": "_:b1", "http://ex/p": [{"@id": "_:b0"}], "http://ex/q": [{"@id": "_:b1"}]},
    {"@id": "_:b0", "http://ex/p": [{"@id": "_:b1"}]}])");
  EXPECT_EQ(rdf::to_nquads(d),
            "_:b0 <http://ex/p> _:b1 .\n"
            "_:b0 <http://ex/q> _:b0 .\n"
            "_:b1 <http://ex/p> _:b0 .\n");
}

TEST(ToRdf, QuadsRecordWhereTheNodeIdIsWritten) {
  rdf::Dataset d = convert("[{\"http://ex/p\": [{\"@value\": 1}],\n  \"@id\": \"http://ex/s\"}]");
  ASSERT_EQ(d.size(), 1u);
  mospec::SourceLoc loc = d.location(0);
  EXPECT_EQ(loc.file, 1u);
  EXPECT_EQ(loc.line, 2u);
  EXPECT_EQ(loc.column, 10u);
}

TEST(LoadInto, QuadsRecordWhereTheNodeIdIsWritten) {
  Options options;
  options.base = "https://example.org/";
  rdf::Dataset d;
  mospec::jsonld::load_into(json::parse("{\"@context\": {\"ex\": \"http://ex/\"},\n"
                                        "  \"@graph\": [{\"ex:p\": 1,\n"
                                        "    \"@id\": \"ex:s\"}, {\"ex:q\": 2}]}",
                                        3, "m.jsonld"),
                            d, options);
  ASSERT_EQ(d.size(), 2u) << rdf::to_nquads(d);
  // The node with an @id points at the @id value; the anonymous one at its object.
  auto at = [&](std::string_view p) {
    auto hits = d.match(rdf::TermId::any(), d.terms().find_iri(p), rdf::TermId::any());
    return hits.size() == 1 ? d.location(hits[0]) : mospec::SourceLoc{};
  };
  EXPECT_EQ(at("http://ex/p"), (mospec::SourceLoc{3, 3, 12}));
  EXPECT_EQ(at("http://ex/q"), (mospec::SourceLoc{3, 3, 21}));
}

TEST(ToRdf, ConflictingIndexesAreAnError) {
  try {
    convert(R"([{"@id": "http://ex/s", "@index": "a"},
                {"@id": "http://ex/s", "@index": "b"}])");
    ADD_FAILURE() << "no error";
  } catch (const mospec::Error& e) {
    EXPECT_EQ(e.code(), "conflicting indexes") << e.what();
    EXPECT_NE(std::string(e.what()).find("node <http://ex/s> has conflicting @index values"),
              std::string::npos)
        << e.what();
  }
}

// A @json literal holding a number JSON cannot write (1e400 overflows to
// Infinity) is an error located at file:line:col.
TEST(LoadInto, UncanonicalisableJsonLiteralIsLocated) {
  mospec::jsonld::MappedDocumentLoader loader;
  const uint32_t id = loader.files().add("inf.jsonld");
  Options options;
  options.loader = &loader;
  rdf::Dataset d;
  try {
    mospec::jsonld::load_into(json::parse("{\"@id\": \"http://ex/s\",\n"
                                          " \"http://ex/p\": {\"@value\": [1e400], "
                                          "\"@type\": \"@json\"}}",
                                          id, "inf.jsonld"),
                              d, options);
    FAIL() << "expected an error";
  } catch (const mospec::Error& e) {
    EXPECT_EQ(e.diagnostic().file, "inf.jsonld");
    EXPECT_EQ(e.diagnostic().line, 2u);
    EXPECT_EQ(e.diagnostic().column, 29u);  // the number
  }
}

// load_into = expand + to_rdf, through a document with a context.
TEST(LoadInto, ExpandsThenConverts) {
  Options options;
  options.base = "https://example.org/models/";
  rdf::Dataset d;
  mospec::jsonld::load_into(json::parse(R"({
    "@context": {"ex": "http://ex/", "mass": {"@id": "ex:mass", "@type": "xsd:double"},
                 "xsd": "http://www.w3.org/2001/XMLSchema#"},
    "@id": "arm", "mass": [1.5, "80.5"]})"),
                            d, options);
  ASSERT_EQ(d.size(), 2u) << rdf::to_nquads(d);
  std::string nq = rdf::to_nquads(d);
  EXPECT_NE(nq.find("<https://example.org/models/arm> <http://ex/mass> \"1.5E0\"^^<" +
                    xsd("double") + ">"),
            std::string::npos)
      << nq;
  EXPECT_NE(nq.find("\"80.5\"^^<" + xsd("double") + ">"), std::string::npos) << nq;
}

}  // namespace
