#include "rdf/iri.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mospec::rdf {
namespace {

using Cases = std::vector<std::pair<std::string, std::string>>;

// Through resolve_iri() and through a prepared IriBase (writing over a buffer
// that holds the previous result, as expansion reuses one).
void expect_resolves(std::string_view base, const Cases& cases) {
  const IriBase prepared{std::string(base)};
  std::string buffer = "left over";
  for (const auto& [reference, expected] : cases) {
    EXPECT_EQ(resolve_iri(base, reference), expected) << "reference \"" << reference << "\"";
    prepared.resolve_into(buffer, reference);
    EXPECT_EQ(buffer, expected) << "IriBase, reference \"" << reference << "\"";
  }
}

// RFC 3986 section 5.4.1.
TEST(ResolveIri, Rfc3986NormalExamples) {
  expect_resolves("http://a/b/c/d;p?q", {
                                            {"g:h", "g:h"},
                                            {"g", "http://a/b/c/g"},
                                            {"./g", "http://a/b/c/g"},
                                            {"g/", "http://a/b/c/g/"},
                                            {"/g", "http://a/g"},
                                            {"//g", "http://g"},
                                            {"?y", "http://a/b/c/d;p?y"},
                                            {"g?y", "http://a/b/c/g?y"},
                                            {"#s", "http://a/b/c/d;p?q#s"},
                                            {"g#s", "http://a/b/c/g#s"},
                                            {"g?y#s", "http://a/b/c/g?y#s"},
                                            {";x", "http://a/b/c/;x"},
                                            {"g;x", "http://a/b/c/g;x"},
                                            {"g;x?y#s", "http://a/b/c/g;x?y#s"},
                                            {"", "http://a/b/c/d;p?q"},
                                            {".", "http://a/b/c/"},
                                            {"./", "http://a/b/c/"},
                                            {"..", "http://a/b/"},
                                            {"../", "http://a/b/"},
                                            {"../g", "http://a/b/g"},
                                            {"../..", "http://a/"},
                                            {"../../", "http://a/"},
                                            {"../../g", "http://a/g"},
                                        });
}

// RFC 3986 section 5.4.2.
TEST(ResolveIri, Rfc3986AbnormalExamples) {
  expect_resolves("http://a/b/c/d;p?q", {
                                            {"../../../g", "http://a/g"},
                                            {"../../../../g", "http://a/g"},
                                            {"/./g", "http://a/g"},
                                            {"/../g", "http://a/g"},
                                            {"g.", "http://a/b/c/g."},
                                            {".g", "http://a/b/c/.g"},
                                            {"g..", "http://a/b/c/g.."},
                                            {"..g", "http://a/b/c/..g"},
                                            {"./../g", "http://a/b/g"},
                                            {"./g/.", "http://a/b/c/g/"},
                                            {"g/./h", "http://a/b/c/g/h"},
                                            {"g/../h", "http://a/b/c/h"},
                                            {"g;x=1/./y", "http://a/b/c/g;x=1/y"},
                                            {"g;x=1/../y", "http://a/b/c/y"},
                                            {"g?y/./x", "http://a/b/c/g?y/./x"},
                                            {"g?y/../x", "http://a/b/c/g?y/../x"},
                                            {"g#s/./x", "http://a/b/c/g#s/./x"},
                                            {"g#s/../x", "http://a/b/c/g#s/../x"},
                                            {"http:g", "http:g"},
                                        });
}

TEST(ResolveIri, BaseWithQueryAndFragment) {
  expect_resolves("http://example.com/a/b?q=1#frag",
                  {
                      {"", "http://example.com/a/b?q=1"},
                      {"#f", "http://example.com/a/b?q=1#f"},
                      {"?p", "http://example.com/a/b?p"},
                      {"c", "http://example.com/a/c"},
                      {"//other.org", "http://other.org"},
                      {"//other.org/x/../y", "http://other.org/y"},
                      {"?", "http://example.com/a/b?"},
                      {"#", "http://example.com/a/b?q=1#"},
                  });
}

TEST(ResolveIri, BaseWithoutPath) {
  expect_resolves("http://example.com", {
                                            {"a", "http://example.com/a"},
                                            {"./a", "http://example.com/a"},
                                            {"../a", "http://example.com/a"},
                                            {"", "http://example.com"},
                                            {"?x", "http://example.com?x"},
                                        });
}

TEST(ResolveIri, NonHierarchicalAndFileBases) {
  expect_resolves("urn:x:y", {{"#a", "urn:x:y#a"}, {"z", "urn:z"}});
  expect_resolves("file:///home/u/doc.jsonld",
                  {{"ctx.jsonld", "file:///home/u/ctx.jsonld"}, {"../c", "file:///home/c"}});
}

// A one-segment reference ("g", the common case in models) against bases of
// every shape: the result is what RFC 3986's merge and remove_dot_segments give,
// including the normalisation of dot segments in the base's own path.
TEST(ResolveIri, OneSegmentReferenceAgainstEveryBaseShape) {
  expect_resolves("http://a", {{"g", "http://a/g"}});
  expect_resolves("http://a/", {{"g", "http://a/g"}, {".g", "http://a/.g"}});
  expect_resolves("http://a/b/./c/d", {{"g", "http://a/b/c/g"}});
  expect_resolves("http://a/b/../c/d", {{"g", "http://a/c/g"}});
  expect_resolves("http://a/b/c/..", {{"g", "http://a/b/c/g"}});
  expect_resolves("http://a/.well-known/x", {{"g", "http://a/.well-known/g"}});
  expect_resolves("http://a/b?q#f", {{"g", "http://a/g"}, {".", "http://a/"}, {"..", "http://a/"}});
  expect_resolves("a/b", {{"g", "a/g"}});
  expect_resolves("./a/b", {{"g", "a/g"}});
  expect_resolves("mailto:x", {{"g", "mailto:g"}});
}

// Each IriBase holds its own prefix for one-segment references: resolving
// against several in turn (and back) never uses another base's prefix.
TEST(ResolveIri, AlternatingBasesResolveAgainstTheirOwn) {
  const std::vector<std::pair<IriBase, std::string>> bases = {
      {IriBase("http://a/b/c"), "http://a/b/g"},   {IriBase("http://a/b/c/"), "http://a/b/c/g"},
      {IriBase("http://a/b/./c"), "http://a/b/g"}, {IriBase("urn:x"), "urn:g"},
      {IriBase("http://x/"), "http://x/g"},        {IriBase("http://y/z/"), "http://y/z/g"},
      {IriBase("http://x"), "http://x/g"},         {IriBase(), "g"}};
  for (int round = 0; round < 2; ++round) {
    for (const auto& [base, expected] : bases) {
      EXPECT_EQ(base.resolve("g"), expected) << "base \"" << base.iri() << "\"";
      EXPECT_EQ(resolve_iri(base.iri(), "g"), expected) << "base \"" << base.iri() << "\"";
    }
  }
  EXPECT_EQ(IriBase("http://a/b/c").resolve("g/h"), "http://a/b/g/h");
}

TEST(ResolveIri, EmptyBaseReturnsReference) {
  EXPECT_EQ(resolve_iri("", "a/../b"), "a/../b");
  EXPECT_EQ(resolve_iri("", "http://x/./y"), "http://x/./y");
}

TEST(ResolveIri, AbsoluteReferenceLosesDotSegments) {
  EXPECT_EQ(resolve_iri("http://a/b", "http://x/y/../z/./w"), "http://x/z/w");
}

TEST(IsAbsoluteIri, RequiresScheme) {
  EXPECT_TRUE(is_absolute_iri("http://example.com"));
  EXPECT_TRUE(is_absolute_iri("urn:isbn:123"));
  EXPECT_TRUE(is_absolute_iri("a+b-c.d:x"));
  EXPECT_TRUE(is_absolute_iri("x:"));
  EXPECT_FALSE(is_absolute_iri(""));
  EXPECT_FALSE(is_absolute_iri(":x"));
  EXPECT_FALSE(is_absolute_iri("1a:x"));
  EXPECT_FALSE(is_absolute_iri("_:b0"));
  EXPECT_FALSE(is_absolute_iri("a b:x"));
  EXPECT_FALSE(is_absolute_iri("relative/path"));
  EXPECT_FALSE(is_absolute_iri("#frag"));
  EXPECT_FALSE(is_absolute_iri("./a:b"));
}

// is_well_formed_iri as its definition reads, one byte at a time: a scheme,
// then no excluded byte (controls, space, DEL, <>"{}|\^`), at most one '#',
// and each '%' starting an escape of two hex digits.
bool reference_well_formed(std::string_view s) {
  const auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  const auto hex = [](char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
  };
  if (s.empty() || !alpha(s[0])) return false;
  size_t colon = std::string_view::npos;
  for (size_t i = 1; i < s.size(); ++i) {
    if (s[i] == ':') {
      colon = i;
      break;
    }
    if (!alpha(s[i]) && !(s[i] >= '0' && s[i] <= '9') && s[i] != '+' && s[i] != '-' && s[i] != '.')
      return false;
  }
  if (colon == std::string_view::npos) return false;
  int hashes = 0;
  for (size_t i = colon + 1; i < s.size(); ++i) {
    const auto u = static_cast<unsigned char>(s[i]);
    if (u <= 0x20 || u == 0x7f || std::string_view("<>\"{}|\\^`").find(s[i]) != s.npos) {
      return false;
    }
    if (s[i] == '#' && ++hashes > 1) return false;
    if (s[i] == '%' && (i + 2 >= s.size() || !hex(s[i + 1]) || !hex(s[i + 2]))) return false;
  }
  return true;
}

// Every byte value at every position of IRIs of every length up to 80 (so
// across each 16- and 4-byte block boundary of the scan), alone and after a
// '#' or a '%' escape earlier in the IRI.
TEST(WellFormedIri, AgreesWithTheDefinitionForEveryByteAtEveryPosition) {
  size_t checked = 0, well_formed = 0;
  for (const std::string prefix : {"https://example.org/", "h:", "urn:x#", "x:%41"}) {
    for (size_t length = prefix.size(); length <= 80; ++length) {
      std::string iri = prefix + std::string(length - prefix.size(), 'a');
      for (size_t at = prefix.size(); at < iri.size(); ++at) {
        for (int byte = 0; byte < 256; ++byte) {
          std::string probe = iri;
          probe[at] = static_cast<char>(byte);
          const bool expected = reference_well_formed(probe);
          ASSERT_EQ(is_well_formed_iri(probe), expected)
              << "byte " << byte << " at " << at << " of a " << probe.size() << "-byte IRI";
          ++checked;
          well_formed += expected ? 1 : 0;
        }
      }
    }
  }
  EXPECT_GT(checked, 300000u);
  EXPECT_GT(well_formed, checked / 2);  // most bytes are allowed
  EXPECT_LT(well_formed, checked);
}

TEST(WellFormedIri, SchemesAndEscapes) {
  EXPECT_TRUE(is_well_formed_iri("https://example.org/a%20b#frag"));
  EXPECT_TRUE(is_well_formed_iri("https://example.org/\xC3\xA9t\xC3\xA9"));  // UTF-8
  EXPECT_FALSE(is_well_formed_iri("https://example.org/a b"));
  EXPECT_FALSE(is_well_formed_iri("https://example.org/a#b#c"));
  EXPECT_FALSE(is_well_formed_iri("https://example.org/%4"));
  EXPECT_FALSE(is_well_formed_iri("https://example.org/%zz/and/more/than/sixteen/bytes"));
  EXPECT_FALSE(is_well_formed_iri("/relative/path"));
  EXPECT_FALSE(is_well_formed_iri("1http://x"));
  EXPECT_FALSE(is_well_formed_iri(""));
}

}  // namespace
}  // namespace mospec::rdf
