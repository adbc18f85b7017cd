// Parsing: accepted syntax, syntax errors with positions, and the rejection of
// every construct outside the supported subset.
#include <map>

#include "test_util.hpp"

namespace mospec::sparql::test {
namespace {

std::string message(std::string_view query) {
  return error_of(query).diagnostic().message;
}
std::string code(std::string_view query) {
  return error_of(query).code();
}

TEST(SparqlParser, PrologueAndPrefixes) {
  Query q = parse_query(
      "BASE <http://base.org/dir/>\n"
      "PREFIX p: <ns#>\n"
      "PREFIX : <http://default.org/>\n"
      "SELECT ?x WHERE { ?x p:a :b , <rel> }");
  EXPECT_EQ(q.variables(), std::vector<std::string>{"x"});
  // Caller prefixes apply; the query's own declarations override them.
  PrefixMap extra{{"ex", "http://wrong.org/"}, {"other", "http://other.org/"}};
  EXPECT_NO_THROW(
      parse_query("PREFIX ex: <http://example.org/> SELECT * { ?s ex:p other:o }", extra));
}

TEST(SparqlParser, KeywordsAreCaseInsensitiveExceptA) {
  EXPECT_NO_THROW(
      parse_query("select distinct ?x where { ?x a ?t optional { ?x ?p ?o } "
                  "filter(bound(?x)) } order by desc(?x) limit 3 offset 1"));
  EXPECT_EQ(message("SELECT ?x { ?x A ?t }"),
            "line 1, column 16: expected a predicate (IRI, 'a', variable or path), found 'A'");
}

TEST(SparqlParser, VariablesWithDollarAndQuestionMarkAreTheSame) {
  Query q = parse_query("SELECT $this ?this { $this <http://e/p> ?this }");
  EXPECT_EQ(q.variables(), (std::vector<std::string>{"this", "this"}));
  EXPECT_TRUE(q.mentions("this"));
  EXPECT_FALSE(q.mentions("that"));
}

TEST(SparqlParser, DotsAfterFiltersAndBinds) {
  // The upstream shapes end FILTER and BIND with '.'.
  EXPECT_NO_THROW(
      parse_query("SELECT $this { $this <http://e/p> ?v . FILTER NOT EXISTS { "
                  "$this <http://e/q> ?v } . BIND(1 AS ?x) . ?v <http://e/r> ?w . }"));
}

TEST(SparqlParser, LessThanIsAnOperatorAfterAnOperand) {
  Data d("ex:a ex:v 1 .");
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:v ?v FILTER(?v<2&&?v>0) }").size(), 1u);
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:v ?v FILTER(?v <=1) }").size(), 1u);
}

TEST(SparqlParser, SyntaxErrorsNamePositionAndExpectation) {
  EXPECT_EQ(message("SELECT ?x WHERE { ?x <http://e/p> ?y .\n"
                    "  FILTER(?y > 1)\n"
                    "  ?y <http://e/q> ?z ]"),
            "line 3, column 22: expected '}' to close the group started at line 1, column 17, "
            "found ']'");
  EXPECT_EQ(code("SELECT ?x { ?x ?p }"), "sparql-syntax");
  EXPECT_EQ(message("SELECT ?x { ?x ?p }"),
            "line 1, column 19: expected a variable, IRI, literal, blank node or collection, "
            "found '}'");
  EXPECT_EQ(message("SELECT ?x { ?x <http://e/p> ?y"),
            "line 1, column 31: expected '}' to close the group started at line 1, column 11, "
            "found end of query");
  EXPECT_EQ(message("SELECT { ?x ?p ?o }"),
            "line 1, column 8: expected '*' or a variable after SELECT, found '{'");
  EXPECT_EQ(message("SELECT ?x { ?x ex2:p ?o }"), "line 1, column 16: undeclared prefix 'ex2:'");
  EXPECT_EQ(message("SELECT ?x { FILTER(?x = \"abc) }"),
            "line 1, column 25: unterminated string literal (opened here)");
  EXPECT_EQ(message("SELECT ?x { FILTER(?x = \"a\\qb\") }"),
            "line 1, column 27: invalid escape \\q in string literal");
  EXPECT_EQ(message("SELECT ?x { FILTER((?x = 1) }"),
            "line 1, column 29: expected ')' to close the expression started at line 1, "
            "column 19, found '}'");
  EXPECT_EQ(message("SELECT ?x { ?x <http://e/p> ( 1 2 }"),
            "line 1, column 35: expected ')' to close the collection started at line 1, "
            "column 29, found '}'");
  EXPECT_EQ(message("SELECT ?x { ?x <http://e/p> [ <http://e/q> 1 }"),
            "line 1, column 46: expected ']' to close the blank node started at line 1, column "
            "29, found '}'");
  EXPECT_EQ(message("SELECT ?x {} LIMIT x"),
            "line 1, column 20: expected an integer after LIMIT, found 'x'");
  EXPECT_EQ(message("SELECT ?x {} garbage"),
            "line 1, column 14: expected end of query, found 'garbage'");
  EXPECT_EQ(message("SELECT ?x { FILTER(FOO(?x)) }"), "line 1, column 20: unknown function FOO");
  EXPECT_EQ(message("SELECT ?x { FILTER(STRLEN(?x, 2)) }"),
            "line 1, column 20: STRLEN expects 1 argument, found 2");
  EXPECT_EQ(message("SELECT ?x { FILTER(REGEX(?x)) }"),
            "line 1, column 20: REGEX expects 2 or 3 arguments, found 1");
  EXPECT_EQ(message("SELECT ?x { FILTER(REGEX(?x, \"(\")) }"),
            "line 1, column 30: invalid regular expression \"(\": missing ): (");
  EXPECT_EQ(message("SELECT ?x { FILTER(REGEX(?x, \"a\", \"g\")) }"),
            "line 1, column 35: invalid regular expression flag 'g' (allowed: s, m, i, x, q)");
  // A query may come from a file that is not text: its bytes are named by code,
  // never copied to the terminal.
  EXPECT_EQ(message("ASK { ~ }"), "line 1, column 7: unexpected character '~'");
  EXPECT_EQ(message(std::string("ASK { \x1b }")), "line 1, column 7: unexpected byte 0x1B");
}

TEST(SparqlParser, ScopingRules) {
  EXPECT_EQ(message("SELECT ?x {\n ?s <http://e/p> ?x .\n BIND(1 AS ?x) }"),
            "line 3, column 12: BIND ... AS ?x: variable ?x is already in scope in this group "
            "(SPARQL 1.1, 18.2.1)");
  // A variable bound in another group is not in scope of this one.
  EXPECT_NO_THROW(parse_query("SELECT ?x { { ?s <http://e/p> ?x } UNION { BIND(1 AS ?x) } }"));
  EXPECT_EQ(message("SELECT (1 AS ?x) { ?x <http://e/p> ?y }"),
            "line 1, column 14: (... AS ?x): variable ?x is already in scope");
}

TEST(SparqlParser, BlankNodeLabelsAreScopedToOneBasicGraphPattern) {
  EXPECT_NO_THROW(
      parse_query("SELECT ?x { ?x <http://e/p> _:b . FILTER(true) _:b <http://e/q> 1 }"));
  EXPECT_EQ(message("SELECT ?x { ?x <http://e/p> _:b OPTIONAL { _:b <http://e/q> 1 } }"),
            "line 1, column 44: blank node _:b is used in two different basic graph patterns "
            "(SPARQL 1.1, 4.1.4)");
}

TEST(SparqlParser, UnsupportedConstructsAreRejectedWithTheirPosition) {
  struct Case {
    const char* query;
    const char* message;
  };
  const Case cases[] = {
      {"SELECT ?x { ?x ?p ?o MINUS { ?x ?p 1 } }", "line 1, column 22: MINUS is not supported"},
      {"SELECT ?x { SERVICE <http://e/> { ?x ?p ?o } }",
       "line 1, column 13: SERVICE (federated query) is not supported"},
      {"SELECT ?x { VALUES ?x { 1 2 } }", "line 1, column 13: VALUES is not supported"},
      {"SELECT ?x { ?x ?p ?o } VALUES ?x { 1 }", "line 1, column 24: VALUES is not supported"},
      {"SELECT ?x { GRAPH ?g { ?x ?p ?o } }", "line 1, column 13: GRAPH is not supported"},
      {"SELECT ?x FROM <http://e/g> { ?x ?p ?o }",
       "line 1, column 11: FROM (dataset clauses) is not supported"},
      {"SELECT (COUNT(?x) AS ?n) { ?x ?p ?o }",
       "line 1, column 9: aggregate COUNT is not supported"},
      {"SELECT ?x { ?x ?p ?o } GROUP BY STR(?x)",
       "line 1, column 33: GROUP BY an expression is (group by variables) not supported"},
      {"ASK { ?x ?p ?o } GROUP BY ?x",
       "line 1, column 18: GROUP BY in an ASK query is not supported"},
      {"SELECT (CONCAT(GROUP_CONCAT(?x), \"!\") AS ?n) { ?x ?p ?o }",
       "line 1, column 16: GROUP_CONCAT is supported only as a whole SELECT expression, "
       "(GROUP_CONCAT(...) AS ?var)"},
      {"SELECT ?x { ?x ?p ?o } ORDER BY GROUP_CONCAT(?x)",
       "line 1, column 33: GROUP_CONCAT is supported only as a whole SELECT expression, "
       "(GROUP_CONCAT(...) AS ?var)"},
      {"SELECT ?x { ?x ?p ?o } HAVING (?x)", "line 1, column 24: HAVING is not supported"},
      {"CONSTRUCT { ?x ?p ?o } WHERE { ?x ?p ?o }",
       "line 1, column 1: CONSTRUCT queries are not supported"},
      {"DESCRIBE ?x", "line 1, column 1: DESCRIBE queries are not supported"},
      {"INSERT DATA { <a> <b> <c> }", "line 1, column 1: SPARQL Update (INSERT) is not supported"},
      {"SELECT ?x { FILTER(<http://e/f>(?x)) }",
       "line 1, column 20: function <http://e/f> is not supported"},
      {"SELECT ?x { FILTER(REPLACE(?x, \"a\", \"b\")) }",
       "line 1, column 20: function REPLACE is not supported"},
      {"SELECT ?x { FILTER(REGEX(?x, \"\\\\p{IsBasicLatin}\")) }",
       "line 1, column 30: XPath block escape \\p{IsBasicLatin} is not supported (in regular "
       "expression \"\\p{IsBasicLatin}\")"},
  };
  for (const Case& c : cases) {
    QueryError e = error_of(c.query);
    EXPECT_EQ(e.code(), "unsupported-sparql") << c.query;
    EXPECT_EQ(e.diagnostic().message, c.message) << c.query;
  }
}

TEST(SparqlParser, GroupConcatAndGroupBy) {
  EXPECT_EQ(parse_query("SELECT ?s (GROUP_CONCAT(DISTINCT STR(?o); SEPARATOR=\", \") AS ?all) "
                        "{ ?s ?p ?o } GROUP BY ?s")
                .algebra(),
            "(select (?s ?all) (extend ?all (group_concat distinct (str ?o) \", \") (group (?s) "
            "(group (join (bgp (?s ?p ?o)))))))");
  // Without GROUP BY the aggregate makes one group; the separator is a space.
  EXPECT_EQ(parse_query("SELECT (group_concat(?o) AS ?all) { ?s ?p ?o }").algebra(),
            "(select (?all) (extend ?all (group_concat ?o \" \") (group () (group (join (bgp (?s "
            "?p ?o)))))))");
  struct Case {
    const char* query;
    const char* message;
  };
  const Case cases[] = {
      {"SELECT ?p (GROUP_CONCAT(?o) AS ?all) { ?s ?p ?o } GROUP BY ?s",
       "line 1, column 8: ?p is neither a GROUP BY variable nor an aggregate's result (a grouped "
       "SELECT projects only those)"},
      {"SELECT (STR(?o) AS ?t) { ?s ?p ?o } GROUP BY ?s",
       "line 1, column 9: ?o is neither a GROUP BY variable nor an aggregate's result (a grouped "
       "SELECT projects only those)"},
      {"SELECT * { ?s ?p ?o } GROUP BY ?s",
       "line 1, column 23: SELECT * cannot be grouped: name the GROUP BY variables and aggregates"},
      {"SELECT (GROUP_CONCAT(?o) AS ?o) { ?s ?p ?o }",
       "line 1, column 29: (... AS ?o): variable ?o is already in scope"},
      {"SELECT (GROUP_CONCAT(?o; ?x) AS ?all) { ?s ?p ?o }",
       "line 1, column 26: expected SEPARATOR after ';' in GROUP_CONCAT, found variable ?x"},
      {"SELECT (GROUP_CONCAT(?o; SEPARATOR=1) AS ?all) { ?s ?p ?o }",
       "line 1, column 36: expected a string after SEPARATOR =, found number 1"},
      {"SELECT ?s { ?s ?p ?o } GROUP BY",
       "line 1, column 32: expected a variable after GROUP BY, "
       "found end of query"},
  };
  for (const Case& c : cases) {
    QueryError e = error_of(c.query);
    EXPECT_EQ(e.code(), "sparql-syntax") << c.query;
    EXPECT_EQ(e.diagnostic().message, c.message) << c.query;
  }
}

TEST(SparqlParser, SubSelectIsAGroupOfItsOwn) {
  EXPECT_EQ(parse_query("SELECT ?x {\n  { SELECT DISTINCT ?x WHERE { ?x ?p ?o } ORDER BY ?x "
                        "LIMIT 2 OFFSET 1 } }")
                .algebra(),
            "(select (?x) (group (join (group (join (project (?x) (slice 1 2 (distinct (order (?x) "
            "(group (join (bgp (?x ?p ?o)))))))))))))");
  // The WHERE clause itself may be one (grammar rule [53]).
  EXPECT_EQ(parse_query("SELECT ?x { SELECT ?x { ?x ?p ?o } }").algebra(),
            "(select (?x) (group (join (project (?x) (group (join (bgp (?x ?p ?o))))))))");
  struct Case {
    const char* query;
    const char* code;
    const char* message;
  };
  const Case cases[] = {
      {"SELECT ?x { ?x ?p ?o SELECT ?x { ?x ?p ?o } }", "sparql-syntax",
       "line 1, column 22: expected '{' before the sub-SELECT (a sub-SELECT is a group of its "
       "own), found 'SELECT'"},
      {"SELECT ?x { { SELECT ?x { ?x ?p ?o } ?x ?p ?o } }", "sparql-syntax",
       "line 1, column 38: expected '}' to close the group of the sub-SELECT at line 1, column "
       "15, found variable ?x"},
      {"SELECT ?x { { SELECT ?x { ?x ?p ?o } VALUES ?x { 1 } } }", "unsupported-sparql",
       "line 1, column 38: VALUES is not supported"},
      {"SELECT ?x { { SELECT (COUNT(?x) AS ?n) { ?x ?p ?o } } }", "unsupported-sparql",
       "line 1, column 23: aggregate COUNT is not supported"},
  };
  for (const Case& c : cases) {
    QueryError e = error_of(c.query);
    EXPECT_EQ(e.code(), c.code) << c.query;
    EXPECT_EQ(e.diagnostic().message, c.message) << c.query;
  }
}

TEST(SparqlParser, PropertyPathSyntax) {
  for (const char* q : {
           "SELECT * { ?s <http://e/p>/<http://e/q> ?o }",
           "SELECT * { ?s ^<http://e/p> ?o }",
           "SELECT * { ?s (<http://e/p>|<http://e/q>)* ?o }",
           "SELECT * { ?s <http://e/p>+/^<http://e/q>? ?o }",
           "SELECT * { ?s !<http://e/p> ?o }",
           "SELECT * { ?s !(<http://e/p>|^<http://e/q>|a) ?o }",
           "SELECT * { ?s !^a ?o }",
           "SELECT * { ?s (a/(<http://e/p>)) ?o }",
           "SELECT * { ?s ^(<http://e/p>/<http://e/q>) ?o }",
       })
    EXPECT_NO_THROW(parse_query(q)) << q;
  EXPECT_EQ(message("SELECT * { ?s !() ?o }"),
            "line 1, column 15: empty negated property set '!()'");
  EXPECT_EQ(message("SELECT * { ?s (<http://e/p> ?o }"),
            "line 1, column 29: expected ')' to close the path group started at line 1, column 15, "
            "found variable ?o");
}

TEST(SparqlParser, NumbersAndSigns) {
  Data d("ex:a ex:v -1 , 2.5 , 3e2 , +4 .");
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:v -1 , 2.5 , 3e2 , +4 }").size(), 1u);
  EXPECT_EQ(d.run("SELECT ?v { ?s ex:v ?v FILTER(?v - 1 < 0) }").size(), 1u);
  EXPECT_EQ(d.run("SELECT ?v { ?s ex:v ?v FILTER(?v-1 < 0) }").size(), 1u);
}

}  // namespace
}  // namespace mospec::sparql::test

namespace mospec::sparql::test {
namespace {

TEST(SparqlParser, CommentsAndDotsInPrefixedNames) {
  Data d("ex:a.b ex:p 1 .");
  EXPECT_EQ(d.run("SELECT ?s { # a comment with } and <\n ?s ex:p 1. }"),
            (Rows{"<http://example.org/a.b>"}));
  EXPECT_EQ(d.run("SELECT ?o { ex:a.b ex:p ?o.}").size(), 1u);
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:p ?o FILTER regex(str(?s), \"a\\\\.b$\") }").size(), 1u);
}

// Repeats `unit` n times.
std::string repeat(std::string_view unit, size_t n) {
  std::string out;
  out.reserve(unit.size() * n);
  for (size_t i = 0; i < n; ++i) out += unit;
  return out;
}

// Each recursive production, nested 2,000 deep (which used to overflow the
// stack), is refused at the construct that goes past the limit.
TEST(SparqlParser, DeepNestingIsALocatedErrorNotACrash) {
  const std::string too_deep =
      "query nested deeper than 256 levels (groups, parentheses, blank nodes, collections, "
      "paths and unary operators count together); simplify the query";
  const size_t n = 2000;
  const std::map<std::string, std::string> queries{
      {"parentheses", "ASK { ?s ?p ?o FILTER" + repeat("(", n) + "?o" + repeat(")", n) + " }"},
      {"unary", "ASK { ?s ?p ?o FILTER(" + repeat("!", n) + "?o) }"},
      {"arguments", "ASK { ?s ?p ?o FILTER(" + repeat("STR(", n) + "?o" + repeat(")", n) + ") }"},
      {"groups", "ASK " + repeat("{ ", n) + repeat("} ", n)},
      {"exists", "ASK { " + repeat("FILTER EXISTS { ", n) + repeat("} ", n) + "}"},
      {"blank nodes",
       "ASK { ?s " + repeat("<http://e/p> [ ", n) + "<http://e/p> ?o" + repeat(" ]", n) + " }"},
      {"collections", "ASK { ?s <http://e/p> " + repeat("( ", n) + repeat(") ", n) + "}"},
      {"paths", "ASK { ?s " + repeat("(", n) + "<http://e/p>" + repeat(")", n) + " ?o }"},
  };
  for (const auto& [what, query] : queries) {
    const QueryError e = error_of(query);
    EXPECT_EQ(e.code(), "sparql-syntax") << what;
    EXPECT_EQ(e.diagnostic().message.substr(e.diagnostic().message.find(':') + 2), too_deep)
        << what;
    EXPECT_EQ(e.line(), 1u) << what;
  }
  // Where: the token after the '(' that opens the 257th level (groups count).
  EXPECT_EQ(message("ASK { ?s ?p ?o FILTER" + repeat("(", n) + "?o" + repeat(")", n) + " }"),
            "line 1, column 278: " + too_deep);
}

TEST(SparqlParser, NestingWithinTheLimitIsAccepted) {
  const size_t n = 100;
  EXPECT_NO_THROW(
      parse_query("ASK { ?s ?p ?o FILTER" + repeat("(", n) + "!!?o" + repeat(")", n) + " }"));
  EXPECT_NO_THROW(parse_query("ASK " + repeat("{ ", n) + repeat("} ", n)));
  EXPECT_NO_THROW(parse_query("ASK { ?s " + repeat("<http://e/p> [ ", n) + "<http://e/p> ?o" +
                              repeat(" ]", n) + " }"));
  EXPECT_NO_THROW(
      parse_query("ASK { ?s " + repeat("(", n) + "<http://e/p>" + repeat(")", n) + " ?o }"));
}

}  // namespace
}  // namespace mospec::sparql::test
