// SHACL-SPARQL constraints (sh:sparql): pre-binding, result mapping,
// messages, prefixes, errors.
#include <gtest/gtest.h>

#include "test_util.hpp"

using namespace mospec;
using namespace mospec::shacl;
using mospec::shacl::test_util::check_one;
using mospec::shacl::test_util::kPrefixLines;
using mospec::shacl::test_util::refused;
using mospec::shacl::test_util::text;
using mospec::shacl::test_util::turtle;

namespace {

TEST(SparqlConstraint, PreboundThisAndResultMapping) {
  Report r = check_one(R"(
ex:S a sh:NodeShape ; sh:targetClass ex:Op ;
  sh:sparql [ a sh:SPARQLConstraint ;
    sh:message "{$this} refers to {?a} and {?b}"@en ;
    sh:select """
      PREFIX ex: <http://example.org/>
      SELECT $this ?a ?b WHERE {
        $this ex:in1/ex:ref ?a .
        $this ex:in2/ex:ref ?b .
        FILTER(?a != ?b)
      }""" ] .
ex:good a ex:Op ; ex:in1 ex:x ; ex:in2 ex:y . ex:x ex:ref ex:f . ex:y ex:ref ex:f .
ex:bad a ex:Op ; ex:in1 ex:u ; ex:in2 ex:v . ex:u ex:ref ex:f . ex:v ex:ref ex:g .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  const Result& x = r.results[0];
  EXPECT_EQ(r.terms[x.focus].value, "http://example.org/bad");
  EXPECT_EQ(x.component, Component::Sparql);
  EXPECT_EQ(x.value, x.focus);  // node shape without ?value: the focus node
  EXPECT_FALSE(x.source_constraint.is_any());
  ASSERT_EQ(x.messages.size(), 1u);
  EXPECT_EQ(r.terms[x.messages[0]].value,
            "<http://example.org/bad> refers to <http://example.org/f> and <http://example.org/g>");
  EXPECT_EQ(r.terms[x.messages[0]].language, "en");
  EXPECT_NE(to_turtle(r).find("sh:sourceConstraintComponent sh:SPARQLConstraintComponent"),
            std::string::npos);
}

TEST(SparqlConstraint, PrefixesValuePathAndPropertyShapes) {
  Report r = check_one(R"(
ex: sh:declare [ sh:prefix "ex" ; sh:namespace "http://example.org/"^^xsd:anyURI ] .
ex:S a sh:NodeShape ; sh:targetNode ex:a ;
  sh:property [ sh:path ex:age ;
    sh:sparql [ sh:prefixes ex: ;
      sh:select "SELECT $this ?value WHERE { $this $PATH ?value . FILTER(?value > 150) }" ] ] ;
  sh:sparql [ sh:prefixes ex: ;
    sh:select "SELECT $this ?path ?value WHERE { $this ?path ?value . FILTER(?path = ex:nick) }" ] .
ex:a ex:age 200, 20 ; ex:nick "al" .
)");
  ASSERT_EQ(r.results.size(), 2u) << text(r);
  std::string t = text(r);
  EXPECT_NE(t.find("path <http://example.org/age>, value \"200\"^^"), std::string::npos) << t;
  EXPECT_NE(t.find("path <http://example.org/nick>, value \"al\""), std::string::npos) << t;
}

TEST(SparqlConstraint, CurrentShapeAndDeactivated) {
  Report r = check_one(R"(
ex:S a sh:NodeShape ; sh:targetNode ex:a ; ex:limit 3 ;
  sh:sparql [ sh:select """PREFIX ex: <http://example.org/>
      SELECT $this WHERE { $currentShape ex:limit ?l . $this ex:n ?n . FILTER(?n > ?l) }""" ] ;
  sh:sparql [ sh:deactivated true ; sh:select "SELECT $this WHERE { }" ] .
ex:a ex:n 5 .
)");
  EXPECT_EQ(r.results.size(), 1u) << text(r);
}

TEST(SparqlConstraint, FailureVariableAbortsValidation) {
  auto g = turtle(R"(
ex:S a sh:NodeShape ; sh:targetNode ex:a ;
  sh:sparql [ sh:select "SELECT $this ?failure WHERE { BIND(true AS ?failure) }" ] .
)");
  Shapes shapes = Shapes::compile(g->data, &g->files);
  try {
    validate(shapes, g->data);
    FAIL() << "no failure";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "shacl-failure");
  }
}

// Sub-SELECTs (W3C sparql/pre-binding-007 and -006): one that returns $this
// sees it pre-bound; one that uses $this without returning it is refused at
// the query's position in the shapes file.
TEST(SparqlConstraint, SubSelects) {
  const std::string data = "ex:a ex:p 1 , 2 , 3 .\nex:b ex:p 1 .\n";
  Report r = check_one(data + R"(
ex:S a sh:NodeShape ; sh:targetNode ex:a , ex:b ;
  sh:sparql [ sh:select """SELECT $this ?value WHERE {
    { SELECT $this ?value WHERE { $this <http://example.org/p> ?value } ORDER BY DESC(?value) LIMIT 1 }
    FILTER (?value > 2) }""" ] .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  EXPECT_EQ(r.terms[r.results[0].focus].value, "http://example.org/a");
  EXPECT_EQ(r.terms[r.results[0].value].value, "3");
  Error e = refused(data + R"(ex:S a sh:NodeShape ; sh:targetNode ex:a ;
  sh:sparql [ sh:select """SELECT $this WHERE {
    { SELECT * WHERE { FILTER ($this = <urn:a>) } } }""" ] .
)");
  EXPECT_EQ(e.code(), "unsupported-shacl") << e.what();
  EXPECT_EQ(e.diagnostic().line, kPrefixLines + 5) << e.what();
  EXPECT_EQ(e.diagnostic().column, 7u) << e.what();
  EXPECT_NE(std::string(e.what()).find("does not return the pre-bound variable $this"),
            std::string::npos)
      << e.what();
}

// W3C sparql/node/sparql-002: a shape that is its own SPARQL constraint
// (`sh:sparql` pointing at itself) may carry sh:select, sh:prefixes and
// sh:message beside its targets; they were refused as unknown shape properties.
TEST(SparqlConstraint, AShapeThatIsItsOwnConstraint) {
  Report r = check_one(R"(
ex:decls sh:declare [ sh:prefix "ex" ; sh:namespace "http://example.org/"^^xsd:anyURI ] .
ex:S a sh:NodeShape , sh:SPARQLConstraint ; sh:targetClass ex:Country ;
  sh:sparql ex:S ; sh:prefixes ex:decls ; sh:message "German labels only" ;
  sh:select """SELECT $this (ex:germanLabel AS ?path) ?value WHERE {
    $this ex:germanLabel ?value . FILTER (!langMatches(lang(?value), "de")) }""" .
ex:es a ex:Country ; ex:germanLabel "Spain"@en .
ex:de a ex:Country ; ex:germanLabel "Spanien"@de .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  EXPECT_EQ(r.terms[r.results[0].focus].value, "http://example.org/es");
  ASSERT_NE(r.results[0].path, nullptr);
  EXPECT_EQ(r.terms[r.results[0].path->predicate].value, "http://example.org/germanLabel");
}

// $shapesGraph and GRAPH are not implemented: a located unsupported-shacl
// error at the query's position, never a conforming verdict (W3C
// sparql/pre-binding/shapesGraph-001 expects a result).
TEST(SparqlConstraint, ShapesGraphAndGraphAreLocatedUnsupportedErrors) {
  const std::pair<const char*, uint32_t> cases[] = {
      {"SELECT $this WHERE {\n  FILTER bound($shapesGraph) }", 16},
      {"SELECT $this WHERE {\n  GRAPH ?g { $this ?p ?o } }", 3},
  };
  for (const auto& [query, column] : cases) {
    Error e = refused(std::string("ex:S a sh:NodeShape ; sh:targetNode ex:a ;\n"
                                  "  sh:sparql [ sh:select \"\"\"") +
                      query + "\"\"\" ] .\n");
    EXPECT_EQ(e.code(), "unsupported-shacl") << e.what();
    EXPECT_EQ(e.diagnostic().line, kPrefixLines + 3) << e.what();
    EXPECT_EQ(e.diagnostic().column, column) << e.what();
  }
}

TEST(SparqlConstraint, BadQueriesAreIllFormedShapes) {
  const char* cases[] = {
      "ex:S a sh:NodeShape ; sh:sparql [ sh:select \"SELECT $this WHERE { $this ex:p }\" ] .",
      "ex:S a sh:NodeShape ; sh:sparql [ sh:select \"SELECT ?x WHERE { ?x ?p ?o }\" ] .",
      "ex:S a sh:NodeShape ; sh:sparql [ ex:noSelect 1 ] .",
  };
  for (const char* body : cases) {
    auto g = turtle(body);
    try {
      Shapes::compile(g->data, &g->files);
      ADD_FAILURE() << "no error for " << body;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), "shacl-ill-formed") << body;
      EXPECT_NE(std::string(e.what()).find("shapes.ttl:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("<http://example.org/S>"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
