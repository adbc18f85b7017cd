// Evaluation of each supported feature against small hand-built datasets.
#include "test_util.hpp"

namespace mospec::sparql::test {
namespace {

const char* kPeople = R"(
ex:alice a ex:Person ; ex:name "Alice" ; ex:age 30 ; ex:knows ex:bob, ex:carol .
ex:bob a ex:Person ; ex:name "Bob"@en ; ex:age 25 ; ex:knows ex:carol .
ex:carol a ex:Person ; ex:name "Carol" ; ex:age "41"^^xsd:int .
ex:dave a ex:Robot ; ex:name "Dave" .
)";

TEST(SparqlEval, BasicGraphPatternWithSemicolonCommaAndA) {
  Data d(kPeople);
  EXPECT_EQ(d.sorted("SELECT ?p ?n WHERE { ?p a ex:Person ; ex:name ?n . }"),
            (Rows{R"(<http://example.org/alice> "Alice")", R"(<http://example.org/bob> "Bob"@en)",
                  R"(<http://example.org/carol> "Carol")"}));
  EXPECT_EQ(d.sorted("SELECT ?x { ex:alice ex:knows ?x , ?x }"),
            (Rows{"<http://example.org/bob>", "<http://example.org/carol>"}));
}

TEST(SparqlEval, ProjectionKeepsOrderAndStarListsInScopeVariables) {
  Data d(kPeople);
  Query q = parse_query("SELECT ?n ?p { ?p ex:name ?n }", prefixes());
  EXPECT_EQ(q.variables(), (std::vector<std::string>{"n", "p"}));
  Query star = parse_query("SELECT * { ?p ex:knows [ ex:name ?n ] FILTER(?z) }", prefixes());
  EXPECT_EQ(star.variables(), (std::vector<std::string>{"p", "n"}));
  EXPECT_EQ(d.run("SELECT ?n ?p { ?p ex:name ?n FILTER(?p = ex:dave) }"),
            (Rows{R"("Dave" <http://example.org/dave>)"}));
}

TEST(SparqlEval, DistinctAndOrderByLimitOffset) {
  Data d(kPeople);
  EXPECT_EQ(d.run("SELECT DISTINCT ?x { ?s ex:knows ?x } ORDER BY ?x"),
            (Rows{"<http://example.org/bob>", "<http://example.org/carol>"}));
  EXPECT_EQ(d.run("SELECT ?x { ?s ex:knows ?x } ORDER BY DESC(?x)"),
            (Rows{"<http://example.org/carol>", "<http://example.org/carol>",
                  "<http://example.org/bob>"}));
  EXPECT_EQ(d.run("SELECT ?a { ?p ex:age ?a } ORDER BY ?a LIMIT 2"),
            (Rows{R"("25"^^<http://www.w3.org/2001/XMLSchema#integer>)",
                  R"("30"^^<http://www.w3.org/2001/XMLSchema#integer>)"}));
  EXPECT_EQ(d.run("SELECT ?a { ?p ex:age ?a } ORDER BY DESC(?a) OFFSET 1 LIMIT 1"),
            (Rows{R"("30"^^<http://www.w3.org/2001/XMLSchema#integer>)"}));
  EXPECT_EQ(d.run("SELECT ?a { ?p ex:age ?a } LIMIT 0"), Rows{});
  EXPECT_EQ(d.run("SELECT REDUCED ?t { ?p a ?t } ORDER BY ?t").size(), 2u);
}

TEST(SparqlEval, GroupConcatPerGroupSortedWithDistinctAndSeparator) {
  Data d(R"(
    ex:arm ex:joint ex:j3, ex:j1, ex:j2 .
    ex:leg ex:joint ex:k2, ex:k1 .
    ex:a ex:tag "b", "a", "c"@en .
    ex:b ex:tag "x"@en, "y"@en .
  )");
  // One row per group, in the order of each group's first solution; the
  // strings in code-point order whatever order the solutions came in.
  EXPECT_EQ(d.sorted("SELECT ?c (GROUP_CONCAT(STR(?j); SEPARATOR=\", \") AS ?js) "
                     "{ ?c ex:joint ?j } GROUP BY ?c"),
            (Rows{R"(<http://example.org/arm> "http://example.org/j1, http://example.org/j2, )"
                  R"(http://example.org/j3")",
                  R"(<http://example.org/leg> "http://example.org/k1, http://example.org/k2")"}));
  // The default separator is a space; DISTINCT keeps one of equal terms.
  EXPECT_EQ(d.run("SELECT (GROUP_CONCAT(?n) AS ?all) { ?c ex:joint ?j BIND(\"j\" AS ?n) }"),
            (Rows{R"("j j j j j")"}));
  EXPECT_EQ(d.run("SELECT (GROUP_CONCAT(DISTINCT ?n; separator=\"\") AS ?all) "
                  "{ ?c ex:joint ?j BIND(\"j\" AS ?n) }"),
            (Rows{R"("j")"}));
  // A language tag is kept when every string has it (as CONCAT does).
  EXPECT_EQ(d.run("SELECT ?s (GROUP_CONCAT(?t) AS ?all) { ?s ex:tag ?t } GROUP BY ?s ORDER BY ?s"),
            (Rows{R"(<http://example.org/a> "a b c")", R"(<http://example.org/b> "x y"@en)"}));
  // An element that is no string (an IRI here) makes the aggregate an error:
  // the variable is unbound, the group stays.
  EXPECT_EQ(d.run("SELECT ?c (GROUP_CONCAT(?j) AS ?js) { ?c ex:joint ?j } GROUP BY ?c ORDER BY ?c"),
            (Rows{"<http://example.org/arm> UNDEF", "<http://example.org/leg> UNDEF"}));
  // No solutions: GROUP BY makes no group; without it, one group with "".
  EXPECT_EQ(d.run("SELECT ?c (GROUP_CONCAT(STR(?j)) AS ?js) { ?c ex:none ?j } GROUP BY ?c"),
            Rows{});
  EXPECT_EQ(d.run("SELECT (GROUP_CONCAT(STR(?j)) AS ?js) { ?c ex:none ?j }"), (Rows{R"("")"}));
  // Pre-bound like SHACL's $this; expressions of keys and aggregates may be projected.
  EXPECT_EQ(
      d.run("SELECT ?c (CONCAT(\"[\", ?js, \"]\") AS ?list) { { SELECT ?c "
            "(GROUP_CONCAT(STR(?j); SEPARATOR=\"|\") AS ?js) { ?c ex:joint ?j } GROUP BY ?c } }",
            {Binding{"c", d.iri("leg")}}),
      (Rows{R"(<http://example.org/leg> "[http://example.org/k1|http://example.org/k2]")"}));
  EXPECT_EQ(
      d.run("SELECT ?s (GROUP_CONCAT(?t) AS ?all) (STRLEN(?all) AS ?n) { ?s ex:tag ?t } "
            "GROUP BY ?s ORDER BY ?s"),
      (Rows{R"(<http://example.org/a> "a b c" "5"^^<http://www.w3.org/2001/XMLSchema#integer>)",
            R"(<http://example.org/b> "x y"@en "3"^^<http://www.w3.org/2001/XMLSchema#integer>)"}));
}

TEST(SparqlEval, BlankNodesAndCollectionsInPatterns) {
  Data d(R"(
    ex:m ex:row ( 1 2 3 ) .
    ex:n ex:row ( 4 5 ) .
    ex:a ex:knows [ ex:name "x" ] .
  )");
  EXPECT_EQ(d.run("SELECT ?s ?c { ?s ex:row ( 1 ?b ?c ) }"),
            (Rows{R"(<http://example.org/m> "3"^^<http://www.w3.org/2001/XMLSchema#integer>)"}));
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:row ( ?x ?y ) }"), (Rows{"<http://example.org/n>"}));
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:knows [ ex:name \"x\" ] }"), (Rows{"<http://example.org/a>"}));
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:knows _:b . _:b ex:name ?n }"),
            (Rows{"<http://example.org/a>"}));
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:knows [] }"), (Rows{"<http://example.org/a>"}));
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:row () }"), Rows{});
}

TEST(SparqlEval, LiteralsOfEveryForm) {
  Data d(R"(
    ex:a ex:v "plain" . ex:b ex:v "tagged"@en . ex:c ex:v "x"^^ex:dt .
    ex:d ex:v 1 . ex:e ex:v 1.5 . ex:f ex:v 1.0e3 . ex:g ex:v true . ex:h ex:v "it's \"q\"\n" .
    ex:i ex:v -7 .
  )");
  auto one = [&](const std::string& literal) {
    auto rows = d.run("SELECT ?s { ?s ex:v " + literal + " }");
    if (rows.size() == 1) return rows[0];
    std::string count = "<";
    count.append(std::to_string(rows.size())).append(" rows>");
    return count;
  };
  EXPECT_EQ(one("\"plain\""), "<http://example.org/a>");
  EXPECT_EQ(one("'plain'"), "<http://example.org/a>");
  EXPECT_EQ(one("\"\"\"plain\"\"\""), "<http://example.org/a>");
  EXPECT_EQ(one("'''plain'''"), "<http://example.org/a>");
  EXPECT_EQ(one("\"plain\"^^xsd:string"), "<http://example.org/a>");
  EXPECT_EQ(one("\"tagged\"@en"), "<http://example.org/b>");
  EXPECT_EQ(one("\"x\"^^<http://example.org/dt>"), "<http://example.org/c>");
  EXPECT_EQ(one("1"), "<http://example.org/d>");
  EXPECT_EQ(one("1.5"), "<http://example.org/e>");
  EXPECT_EQ(one("1.0e3"), "<http://example.org/f>");
  EXPECT_EQ(one("true"), "<http://example.org/g>");
  EXPECT_EQ(one("\"it\\u0027s \\\"q\\\"\\n\""), "<http://example.org/h>");
  EXPECT_EQ(one("'''it's \"q\"\n'''"), "<http://example.org/h>");
  EXPECT_EQ(one("-7"), "<http://example.org/i>");
}

TEST(SparqlEval, OptionalAndItsFilterAsLeftJoinCondition) {
  Data d(kPeople);
  EXPECT_EQ(d.sorted("SELECT ?p ?k { ?p ex:name ?n OPTIONAL { ?p ex:knows ?k } }"),
            (Rows{"<http://example.org/alice> <http://example.org/bob>",
                  "<http://example.org/alice> <http://example.org/carol>",
                  "<http://example.org/bob> <http://example.org/carol>",
                  "<http://example.org/carol> UNDEF", "<http://example.org/dave> UNDEF"}));
  // The filter inside OPTIONAL sees the outer ?a (LeftJoin condition).
  EXPECT_EQ(d.sorted("SELECT ?p ?k { ?p ex:age ?a OPTIONAL { ?p ex:knows ?k FILTER(?a > 26) } }"),
            (Rows{"<http://example.org/alice> <http://example.org/bob>",
                  "<http://example.org/alice> <http://example.org/carol>",
                  "<http://example.org/bob> UNDEF", "<http://example.org/carol> UNDEF"}));
  // !BOUND after OPTIONAL: negation as failure.
  EXPECT_EQ(d.sorted("SELECT ?p { ?p ex:name ?n OPTIONAL { ?p ex:knows ?k } FILTER(!BOUND(?k)) }"),
            (Rows{"<http://example.org/carol>", "<http://example.org/dave>"}));
}

TEST(SparqlEval, FilterInNestedGroupDoesNotSeeOuterVariables) {
  Data d(kPeople);
  // Bottom-up semantics: ?a is unbound inside the inner group, so the filter fails.
  EXPECT_EQ(d.run("SELECT ?p { ?p ex:age ?a { ?p ex:name ?n FILTER(BOUND(?a)) } }"), Rows{});
  EXPECT_EQ(d.run("SELECT ?p { ?p ex:age ?a { ?p ex:name ?n FILTER(!BOUND(?a)) } }").size(), 3u);
}

TEST(SparqlEval, UnionBranchesAreJoinedWithTheOuterSolutionSeparately) {
  Data d(kPeople);
  // The first branch's filter must not see the outer ?a; the second branch joins on ?x.
  EXPECT_EQ(d.sorted("SELECT ?x ?z { ?x ex:age ?a { { ?x ex:knows ?z FILTER(BOUND(?a)) } "
                     "UNION { ?x ex:name ?z } } }"),
            (Rows{R"(<http://example.org/alice> "Alice")", R"(<http://example.org/bob> "Bob"@en)",
                  R"(<http://example.org/carol> "Carol")"}));
}

TEST(SparqlEval, UnionAndNestedGroups) {
  Data d(kPeople);
  EXPECT_EQ(d.sorted("SELECT ?x { { ?x a ex:Robot } UNION { ?x ex:age 25 } }"),
            (Rows{"<http://example.org/bob>", "<http://example.org/dave>"}));
  EXPECT_EQ(d.sorted("SELECT ?x ?y { { ?x a ex:Robot } UNION { ?y ex:age 25 } }"),
            (Rows{"<http://example.org/dave> UNDEF", "UNDEF <http://example.org/bob>"}));
  EXPECT_EQ(d.sorted("SELECT ?x { ?x a ex:Person { ?x ex:knows ex:carol } }"),
            (Rows{"<http://example.org/alice>", "<http://example.org/bob>"}));
}

// An evaluator remembers the dataset's literals as it decoded them: queries
// that read the same literals again (numbers, ill-typed numbers, language
// strings) answer as they do on a fresh evaluator, in either order.
TEST(SparqlEval, LiteralsDecodedOnceAnswerAsOnAFreshEvaluator) {
  const char* turtle = R"(
    ex:a ex:v 1.5, "2"^^xsd:int, "x"^^xsd:int, "hi"@en, "3.0E0"^^xsd:double, true .
  )";
  const std::vector<std::string> queries = {
      "SELECT ?v { ex:a ex:v ?v FILTER(?v > 1) } ORDER BY ?v",
      "SELECT ?v { ex:a ex:v ?v FILTER(isNumeric(?v)) } ORDER BY ?v",
      "SELECT (?v * 2 AS ?w) { ex:a ex:v ?v } ORDER BY ?w",
      "SELECT ?v { ex:a ex:v ?v FILTER(lang(?v) = \"en\" || ?v) } ORDER BY ?v",
  };
  std::vector<Rows> fresh;
  for (const std::string& q : queries) fresh.push_back(Data(turtle).run(q));
  Data d(turtle);
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < queries.size(); ++i) {
      const size_t k = pass == 0 ? i : queries.size() - 1 - i;
      EXPECT_EQ(d.run(queries[k]), fresh[k]) << queries[k];
    }
  }
  EXPECT_EQ(fresh[1].size(), 3u);  // 1.5, 2, 3.0E0; the ill-typed "x"^^xsd:int is not numeric
}

TEST(SparqlEval, ComparisonsAcrossNumericTypes) {
  Data d(kPeople);
  // "41"^^xsd:int compares numerically with integers and decimals.
  EXPECT_EQ(d.sorted("SELECT ?p { ?p ex:age ?a FILTER(?a > 29.5) }"),
            (Rows{"<http://example.org/alice>", "<http://example.org/carol>"}));
  EXPECT_EQ(d.run("SELECT ?p { ?p ex:age ?a FILTER(?a = 4.1e1) }"),
            (Rows{"<http://example.org/carol>"}));
  EXPECT_EQ(d.run("SELECT ?p { ?p ex:age ?a FILTER(?a >= 41 && ?a <= 41) }"),
            (Rows{"<http://example.org/carol>"}));
  EXPECT_EQ(d.run("SELECT ?p { ?p ex:age ?a FILTER(?a != 30 && ?a < 30) }"),
            (Rows{"<http://example.org/bob>"}));
}

TEST(SparqlEval, StringAndTermComparisons) {
  Data d(kPeople);
  EXPECT_EQ(d.sorted("SELECT ?n { ?p ex:name ?n FILTER(?n < \"Carol\") }"),
            (Rows{R"("Alice")"}));  // "Bob"@en is not comparable with a simple literal
  EXPECT_EQ(d.run("SELECT ?p { ?p ex:name ?n FILTER(?n = \"Bob\"@EN) }"),
            (Rows{"<http://example.org/bob>"}));
  EXPECT_EQ(d.run("SELECT ?p { ?p ex:knows ?k FILTER(?k != ex:carol) }"),
            (Rows{"<http://example.org/alice>"}));
  // Different literals of unknown datatypes: '=' is a type error, so both filters fail.
  Data u(R"(ex:a ex:v "1"^^ex:t1 ; ex:w "2"^^ex:t1 .)");
  EXPECT_EQ(u.run("SELECT ?s { ?s ex:v ?x ; ex:w ?y FILTER(?x = ?y) }"), Rows{});
  EXPECT_EQ(u.run("SELECT ?s { ?s ex:v ?x ; ex:w ?y FILTER(?x != ?y) }"), Rows{});
  EXPECT_EQ(u.run("SELECT ?s { ?s ex:v ?x FILTER(?x = ?x) }").size(), 1u);
}

TEST(SparqlEval, DateTimeComparison) {
  Data d(R"(ex:a ex:t "2024-01-01T10:00:00Z"^^xsd:dateTime .
             ex:b ex:t "2024-01-01T11:30:00+02:00"^^xsd:dateTime .)");
  // 11:30+02:00 is 09:30Z, before 10:00Z.
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:t ?t FILTER(?t < \"2024-01-01T09:45:00Z\"^^xsd:dateTime) }"),
            (Rows{"<http://example.org/b>"}));
}

// Lexical forms are read by rdf/xsd.hpp, as sh:datatype reads them: a
// dateTime on a day the calendar does not have is ill-typed, so comparing it
// is an error and the filter drops the row.
TEST(SparqlEval, IllTypedDateTimeIsNotComparable) {
  Data d(R"(ex:a ex:t "2024-02-30T10:00:00Z"^^xsd:dateTime .
             ex:b ex:t "2024-02-28T10:00:00Z"^^xsd:dateTime .)");
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:t ?t FILTER(?t < \"2024-03-01T00:00:00Z\"^^xsd:dateTime) }"),
            (Rows{"<http://example.org/b>"}));
}

TEST(SparqlEval, ThreeValuedLogic) {
  Data d("ex:a ex:v 1 .");
  auto passes = [&](const std::string& expr) {
    return d.run("SELECT ?s { ?s ex:v ?v FILTER(" + expr + ") }").size() == 1;
  };
  // ?u is unbound: comparisons with it are errors.
  EXPECT_TRUE(passes("?u = 1 || true"));
  EXPECT_TRUE(passes("true || ?u = 1"));
  EXPECT_FALSE(passes("?u = 1 || false"));
  EXPECT_FALSE(passes("?u = 1 && true"));
  EXPECT_TRUE(passes("!(?u = 1 && false)"));  // E && F = F, !F = T
  EXPECT_FALSE(passes("!(?u = 1)"));          // !E = E
  EXPECT_FALSE(passes("!(!(?u = 1))"));
  EXPECT_TRUE(passes("!(?u = 1 || ?u = 2) || true"));
  EXPECT_FALSE(passes("?u = 1 || ?u = 2"));
  EXPECT_FALSE(
      passes("\"abc\""
             " && ?u"));
  EXPECT_TRUE(passes("\"abc\""));
  EXPECT_FALSE(passes("\"\""));
  EXPECT_FALSE(passes("0"));
  EXPECT_TRUE(passes("0.5"));
  EXPECT_FALSE(passes("\"NaN\"^^xsd:double"));
  EXPECT_FALSE(passes("\"abc\"^^xsd:integer"));  // ill-typed: EBV false
  EXPECT_FALSE(passes("ex:a"));                  // IRI: EBV error
}

TEST(SparqlEval, ArithmeticPromotionAndResultDatatypes) {
  Data d("ex:a ex:v 1 .");
  auto value = [&](const std::string& expr) {
    auto rows = d.run("SELECT ?x { ?s ex:v ?v BIND((" + expr + ") AS ?x) }");
    return rows.size() == 1 ? rows[0] : "?";
  };
  const std::string xsd = "^^<http://www.w3.org/2001/XMLSchema#";
  EXPECT_EQ(value("1 + 2"), "\"3\"" + xsd + "integer>");
  EXPECT_EQ(value("7 / 2"), "\"3.5\"" + xsd + "decimal>");
  EXPECT_EQ(value("6 / 3"), "\"2.0\"" + xsd + "decimal>");
  EXPECT_EQ(value("1 + 0.5"), "\"1.5\"" + xsd + "decimal>");
  EXPECT_EQ(value("2 * 1.5e0"), "\"3.0E0\"" + xsd + "double>");
  EXPECT_EQ(value("\"2\"^^xsd:float * 2"), "\"4.0E0\"" + xsd + "float>");
  EXPECT_EQ(value("-?v - 1"), "\"-2\"" + xsd + "integer>");
  EXPECT_EQ(value("ABS(-2.25)"), "\"2.25\"" + xsd + "decimal>");
  EXPECT_EQ(value("1 / 0"), "UNDEF");                          // decimal division by zero
  EXPECT_EQ(value("1.0e0 / 0"), "\"INF\"" + xsd + "double>");  // IEEE
  EXPECT_EQ(value("9223372036854775807 + 1"), "UNDEF");        // 64-bit overflow
  EXPECT_EQ(value("\"a\" + 1"), "UNDEF");
  EXPECT_EQ(value("?v * 10"), "\"10\"" + xsd + "integer>");
}

TEST(SparqlEval, BuiltinFunctions) {
  Data d(R"(ex:a ex:name "Alice"@en ; ex:v 1 ; ex:n "ab\ncd" . _:b ex:v 2 .)");
  auto passes = [&](const std::string& expr) {
    return d.run("SELECT ?s { ex:a ex:name ?name ; ex:v ?v ; ex:n ?nl . BIND(ex:a AS ?s) FILTER(" +
                 expr + ") }")
               .size() == 1;
  };
  EXPECT_TRUE(passes("isIRI(?s) && isURI(?s) && !isBlank(?s) && !isLiteral(?s)"));
  EXPECT_TRUE(passes("isLiteral(?name) && isNumeric(?v) && !isNumeric(?name)"));
  EXPECT_TRUE(passes("STR(?s) = \"http://example.org/a\""));
  EXPECT_TRUE(passes("STR(?name) = \"Alice\" && LANG(?name) = \"en\" && LANG(?v) = \"\""));
  EXPECT_TRUE(passes("DATATYPE(?v) = xsd:integer && DATATYPE(?name) = rdf:langString"));
  EXPECT_TRUE(passes("DATATYPE(STR(?v)) = xsd:string"));
  EXPECT_TRUE(passes("REGEX(?name, \"^al\", \"i\") && !REGEX(?name, \"^al\")"));
  EXPECT_TRUE(passes("REGEX(?nl, \"b.c\", \"s\") && !REGEX(?nl, \"b.c\")"));
  EXPECT_TRUE(passes("REGEX(?nl, \"^cd\", \"m\") && !REGEX(?nl, \"^cd\")"));
  EXPECT_TRUE(passes("REGEX(\"abc\", \"a b c\", \"x\")"));
  EXPECT_TRUE(passes("REGEX(\"abc\", CONCAT(\"a\", \"b\"))"));
  EXPECT_TRUE(passes("STRSTARTS(?name, \"Al\") && STRENDS(STR(?s), \"/a\")"));
  EXPECT_TRUE(passes("CONTAINS(?name, \"lic\") && !CONTAINS(\"x\", \"y\")"));
  EXPECT_TRUE(passes("STRLEN(?name) = 5 && STRLEN(\"\\u00e9t\\u00e9\") = 3"));
  EXPECT_TRUE(passes("sameTerm(?s, ex:a) && !sameTerm(?v, 1.0) && ?v = 1.0"));
  EXPECT_TRUE(passes("IRI(\"http://example.org/a\") = ?s && URI(?s) = ?s"));
  EXPECT_TRUE(passes("COALESCE(?undefined, 1/0, 42) = 42"));
  EXPECT_TRUE(passes("IF(?v = 1, true, false) && IF(false, false, true)"));
  EXPECT_FALSE(passes("IF(?undefined, true, true)"));
  EXPECT_TRUE(passes("?v IN (3, 2, 1) && ?v NOT IN (4, 5) && !(?v IN ())"));
  EXPECT_FALSE(passes("?v IN (?undefined, 4)"));  // no match and an error: error
  EXPECT_TRUE(passes("?v IN (?undefined, 1)"));   // a match wins
  EXPECT_TRUE(passes("UCASE(\"ab\") = \"AB\" && LCASE(?name) = \"alice\"@en"));
  EXPECT_TRUE(passes("LANGMATCHES(LANG(?name), \"EN\") && LANGMATCHES(LANG(?name), \"*\")"));
  EXPECT_TRUE(passes("xsd:integer(\"12\") = 12 && xsd:double(?v) = 1 && xsd:string(?v) = \"1\""));
  EXPECT_TRUE(passes("xsd:boolean(\"true\") && CEIL(1.2) = 2 && FLOOR(-1.5) = -2"));
  EXPECT_TRUE(passes("ROUND(2.5) = 3 && ROUND(-2.5) = -2"));
  EXPECT_TRUE(passes("BOUND(?v) && !BOUND(?zz)"));
  EXPECT_EQ(d.run("SELECT ?x { ?x ex:v 2 FILTER(isBlank(?x)) }").size(), 1u);
}

TEST(SparqlEval, BindExtendsAndErrorsLeaveUnbound) {
  Data d(kPeople);
  EXPECT_EQ(
      d.sorted("SELECT ?p ?b { ?p ex:age ?a BIND(?a + 1 AS ?b) FILTER(?b > 30) }"),
      (Rows{R"(<http://example.org/alice> "31"^^<http://www.w3.org/2001/XMLSchema#integer>)",
            R"(<http://example.org/carol> "42"^^<http://www.w3.org/2001/XMLSchema#integer>)"}));
  // BIND to a term of the data joins with later patterns.
  EXPECT_EQ(d.run("SELECT ?p { BIND(\"Alice\" AS ?n) ?p ex:name ?n }"),
            (Rows{"<http://example.org/alice>"}));
  EXPECT_EQ(d.run("SELECT ?x { ex:dave ex:name ?n BIND(?n + 1 AS ?x) }"), (Rows{"UNDEF"}));
  EXPECT_EQ(d.run("SELECT (STR(?n) AS ?s) { ex:dave ex:name ?n }"), (Rows{R"("Dave")"}));
}

TEST(SparqlEval, ExistsAndNotExistsSubstituteTheCurrentSolution) {
  Data d(kPeople);
  EXPECT_EQ(d.sorted("SELECT ?p { ?p a ex:Person FILTER NOT EXISTS { ?p ex:knows ?x } }"),
            (Rows{"<http://example.org/carol>"}));
  EXPECT_EQ(d.sorted("SELECT ?p { ?p a ex:Person FILTER EXISTS { ?p ex:knows ex:carol } }"),
            (Rows{"<http://example.org/alice>", "<http://example.org/bob>"}));
  // Substitution reaches filters inside the EXISTS pattern.
  EXPECT_EQ(d.sorted("SELECT ?p { ?p ex:age ?a FILTER EXISTS { ?q ex:age ?b FILTER(?b > ?a) } }"),
            (Rows{"<http://example.org/alice>", "<http://example.org/bob>"}));
}

TEST(SparqlEval, PreBindingHoldsInEverySubPattern) {
  Data d(kPeople);
  const rdf::TermId alice = d.iri("alice");
  const rdf::TermId bob = d.iri("bob");
  const char* q = "SELECT $this ?k { $this ex:knows ?k }";
  EXPECT_EQ(d.sorted(q, {{"this", alice}}),
            (Rows{"<http://example.org/alice> <http://example.org/bob>",
                  "<http://example.org/alice> <http://example.org/carol>"}));
  EXPECT_EQ(d.sorted(q, {{"this", bob}}),
            (Rows{"<http://example.org/bob> <http://example.org/carol>"}));
  // Only in a filter: still bound (Replace joins every BGP with the bindings).
  EXPECT_EQ(d.run("SELECT ?n { ?p ex:name ?n FILTER(?p = $this) }", {{"this", bob}}),
            (Rows{R"("Bob"@en)"}));
  // In a nested group with a filter, in OPTIONAL and UNION.
  EXPECT_EQ(d.run("SELECT ?x { { FILTER(BOUND($this)) } BIND(1 AS ?x) }", {{"this", bob}}).size(),
            1u);
  EXPECT_EQ(d.run("SELECT ?k { OPTIONAL { $this ex:knows ?k } }", {{"this", bob}}),
            (Rows{"<http://example.org/carol>"}));
  EXPECT_EQ(d.sorted("SELECT ?k { { $this ex:knows ?k } UNION { ?k ex:knows $this } }",
                     {{"this", d.iri("carol")}}),
            (Rows{"<http://example.org/alice>", "<http://example.org/bob>"}));
  // EXISTS with pre-binding (the SHACL pattern of the upstream shapes).
  const char* shacl =
      "SELECT $this ?value { $this ex:knows ?value . "
      "FILTER NOT EXISTS { $this ex:knows / ex:knows ?value } . }";
  EXPECT_EQ(d.run(shacl, {{"this", alice}}),
            (Rows{"<http://example.org/alice> <http://example.org/bob>"}));
  EXPECT_EQ(d.run(shacl, {{"$this", bob}}),
            (Rows{"<http://example.org/bob> <http://example.org/carol>"}));
  // An unknown focus node (not in the data): zero-length paths still include it.
  Data e("ex:a ex:p ex:b .");
  const rdf::TermId outside = e.eval().import(d.data().terms(), alice);
  EXPECT_EQ(e.run("SELECT ?x { $this ex:p* ?x }", {{"this", outside}}),
            (Rows{"<http://example.org/alice>"}));
}

TEST(SparqlEval, PreBoundVariableMustNotBeAssigned) {
  Data d(kPeople);
  Query q = parse_query("SELECT $this { ?x ex:age ?a\n  BIND(?x AS $this) }", prefixes());
  ResultSet rs;
  try {
    d.eval().select(q, std::vector<Binding>{{"this", d.iri("alice")}}, rs);
    FAIL() << "no error";
  } catch (const QueryError& e) {
    EXPECT_EQ(e.code(), "unsupported-sparql");
    EXPECT_EQ(e.line(), 2u);
    EXPECT_STREQ(e.diagnostic().message.c_str(),
                 "line 2, column 14: AS ?this assigns the pre-bound variable $this (not allowed "
                 "with SHACL pre-binding)");
  }
  const std::string_view names[] = {"this", "currentShape"};
  EXPECT_THROW(q.check_prebinding(names), QueryError);
  Query ok = parse_query("SELECT $this { $this ex:age ?a BIND(?a AS ?b) }", prefixes());
  EXPECT_NO_THROW(ok.check_prebinding(names));
  EXPECT_THROW(parse_query("SELECT (1 AS ?this) {}", prefixes()).check_prebinding(names),
               QueryError);
}

TEST(SparqlEval, AskQueries) {
  Data d(kPeople);
  EXPECT_TRUE(d.eval().ask(parse_query("ASK { ex:alice ex:knows ex:bob }", prefixes())));
  EXPECT_FALSE(d.eval().ask(parse_query("ASK { ex:bob ex:knows ex:alice }", prefixes())));
  Query q = parse_query("ASK { $this ex:knows ?x }", prefixes());
  EXPECT_TRUE(d.eval().ask(q, std::vector<Binding>{{"this", d.iri("bob")}}));
  EXPECT_FALSE(d.eval().ask(q, std::vector<Binding>{{"this", d.iri("carol")}}));
  ResultSet rs;
  d.eval().select(q, std::vector<Binding>{{"this", d.iri("bob")}}, rs);
  EXPECT_EQ(rs.size(), 1u);
}

TEST(SparqlEval, DefaultGraphIsTheUnionOfGraphsAsASet) {
  rdf::Dataset data;
  auto& t = data.terms();
  const auto a = t.iri("http://example.org/a"), p = t.iri("http://example.org/p"),
             b = t.iri("http://example.org/b"), g1 = t.iri("http://example.org/g1"),
             g2 = t.iri("http://example.org/g2");
  data.add({a, p, b, g1});
  data.add({a, p, b, g2});
  data.add({b, p, a, g2});
  Evaluator ev(data);
  ResultSet rs;
  ev.select(parse_query("SELECT ?x ?y { ?x <http://example.org/p> ?y }"), {}, rs);
  EXPECT_EQ(rs.size(), 2u);
  // The evaluator remembers which quads restate an earlier one: later queries
  // over the same quads, entered from either end, still see each triple once.
  const std::pair<const char*, size_t> queries[] = {
      {"SELECT ?y { <http://example.org/a> <http://example.org/p> ?y }", 1},
      {"SELECT ?x { ?x <http://example.org/p> <http://example.org/b> }", 1},
      {"SELECT ?x ?y { ?x ?p ?y }", 2}};
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& [q, n] : queries) {
      ResultSet again;
      ev.select(parse_query(q), {}, again);
      EXPECT_EQ(again.size(), n) << q;
    }
  }
}

TEST(SparqlEval, ComputedTermsAndConstantsMissingFromTheData) {
  Data d(kPeople);
  // A constant absent from the data matches nothing, but compares fine.
  EXPECT_EQ(d.run("SELECT ?p { ?p ex:knows ex:nobody }"), Rows{});
  EXPECT_EQ(d.run("SELECT ?p { ?p ex:name ?n FILTER(?n != \"Zed\") }").size(), 4u);
  ResultSet rs;
  Query q = parse_query("SELECT ?x { BIND(CONCAT(\"new\", \"term\") AS ?x) }");
  d.eval().select(q, {}, rs);
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_GE(rs.at(0, 0).index, Evaluator::kComputedBase);
  EXPECT_EQ(d.eval().to_ntriples(rs.at(0, 0)), R"("newterm")");
  // A computed term that exists in the data gets the data id.
  d.eval().select(parse_query("SELECT ?x { BIND(STR(\"Alice\") AS ?x) }"), {}, rs);
  EXPECT_LT(rs.at(0, 0).index, Evaluator::kComputedBase);
}

TEST(SparqlEval, FilterPlacementDoesNotChangeResults) {
  Data d(kPeople);
  // The filter mentions ?k bound by the OPTIONAL: it must run after it.
  EXPECT_EQ(d.sorted("SELECT ?p { ?p ex:age ?a FILTER(!BOUND(?k)) OPTIONAL { ?p ex:knows ?k } }"),
            (Rows{"<http://example.org/carol>"}));
  // The filter mentions ?b bound by a later BIND.
  EXPECT_EQ(d.sorted("SELECT ?p { FILTER(?b = 31) ?p ex:age ?a BIND(?a + 1 AS ?b) }"),
            (Rows{"<http://example.org/alice>"}));
}

TEST(SparqlEval, SubSelectIsEvaluatedOnItsOwnThenJoined) {
  Data d(kPeople);
  // LIMIT applies inside, before the join: the oldest person, then their name.
  EXPECT_EQ(d.run("SELECT ?p ?n { ?p ex:name ?n { SELECT ?p { ?p ex:age ?a } ORDER BY DESC(?a) "
                  "LIMIT 1 } }"),
            (Rows{R"(<http://example.org/carol> "Carol")"}));
  // A variable the sub-SELECT does not project is its own: ?n inside is not ?n outside.
  EXPECT_EQ(d.sorted("SELECT ?p ?n { ?p ex:age ?n { SELECT ?p { ?p ex:name ?n } } }"),
            (Rows{"<http://example.org/alice> \"30\"^^<http://www.w3.org/2001/XMLSchema#integer>",
                  "<http://example.org/bob> \"25\"^^<http://www.w3.org/2001/XMLSchema#integer>",
                  "<http://example.org/carol> \"41\"^^<http://www.w3.org/2001/XMLSchema#int>"}));
  // Projected expressions, DISTINCT, and a sub-SELECT under OPTIONAL run per solution.
  EXPECT_EQ(d.sorted("SELECT ?p ?k { ?p a ?t OPTIONAL { { SELECT DISTINCT ?p (1 AS ?k) "
                     "{ ?p ex:knows ?x } } } }"),
            (Rows{"<http://example.org/alice> \"1\"^^<http://www.w3.org/2001/XMLSchema#integer>",
                  "<http://example.org/bob> \"1\"^^<http://www.w3.org/2001/XMLSchema#integer>",
                  "<http://example.org/carol> UNDEF", "<http://example.org/dave> UNDEF"}));
  EXPECT_EQ(d.run("SELECT * { { SELECT * { ex:alice ex:knows ?x } ORDER BY ?x OFFSET 1 } }"),
            (Rows{"<http://example.org/carol>"}));
  // Nested sub-SELECTs.
  EXPECT_EQ(d.run("SELECT ?n { { SELECT ?n { { SELECT ?p { ?p a ex:Robot } } ?p ex:name ?n } } }"),
            (Rows{R"("Dave")"}));
}

TEST(SparqlEval, PreBindingReachesIntoSubSelectsThatProjectTheVariable) {
  Data d(kPeople);
  const rdf::TermId bob = d.iri("bob");
  // W3C SHACL test sparql/pre-binding/pre-binding-007.
  EXPECT_EQ(d.run("SELECT $this { { SELECT $this { FILTER($this = ex:bob) } } }", {{"this", bob}}),
            (Rows{"<http://example.org/bob>"}));
  EXPECT_EQ(d.run("SELECT $this ?x { { SELECT $this ?x { $this ex:knows ?x } } }", {{"this", bob}}),
            (Rows{"<http://example.org/bob> <http://example.org/carol>"}));
  // pre-binding-006: a sub-SELECT that uses $this without returning it.
  Query q = parse_query("SELECT $this {\n  { SELECT * { FILTER($this = ex:bob) } } }", prefixes());
  const std::string_view names[] = {"this"};
  try {
    q.check_prebinding(names);
    FAIL() << "no error";
  } catch (const QueryError& e) {
    EXPECT_EQ(e.code(), "unsupported-sparql");
    EXPECT_EQ(e.diagnostic().message,
              "line 2, column 5: this sub-SELECT does not return the pre-bound variable $this "
              "(SHACL pre-binding requires every sub-SELECT to return the pre-bound variables the "
              "query uses)");
  }
  ResultSet rs;
  EXPECT_THROW(d.eval().select(q, std::vector<Binding>{{"this", bob}}, rs), QueryError);
  EXPECT_TRUE(q.mentions("this"));
  // unsupported-sparql-004: even one that does not use $this must return it.
  EXPECT_THROW(parse_query("SELECT $this { $this ?p ?o { SELECT ?x { ?x ?q ?y } } }", prefixes())
                   .check_prebinding(names),
               QueryError);
  EXPECT_NO_THROW(parse_query("SELECT ?x { ?x ?p ?o { SELECT ?x { ?x ?q ?y } } }", prefixes())
                      .check_prebinding(names));
}

}  // namespace
}  // namespace mospec::sparql::test
