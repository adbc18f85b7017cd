#include "rdf/nquads.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "rdf/isomorphism.hpp"

namespace mospec::rdf {
namespace {

// The full located message of the syntax error `text` raises.
std::string error_of(std::string_view text, std::string_view file = "<input>") {
  Dataset d;
  try {
    read_nquads(text, d, 1, file);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "syntax");
    return e.what();
  }
  return "no error";
}

std::string label_of(const Dataset& d, TermId id) {
  std::string_view label = d.terms()[id].value;
  return std::string(label.substr(label.find('_') + 1));  // drop the document prefix
}

TEST(ReadNQuads, StatementsCommentsAndBlankLines) {
  Dataset d;
  read_nquads(
      "# leading comment\n"
      "\n"
      "<http://ex.org/s> <http://ex.org/p> <http://ex.org/o> .   # trailing comment\r\n"
      "\t<http://ex.org/s> <http://ex.org/p> \"lit\" <http://ex.org/g> .\n"
      "<http://ex.org/s><http://ex.org/p>_:b1 _:g.\n"
      "<http://ex.org/s> <http://ex.org/p> \"x\" .",  // no final newline
      d);
  ASSERT_EQ(d.size(), 4u);
  const TermTable& t = d.terms();
  EXPECT_EQ(to_ntriples(t, d.quads()[0].object), "<http://ex.org/o>");
  EXPECT_EQ(d.quads()[0].graph, TermId::default_graph());
  EXPECT_EQ(to_ntriples(t, d.quads()[1].graph), "<http://ex.org/g>");
  EXPECT_EQ(label_of(d, d.quads()[2].object), "b1");
  EXPECT_EQ(label_of(d, d.quads()[2].graph), "g");
  EXPECT_EQ(t[d.quads()[3].object].value, "x");
}

TEST(ReadNQuads, EveryEscapeInLiterals) {
  Dataset d;
  read_nquads(
      R"(<http://ex.org/s> <http://ex.org/p> "t\t b\b n\n r\r f\f q\" a\' s\\ u\u00E9 U\U0001F600 z\u0000" .)",
      d);
  ASSERT_EQ(d.size(), 1u);
  std::string expected = "t\t b\b n\n r\r f\f q\" a' s\\ u\xC3\xA9 U\xF0\x9F\x98\x80 z";
  expected += '\0';
  EXPECT_EQ(d.terms()[d.quads()[0].object].value, expected);
}

TEST(ReadNQuads, UnicodeEscapesInIris) {
  Dataset d;
  read_nquads(R"(<http://ex.org/\u00E9> <http://ex.org/p\U0001F600> <http://ex.org/o> .)", d);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d.terms()[d.quads()[0].subject].value, "http://ex.org/\xC3\xA9");
  EXPECT_EQ(d.terms()[d.quads()[0].predicate].value, "http://ex.org/p\xF0\x9F\x98\x80");
}

TEST(ReadNQuads, LanguageTagsDirectionsAndDatatypes) {
  Dataset d;
  read_nquads(
      "<http://ex.org/s> <http://ex.org/p> \"a\"@en-US .\n"
      "<http://ex.org/s> <http://ex.org/p> \"b\"@ar--rtl .\n"
      "<http://ex.org/s> <http://ex.org/p> \"c\"^^<http://www.w3.org/2001/XMLSchema#integer> .\n"
      "<http://ex.org/s> <http://ex.org/p> \"d\"^^<http://www.w3.org/2001/XMLSchema#string> .\n",
      d);
  const TermTable& t = d.terms();
  ASSERT_EQ(d.size(), 4u);
  const Term& a = t[d.quads()[0].object];
  EXPECT_EQ(a.language, "en-US");
  EXPECT_EQ(t[a.datatype].value, kRdfLangString);
  const Term& b = t[d.quads()[1].object];
  EXPECT_EQ(b.language, "ar");
  EXPECT_EQ(b.direction, "rtl");
  EXPECT_EQ(t[b.datatype].value, kRdfDirLangString);
  EXPECT_EQ(t[t[d.quads()[2].object].datatype].value, "http://www.w3.org/2001/XMLSchema#integer");
  EXPECT_EQ(d.quads()[3].object, d.terms().find_literal("d"));
}

TEST(ReadNQuads, BlankLabelsEndBeforeTheFinalDot) {
  Dataset d;
  read_nquads("_:s.x <http://ex.org/p> _:o.\n_:a:b-c\xC2\xB7 <http://ex.org/p> _:9z .\n", d);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(label_of(d, d.quads()[0].subject), "s.x");
  EXPECT_EQ(label_of(d, d.quads()[0].object), "o");
  EXPECT_EQ(label_of(d, d.quads()[1].subject), "a:b-c\xC2\xB7");
  EXPECT_EQ(label_of(d, d.quads()[1].object), "9z");
}

TEST(ReadNQuads, EachDocumentGetsItsOwnBlankNodes) {
  Dataset d;
  const std::string doc =
      "_:a <http://ex.org/p> _:b .\n"
      "_:b <http://ex.org/p> _:a .\n";
  read_nquads(doc, d);
  read_nquads(doc, d);
  ASSERT_EQ(d.size(), 4u);
  const auto& q = d.quads();
  // Within a document, a label names one node.
  EXPECT_EQ(q[0].subject, q[1].object);
  EXPECT_EQ(q[0].object, q[1].subject);
  // Across documents, never.
  EXPECT_NE(q[0].subject, q[2].subject);
  EXPECT_NE(q[0].subject, q[3].object);
  EXPECT_NE(q[0].object, q[2].object);
}

TEST(ReadNQuads, RecordsLocationOfEachSubject) {
  Dataset d;
  read_nquads(
      "# c\n"
      "\n"
      "  <http://ex.org/s> <http://ex.org/p> <http://ex.org/o> .\r\n"
      "<http://ex.org/s> <http://ex.org/p> <http://ex.org/o2> .\n",
      d, 4, "f.nq");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d.location(0), (SourceLoc{4, 3, 3}));
  EXPECT_EQ(d.location(1), (SourceLoc{4, 4, 1}));
}

TEST(ReadNQuads, ErrorsAreLocated) {
  EXPECT_EQ(error_of("<http://ex.org/s> <http://ex.org/p> \"o\" .\n"
                     "<http://ex.org/s> <http://ex.org/p> \"o\"\n"),
            "<input>:2:40: error: expected '.' at end of statement, found end of line");
  EXPECT_EQ(error_of("<s> <http://ex.org/p> <http://ex.org/o> ."),
            "<input>:1:1: error: relative IRI <s> (N-Quads needs absolute IRIs)");
  EXPECT_EQ(error_of(R"(<http://a/s> <http://a/p> "x\qy" .)"),
            "<input>:1:29: error: invalid escape sequence in string literal");
  EXPECT_EQ(error_of(R"(<http://a/s> <http://a/p> "abc)"),
            "<input>:1:27: error: unterminated string literal");
  EXPECT_EQ(error_of("<http://a/s> <http://a/p> \"ab\ncd\" ."),
            "<input>:1:30: error: line break in string literal (write it as \\n or \\r)");
  EXPECT_EQ(error_of("<http://a/s> <http://a/p> \"\xFF\" ."),
            "<input>:1:28: error: invalid UTF-8 byte 0xFF");
  EXPECT_EQ(error_of("<http://a/s> <http://a/p> \"\xC3\" ."),
            "<input>:1:28: error: invalid UTF-8 sequence starting with byte 0xC3");
  EXPECT_EQ(error_of(R"(<http://a/s> <http://a/p> "\u12G4" .)"),
            "<input>:1:28: error: \\u escape needs 4 hexadecimal digits");
  EXPECT_EQ(error_of(R"(<http://a/s> <http://a/p> "\uD800" .)"),
            "<input>:1:28: error: U+D800 is not a Unicode scalar value");
  EXPECT_EQ(error_of("<http://a/s> <http://a/p> ."),
            "<input>:1:27: error: expected object (IRI, blank node or literal), found '.'");
  EXPECT_EQ(error_of("<http://a/s> <http://a/p> <http://a/o> . x"),
            "<input>:1:42: error: expected end of line after '.', found 'x'");
  EXPECT_EQ(error_of("<http://a/s p> <http://a/p> <http://a/o> ."),
            "<input>:1:12: error: character ' ' is not allowed in an IRI");
  EXPECT_EQ(error_of(R"(<http://a/\u0020> <http://a/p> <http://a/o> .)"),
            "<input>:1:11: error: escaped character U+0020 is not allowed in an IRI");
  EXPECT_EQ(error_of("<http://a/s> <http://a/p> \"x\"@en--up ."),
            "<input>:1:33: error: base direction must be 'ltr' or 'rtl'");
  EXPECT_EQ(error_of("_:-a <http://a/p> <http://a/o> ."),
            "<input>:1:3: error: blank node label cannot start with '-'");
  EXPECT_EQ(error_of("\"s\" <http://a/p> <http://a/o> ."),
            "<input>:1:1: error: expected subject (IRI or blank node), found '\"'");
  EXPECT_EQ(error_of("<http://a/s> _:p <http://a/o> ."),
            "<input>:1:14: error: expected predicate IRI, found '_'");
  EXPECT_EQ(error_of("<http://a/s> <http://a/p> <http://a/o"),
            "<input>:1:27: error: unterminated IRI");
  EXPECT_EQ(error_of("\n\n<http://a/s> <http://a/p> <http://a/o> . .", "models/x.nq"),
            "models/x.nq:3:42: error: expected end of line after '.', found '.'");
}

TEST(ReadNQuads, GeneralizedRdfOnlyWhenAsked) {
  const std::string text = "_:b0 _:b0 \"v\" .\n\"lit\" <http://ex.org/p> _:b0 .\n";
  EXPECT_EQ(error_of(text), "<input>:1:6: error: expected predicate IRI, found '_'");
  Dataset d;
  read_nquads(text, d, NQuadsOptions{.generalized = true});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d.quads()[0].subject, d.quads()[0].predicate);
  EXPECT_TRUE(d.terms()[d.quads()[1].subject].is_literal());
  EXPECT_EQ(to_nquads(d),
            "\"lit\" <http://ex.org/p> _:r0_b0 .\n"
            "_:r0_b0 _:r0_b0 \"v\" .\n");
  Dataset bad;
  try {
    read_nquads("<http://ex.org/s> . .", bad, NQuadsOptions{.generalized = true});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "<input>:1:19: error: expected predicate (IRI, blank node or literal), found '.'");
  }
}

TEST(ReadNQuads, QuadsBeforeAnErrorAreKept) {
  Dataset d;
  EXPECT_THROW(read_nquads("<http://a/s> <http://a/p> <http://a/o> .\n<bad", d), Error);
  EXPECT_EQ(d.size(), 1u);
}

TEST(WriteNQuads, CanonicalLinesSorted) {
  Dataset d;
  TermTable& t = d.terms();
  TermId p = t.iri("http://ex.org/p");
  d.add(Quad{t.iri("http://ex.org/z"), p, t.literal("plain")});
  d.add(Quad{t.iri("http://ex.org/a"), p, t.literal("x", TermId::default_graph(), "en")});
  d.add(Quad{t.iri("http://ex.org/m"), p,
             t.literal("1", "http://www.w3.org/2001/XMLSchema#integer"), t.iri("http://ex.org/g")});
  d.add(Quad{t.blank("b"), p, t.literal("y", TermId::default_graph(), "he", "rtl"), t.blank("g")});
  EXPECT_EQ(to_nquads(d),
            "<http://ex.org/a> <http://ex.org/p> \"x\"@en .\n"
            "<http://ex.org/m> <http://ex.org/p> "
            "\"1\"^^<http://www.w3.org/2001/XMLSchema#integer> <http://ex.org/g> .\n"
            "<http://ex.org/z> <http://ex.org/p> \"plain\" .\n"
            "_:b <http://ex.org/p> \"y\"@he--rtl _:g .\n");
  std::ostringstream os;
  write_nquads(d, os, Format::NTriples);
  EXPECT_EQ(os.str(),
            "<http://ex.org/a> <http://ex.org/p> \"x\"@en .\n"
            "<http://ex.org/m> <http://ex.org/p> "
            "\"1\"^^<http://www.w3.org/2001/XMLSchema#integer> .\n"
            "<http://ex.org/z> <http://ex.org/p> \"plain\" .\n"
            "_:b <http://ex.org/p> \"y\"@he--rtl .\n");
}

TEST(WriteNQuads, NTriplesMergesQuadsThatDifferOnlyByGraph) {
  Dataset d;
  TermTable& t = d.terms();
  Quad q{t.iri("http://ex.org/s"), t.iri("http://ex.org/p"), t.literal("o")};
  d.add(q);
  q.graph = t.iri("http://ex.org/g");
  d.add(q);
  EXPECT_EQ(to_nquads(d, Format::NTriples), "<http://ex.org/s> <http://ex.org/p> \"o\" .\n");
}

TEST(NQuadsRoundTrip, EveryEscapeSurvives) {
  const std::string input =
      R"(<http://ex.org/s> <http://ex.org/p> "t\t b\b n\n r\r f\f q\" a\' s\\ u\u00E9 c\u0001 d\u007F" .)"
      "\n"
      R"(_:x <http://ex.org/p> "v"@en--ltr _:g .)"
      "\n"
      R"(_:x <http://ex.org/\u00E9> "1"^^<http://ex.org/dt> <http://ex.org/g> .)"
      "\n";
  Dataset first;
  read_nquads(input, first);
  const std::string written = to_nquads(first);
  EXPECT_NE(written.find(R"("t\u0009 b\u0008 n\n r\r f\u000C q\" a' s\\ u)"
                         "\xC3\xA9"
                         R"( c\u0001 d\u007F")"),
            std::string::npos)
      << written;
  Dataset second;
  read_nquads(written, second);
  EXPECT_TRUE(isomorphic(first, second)) << describe_difference(first, second);
  // Reading back the original text gives the same literal terms.
  EXPECT_EQ(second.terms()[second.quads()[0].object].value,
            first.terms()[first.quads()[0].object].value);
  // Writing is a fixed point up to blank-node labels.
  Dataset third;
  read_nquads(to_nquads(second), third);
  EXPECT_TRUE(isomorphic(second, third));
}

}  // namespace
}  // namespace mospec::rdf
