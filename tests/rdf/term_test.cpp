#include "rdf/term.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "test_util.hpp"

namespace mospec::rdf {
namespace {

using testing::numbered;

constexpr std::string_view kXsdInteger = "http://www.w3.org/2001/XMLSchema#integer";

TEST(TermTable, InternsEachTermOnce) {
  TermTable t;
  const size_t before = t.size();
  TermId a = t.iri("http://ex.org/a");
  EXPECT_EQ(t.iri("http://ex.org/a"), a);
  EXPECT_NE(t.iri("http://ex.org/b"), a);
  EXPECT_EQ(t.size(), before + 2);
  EXPECT_EQ(t[a].kind, TermKind::Iri);
  EXPECT_EQ(t[a].value, "http://ex.org/a");
}

TEST(TermTable, KindsWithTheSameTextAreDistinct) {
  TermTable t;
  TermId i = t.iri("x:y");
  TermId b = t.blank("x:y");
  TermId l = t.literal("x:y");
  EXPECT_NE(i, b);
  EXPECT_NE(i, l);
  EXPECT_NE(b, l);
  EXPECT_EQ(t[b].kind, TermKind::Blank);
  EXPECT_EQ(t[l].kind, TermKind::Literal);
}

TEST(TermTable, DefaultGraphIsIndexZero) {
  TermTable t;
  EXPECT_EQ(t[TermId::default_graph()].kind, TermKind::DefaultGraph);
  EXPECT_TRUE(TermId::any().is_any());
  EXPECT_FALSE(TermId::default_graph().is_any());
}

TEST(TermTable, LiteralDefaultDatatypes) {
  TermTable t;
  const Term& plain = t[t.literal("a")];
  EXPECT_EQ(t[plain.datatype].value, kXsdString);
  EXPECT_TRUE(plain.language.empty());

  const Term& tagged = t[t.literal("a", TermId::default_graph(), "en-GB")];
  EXPECT_EQ(t[tagged.datatype].value, kRdfLangString);
  EXPECT_EQ(tagged.language, "en-GB");

  const Term& directed = t[t.literal("a", TermId::default_graph(), "ar", "rtl")];
  EXPECT_EQ(t[directed.datatype].value, kRdfDirLangString);
  EXPECT_EQ(directed.language, "ar");
  EXPECT_EQ(directed.direction, "rtl");
}

TEST(TermTable, ExplicitXsdStringIsTheSameAsDefault) {
  TermTable t;
  EXPECT_EQ(t.literal("a"), t.literal("a", kXsdString));
  EXPECT_EQ(t.literal("a"), t.literal("a", TermTable::xsd_string()));
}

TEST(TermTable, LiteralComponentsAllDistinguish) {
  TermTable t;
  TermId base = t.literal("1");
  EXPECT_NE(base, t.literal("1", kXsdInteger));
  EXPECT_NE(base, t.literal("2"));
  EXPECT_NE(t.literal("1", TermId::default_graph(), "en"),
            t.literal("1", TermId::default_graph(), "de"));
  EXPECT_NE(t.literal("1", TermId::default_graph(), "en"),
            t.literal("1", TermId::default_graph(), "en", "ltr"));
  EXPECT_NE(t.literal("1", TermId::default_graph(), "en", "ltr"),
            t.literal("1", TermId::default_graph(), "en", "rtl"));
  EXPECT_EQ(t[t.literal("1", kXsdInteger)].value, "1");
  EXPECT_EQ(t[t[t.literal("1", kXsdInteger)].datatype].value, kXsdInteger);
}

TEST(TermTable, LanguageTagsKeepTheirCase) {
  TermTable t;
  TermId upper = t.literal("x", TermId::default_graph(), "EN-us");
  TermId lower = t.literal("x", TermId::default_graph(), "en-us");
  EXPECT_NE(upper, lower);
  EXPECT_EQ(t[upper].language, "EN-us");
}

TEST(TermTable, EmptyStringsAreValidTerms) {
  TermTable t;
  TermId empty = t.literal("");
  EXPECT_EQ(t.literal(""), empty);
  EXPECT_EQ(t[empty].value, "");
  EXPECT_NE(t.iri(""), empty);
}

TEST(TermTable, ViewsStayValidWhileGrowingAndAfterMove) {
  TermTable t;
  TermId first = t.iri("http://ex.org/first");
  const char* data = t[first].value.data();
  std::string big(100000, 'x');
  TermId large = t.literal(big);
  for (int i = 0; i < 50000; ++i) t.iri(numbered("http://ex.org/n", i));
  EXPECT_EQ(t[first].value.data(), data);
  EXPECT_EQ(t[first].value, "http://ex.org/first");
  EXPECT_EQ(t[large].value, big);

  TermTable moved = std::move(t);
  EXPECT_EQ(moved[first].value.data(), data);
  EXPECT_EQ(moved.iri("http://ex.org/n49999"), moved.find_iri("http://ex.org/n49999"));
  EXPECT_EQ(moved.iri("http://ex.org/first"), first);
}

TEST(TermTable, FindDoesNotIntern) {
  TermTable t;
  TermId a = t.iri("http://ex.org/a");
  const size_t n = t.size();
  EXPECT_EQ(t.find_iri("http://ex.org/a"), a);
  EXPECT_TRUE(t.find_iri("http://ex.org/zz").is_any());
  EXPECT_TRUE(t.find_blank("zz").is_any());
  EXPECT_TRUE(t.find_literal("zz").is_any());
  EXPECT_TRUE(t.find_literal("zz", TermId::default_graph(), "en").is_any());
  EXPECT_EQ(t.size(), n);
  TermId lit = t.literal("v", TermId::default_graph(), "en");
  EXPECT_EQ(t.find_literal("v", TermId::default_graph(), "en"), lit);
}

// well_formed_iri interns a well-formed IRI (once) and nothing else; an IRI
// interned by iri() without a check is still checked on its first ask.
TEST(TermTable, WellFormedIriInternsOnlyWellFormedIris) {
  TermTable t;
  const size_t n = t.size();
  EXPECT_TRUE(t.well_formed_iri("http://ex.org/a b").is_any());
  EXPECT_TRUE(t.well_formed_iri("no-scheme").is_any());
  EXPECT_TRUE(t.well_formed_iri("").is_any());
  EXPECT_EQ(t.size(), n);
  TermId a = t.well_formed_iri("http://ex.org/a");
  EXPECT_EQ(t.size(), n + 1);
  EXPECT_EQ(t.find_iri("http://ex.org/a"), a);
  EXPECT_EQ(t.well_formed_iri("http://ex.org/a"), a);
  EXPECT_EQ(t.iri("http://ex.org/a"), a);
  TermId bad = t.iri("http://ex.org/{bad}");
  EXPECT_TRUE(t.well_formed_iri("http://ex.org/{bad}").is_any());
  EXPECT_TRUE(t.well_formed_iri("http://ex.org/{bad}").is_any());
  EXPECT_EQ(t.find_iri("http://ex.org/{bad}"), bad);
  TermId good = t.iri("http://ex.org/good");
  EXPECT_EQ(t.well_formed_iri("http://ex.org/good"), good);
  // With the caller's hash: the same terms.
  EXPECT_EQ(t.well_formed_iri("http://ex.org/good", detail::hash_text("http://ex.org/good")), good);
  TermId c = t.well_formed_iri("http://ex.org/c", detail::hash_text("http://ex.org/c"));
  EXPECT_EQ(t.iri("http://ex.org/c"), c);
  EXPECT_TRUE(
      t.well_formed_iri("http://ex.org/{c}", detail::hash_text("http://ex.org/{c}")).is_any());
  // Many IRIs: the per-term record grows with the table.
  for (int i = 0; i < 300; ++i) {
    const std::string iri = numbered("http://ex.org/n", i);
    const TermId id = t.well_formed_iri(iri);
    EXPECT_FALSE(id.is_any()) << iri;
    EXPECT_EQ(t.find_iri(iri), id) << iri;
    EXPECT_EQ(t.well_formed_iri(iri), id) << iri;
  }
}

TEST(TermTable, FreshBlankNeverCollides) {
  TermTable t;
  t.blank("b0");
  t.blank("b1");
  t.blank("b3");
  TermId f1 = t.fresh_blank();
  TermId f2 = t.fresh_blank();
  TermId f3 = t.fresh_blank();
  EXPECT_EQ(t[f1].value, "b2");
  EXPECT_EQ(t[f2].value, "b4");
  EXPECT_EQ(t[f3].value, "b5");
}

TEST(TermTable, FreshBlankPrefixAvoidsExistingLabels) {
  TermTable t;
  t.blank("r0_x");
  t.blank("r2_");
  const std::string p1 = t.fresh_blank_prefix();
  const std::string p2 = t.fresh_blank_prefix();
  EXPECT_EQ(p1, "r1_");
  EXPECT_EQ(p2, "r3_");
  // A label merely containing the prefix later on does not block it.
  t.blank("xr4_");
  EXPECT_EQ(t.fresh_blank_prefix(), "r4_");
}

TEST(TermTable, CrossTableLookupAndImport) {
  TermTable a, b;
  TermId lit = a.literal("5", kXsdInteger);
  TermId bl = a.blank("n1");
  EXPECT_TRUE(b.find_equivalent(a, lit).is_any());
  TermId imported = b.import(a, lit);
  EXPECT_EQ(b.find_equivalent(a, lit), imported);
  EXPECT_EQ(b[b[imported].datatype].value, kXsdInteger);
  EXPECT_EQ(b[b.import(a, bl)].value, "n1");
  EXPECT_EQ(b.find_equivalent(a, TermId::default_graph()), TermId::default_graph());
}

TEST(ToNTriples, RendersEveryKind) {
  TermTable t;
  EXPECT_EQ(to_ntriples(t, t.iri("http://ex.org/a")), "<http://ex.org/a>");
  EXPECT_EQ(to_ntriples(t, t.blank("x1")), "_:x1");
  EXPECT_EQ(to_ntriples(t, t.literal("hi")), "\"hi\"");
  EXPECT_EQ(to_ntriples(t, t.literal("hi", TermId::default_graph(), "en-US")), "\"hi\"@en-US");
  EXPECT_EQ(to_ntriples(t, t.literal("hi", TermId::default_graph(), "he", "rtl")),
            "\"hi\"@he--rtl");
  EXPECT_EQ(to_ntriples(t, t.literal("1", kXsdInteger)),
            "\"1\"^^<http://www.w3.org/2001/XMLSchema#integer>");
  EXPECT_EQ(to_ntriples(t, TermId::default_graph()), "");
}

TEST(ToNTriples, EscapesLiteralsCanonically) {
  TermTable t;
  std::string all = "q\" b\\ n\n r\r t\t bs\b ff\f nul";
  all += '\0';
  all += " us\x1f del\x7f \xc3\xa9 '";
  EXPECT_EQ(to_ntriples(t, t.literal(all)),
            "\"q\\\" b\\\\ n\\n r\\r t\\u0009 bs\\u0008 ff\\u000C nul\\u0000 us\\u001F "
            "del\\u007F \xc3\xa9 '\"");
}

}  // namespace
}  // namespace mospec::rdf

namespace mospec::rdf {
namespace {

// hash_text reads every byte: strings that differ in any one byte, at any
// position of any length up to three words (the tail bytes included), and
// strings that differ only in length hash differently.
TEST(HashText, EveryByteAndTheLengthCount) {
  std::set<uint64_t> hashes;
  size_t strings = 0;
  for (size_t n = 0; n <= 24; ++n) {
    const std::string base(n, 'a');
    hashes.insert(detail::hash_text(base));
    ++strings;
    for (size_t i = 0; i < n; ++i) {
      std::string s = base;
      s[i] = 'b';
      hashes.insert(detail::hash_text(s));
      ++strings;
    }
  }
  EXPECT_EQ(hashes.size(), strings);
  EXPECT_EQ(detail::hash_text("http://example.org/a"), detail::hash_text("http://example.org/a"));
}

}  // namespace
}  // namespace mospec::rdf
