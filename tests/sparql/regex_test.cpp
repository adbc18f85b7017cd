// XPath regular expressions run by RE2 (regex.hpp): the translation, the
// errors, and the inputs that crashed or hung the backtracking engine before.
#include "sparql/regex.hpp"

#include "test_util.hpp"

namespace mospec::sparql::test {
namespace {

bool matches(std::string_view pattern, std::string_view text, std::string_view flags = {}) {
  return Regex(pattern, flags).search(text);
}

// The error compiling `pattern` throws: its kind and message.
std::pair<RegexError::Kind, std::string> error(std::string_view pattern,
                                               std::string_view flags = {}) {
  try {
    Regex r(pattern, flags);
  } catch (const RegexError& e) {
    return {e.kind(), e.what()};
  }
  ADD_FAILURE() << "compiled: " << pattern;
  return {};
}

TEST(Regex, BacktrackingPatternsRunInLinearTime) {
  // Recursion per character overflowed the stack; exponential backtracking hung.
  EXPECT_TRUE(matches("^(a|b)*$", std::string(20000, 'a') + std::string(20000, 'b')));
  EXPECT_FALSE(matches("^(a|a)*$", std::string(35, 'a') + "b"));
  EXPECT_FALSE(matches("^(a*)*c$", std::string(100000, 'a')));
}

TEST(Regex, SearchesAnywhereUnlessAnchored) {
  EXPECT_TRUE(matches("b", "abc"));
  EXPECT_FALSE(matches("^b", "abc"));
  EXPECT_FALSE(matches("a$", "ba\n"));  // $ is the end of the text, not of a line
}

TEST(Regex, Flags) {
  EXPECT_TRUE(matches("^al", "Alice", "i"));
  EXPECT_FALSE(matches("^al", "Alice"));
  EXPECT_TRUE(matches("^ÉT", "été", "i"));
  EXPECT_TRUE(matches("b.c", "ab\ncd", "s"));
  EXPECT_FALSE(matches("b.c", "ab\ncd"));
  EXPECT_FALSE(matches("b.c", "ab\rcd"));  // '.' excludes \r too
  EXPECT_TRUE(matches("^cd", "ab\ncd", "m"));
  EXPECT_FALSE(matches("^cd", "ab\ncd"));
  EXPECT_TRUE(matches("a b [ ]c", "ab c", "x"));  // whitespace in classes stays
  EXPECT_TRUE(matches("a.b(", "xa.b(y", "q"));
  EXPECT_FALSE(matches("a.b", "aXb", "q"));
  EXPECT_TRUE(matches("A.B", "xa.by", "qi"));
  EXPECT_TRUE(matches("a.b", "a.b", "qsmx"));  // q makes s, m and x irrelevant
  EXPECT_EQ(error("a", "ig"), std::make_pair(RegexError::Kind::Flag,
                                             std::string("invalid regular expression flag 'g' "
                                                         "(allowed: s, m, i, x, q)")));
}

TEST(Regex, XPathEscapesAndClasses) {
  EXPECT_TRUE(matches("^\\i\\c*$", "ex:name-1.x"));
  EXPECT_FALSE(matches("^\\i\\c*$", "1abc"));
  EXPECT_TRUE(matches("^\\i\\c*$", "été"));
  EXPECT_TRUE(matches("^\\I", "1"));
  EXPECT_FALSE(matches("^\\C", "a"));
  EXPECT_TRUE(matches("^[\\i-]+$", "a-b"));
  EXPECT_TRUE(matches("^\\p{Lu}", "Émile"));
  EXPECT_FALSE(matches("^\\p{Lu}", "émile"));
  EXPECT_TRUE(matches("^[[]$", "["));  // '[' inside a class is a character
  EXPECT_TRUE(matches("^[]a]+$", "]a"));
  EXPECT_EQ(error("[\\I]"),
            std::make_pair(RegexError::Kind::Unsupported,
                           std::string("XPath escape \\I inside a character class is not "
                                       "supported (in regular expression \"[\\I]\")")));
  EXPECT_EQ(error("\\p{IsBasicLatin}+").first, RegexError::Kind::Unsupported);
  EXPECT_EQ(error("[a-z-[aeiou]]").first, RegexError::Kind::Unsupported);
}

TEST(Regex, WhatRe2CannotCompileIsAnErrorNamingThePattern) {
  EXPECT_EQ(error("("),
            std::make_pair(RegexError::Kind::Invalid,
                           std::string("invalid regular expression \"(\": missing ): (")));
  EXPECT_EQ(error("(a)\\1").second,
            "invalid regular expression \"(a)\\1\": invalid escape sequence: \\1");
  EXPECT_EQ(error("a{1001}").first, RegexError::Kind::Invalid);
  EXPECT_EQ(error("ab\\").second, "invalid regular expression \"ab\\\": trailing '\\'");
  // A long pattern is quoted in part.
  const std::string long_pattern = std::string("(").append(200, 'a');
  const std::string quoted =
      std::string("invalid regular expression \"(").append(79, 'a').append("...\" (201 bytes): ");
  EXPECT_EQ(error(long_pattern).second.substr(0, quoted.size()), quoted);
}

TEST(Regex, SparqlRegexUsesTheSameTranslation) {
  Data d("ex:s ex:p \"" + std::string(20000, 'a') + "\" . ex:t ex:p \"" + std::string(35, 'a') +
         "b\" .");
  EXPECT_EQ(d.sorted("SELECT ?s { ?s ex:p ?o FILTER REGEX(?o, \"^(a|b)*$\") }"),
            (Rows{"<http://example.org/s>", "<http://example.org/t>"}));
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:p ?o FILTER REGEX(?o, \"^(a|a)*$\") }"),
            Rows{"<http://example.org/s>"});
  // Computed patterns too; an invalid one is an expression error (no match).
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:p ?o FILTER REGEX(?o, CONCAT(\"^(a|a)*\", \"b$\")) }"),
            Rows{"<http://example.org/t>"});
  EXPECT_TRUE(d.run("SELECT ?s { ?s ex:p ?o FILTER REGEX(?o, CONCAT(\"(\", \"\")) }").empty());
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:p ?o FILTER REGEX(\"X:y\", \"^\\\\i\\\\c*$\") } LIMIT 1"),
            Rows{"<http://example.org/s>"});
}

}  // namespace
}  // namespace mospec::sparql::test
