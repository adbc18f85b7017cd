// The translation to the algebra (SPARQL 1.1 section 18.2), checked on its
// printed form: filter placement, OPTIONAL filters as LeftJoin conditions,
// BIND as Extend, paths and syntactic sugar expanded.
#include "test_util.hpp"

namespace mospec::sparql::test {
namespace {

std::string algebra(std::string_view query) {
  return parse_query(query, prefixes()).algebra();
}

TEST(SparqlAlgebra, FilterMovesToTheBgpThatBindsItsVariables) {
  EXPECT_EQ(algebra("SELECT ?x { FILTER(?y > 1) ?x ex:p ?y }"),
            "(select (?x) (group (join (bgp (?x <http://example.org/p> ?y) (filter (> ?y "
            "\"1\"^^<http://www.w3.org/2001/XMLSchema#integer>))))))");
}

TEST(SparqlAlgebra, OptionalFiltersBecomeTheLeftJoinCondition) {
  EXPECT_EQ(algebra("SELECT * { ?x ex:p ?y OPTIONAL { ?x ex:q ?z FILTER(?z != ?y) } }"),
            "(select (?x ?y ?z) (group (join (bgp (?x <http://example.org/p> ?y))) (leftjoin "
            "(group (join (bgp (?x <http://example.org/q> ?z)))) (!= ?z ?y))))");
}

TEST(SparqlAlgebra, FiltersStayAfterOptionalAndBindWhenTheyNeedThem) {
  EXPECT_EQ(algebra("SELECT ?x { ?x ex:p ?y OPTIONAL { ?x ex:q ?z } FILTER(!BOUND(?z)) }"),
            "(select (?x) (group (join (bgp (?x <http://example.org/p> ?y))) (leftjoin (group "
            "(join (bgp (?x <http://example.org/q> ?z))))) (filter (! (bound ?z)))))");
  EXPECT_EQ(algebra("SELECT ?x { ?x ex:p ?y BIND(?y + 1 AS ?z) FILTER(?z > 2) }"),
            "(select (?x) (group (join (bgp (?x <http://example.org/p> ?y))) (extend ?z (+ ?y "
            "\"1\"^^<http://www.w3.org/2001/XMLSchema#integer>)) (filter (> ?z "
            "\"2\"^^<http://www.w3.org/2001/XMLSchema#integer>))))");
}

TEST(SparqlAlgebra, FilterWithoutGroupVariablesRunsFirst) {
  EXPECT_EQ(algebra("SELECT ?x { ?x ex:p ?y { ?y ex:q ?w } FILTER(BOUND($this)) }"),
            "(select (?x) (group (filter (bound ?this)) (join (bgp (?x <http://example.org/p> "
            "?y))) (join (group (join (bgp (?y <http://example.org/q> ?w)))))))");
}

TEST(SparqlAlgebra, PathsAreSplitPerTranslationRules) {
  EXPECT_EQ(algebra("SELECT ?o { ?s ex:a/^ex:b/(ex:c|ex:d)* ?o }"),
            "(select (?o) (group (join (bgp (?s <http://example.org/a> ?_:#0) (?_:#1 "
            "<http://example.org/b> ?_:#0) (?_:#1 (* (alt <http://example.org/c> "
            "<http://example.org/d>)) ?o)))))");
  EXPECT_EQ(algebra("SELECT ?o { ?s ^(ex:a/ex:b) ?o }"),
            "(select (?o) (group (join (bgp (?_:#0 <http://example.org/b> ?s) (?o "
            "<http://example.org/a> ?_:#0)))))");
  EXPECT_EQ(algebra("SELECT ?o { ?s !(ex:a|^ex:b) ?o }"),
            "(select (?o) (group (join (bgp (?s (! <http://example.org/a> ^<http://example.org/b>) "
            "?o)))))");
}

TEST(SparqlAlgebra, CollectionsAndBlankNodePropertyLists) {
  EXPECT_EQ(
      algebra("SELECT ?s { ?s ex:p ( 1 [ ex:q ?v ] ) }"),
      "(select (?s) (group (join (bgp (?_:#0 <http://www.w3.org/1999/02/22-rdf-syntax-ns#first> "
      "\"1\"^^<http://www.w3.org/2001/XMLSchema#integer>) (?_:#0 "
      "<http://www.w3.org/1999/02/22-rdf-syntax-ns#rest> ?_:#1) (?_:#2 "
      "<http://example.org/q> ?v) (?_:#1 <http://www.w3.org/1999/02/22-rdf-syntax-ns#first> "
      "?_:#2) (?_:#1 <http://www.w3.org/1999/02/22-rdf-syntax-ns#rest> "
      "<http://www.w3.org/1999/02/22-rdf-syntax-ns#nil>) (?s <http://example.org/p> "
      "?_:#0)))))");
}

TEST(SparqlAlgebra, UnionExistsAndSolutionModifiers) {
  EXPECT_EQ(algebra("SELECT DISTINCT ?x { { ?x a ex:A } UNION { ?x a ex:B } "
                    "FILTER NOT EXISTS { ?x ex:p ?x } } ORDER BY DESC(?x) LIMIT 2"),
            "(select (?x) (slice 0 2 (distinct (order ((desc ?x)) (group (join (union (group "
            "(join (bgp (?x <http://www.w3.org/1999/02/22-rdf-syntax-ns#type> "
            "<http://example.org/A>)))) (group (join (bgp (?x "
            "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type> <http://example.org/B>)))))) "
            "(filter (notexists (group (join (bgp (?x <http://example.org/p> ?x)))))))))))");
  EXPECT_EQ(algebra("ASK {}"), "(ask (group))");
  EXPECT_EQ(algebra("SELECT (STR(?x) AS ?s) { ?x ex:p 1 }"),
            "(select (?s) (extend ?s (str ?x) (group (join (bgp (?x <http://example.org/p> "
            "\"1\"^^<http://www.w3.org/2001/XMLSchema#integer>))))))");
}

}  // namespace
}  // namespace mospec::sparql::test
