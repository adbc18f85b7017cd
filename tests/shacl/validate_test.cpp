// Validation semantics beyond the W3C suite: separate graphs, recursion,
// focus locations, and a larger generated graph.
#include <gtest/gtest.h>

#include <chrono>

#include "test_util.hpp"

using namespace mospec;
using namespace mospec::shacl;
using mospec::shacl::test_util::check;
using mospec::shacl::test_util::check_one;
using mospec::shacl::test_util::kPrefixLines;
using mospec::shacl::test_util::text;
using mospec::shacl::test_util::turtle;

namespace {

TEST(Validate, ConformingDataHasNoResults) {
  Report r = check(
      "ex:S a sh:NodeShape ; sh:targetClass ex:C ; sh:property [ sh:path ex:p ; "
      "sh:minCount 1 ; sh:datatype xsd:integer ] .",
      "ex:a a ex:C ; ex:p 1 .");
  EXPECT_TRUE(r.conforms()) << text(r);
}

TEST(Validate, SeparateGraphsShareNoBlankNodesAndKeepTargetNodesAbsentFromData) {
  // Both files get the same blank-node label prefix in their own tables; the
  // report must still tell the shape's blank node from the data's.
  Report r = check(R"(
ex:S a sh:NodeShape ; sh:targetNode ex:missing ; sh:targetClass ex:C ;
  sh:property [ sh:path ex:p ; sh:class ex:D ] .
)",
                   R"(
ex:a a ex:C ; ex:p [ ex:q 1 ] .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  const Result& x = r.results[0];
  EXPECT_EQ(r.terms[x.focus].value, "http://example.org/a");
  EXPECT_TRUE(r.terms[x.value].is_blank());
  EXPECT_TRUE(r.terms[x.shape].is_blank());
  EXPECT_NE(x.value, x.shape);
  ASSERT_TRUE(x.path);
  EXPECT_EQ(x.component, Component::Class);
}

TEST(Validate, TargetNodeMissingFromDataIsStillValidated) {
  Report r = check(
      "ex:S a sh:NodeShape ; sh:targetNode ex:ghost ; sh:property [ sh:path ex:p ; "
      "sh:minCount 1 ] ; sh:in ( ex:ghost ) .",
      "ex:a ex:p 1 .");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  EXPECT_EQ(r.terms[r.results[0].focus].value, "http://example.org/ghost");
  EXPECT_EQ(r.results[0].component, Component::MinCount);
}

TEST(Validate, RecursiveShapesOnCyclicDataRaiseANamedError) {
  auto g = turtle(R"(ex:Person a sh:NodeShape ;
  sh:targetNode ex:alice ;
  sh:property ex:KnowsShape .
ex:KnowsShape sh:path ex:knows ; sh:node ex:Person .
ex:alice ex:knows ex:bob .
ex:bob ex:knows ex:alice .
)");
  Shapes shapes = Shapes::compile(g->data, &g->files);
  try {
    validate(shapes, g->data);
    FAIL() << "no recursion error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "shacl-recursion");
    std::string what = e.what();
    EXPECT_NE(what.find("<http://example.org/Person> -> <http://example.org/KnowsShape> -> "
                        "<http://example.org/Person>"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("shapes.ttl:"), std::string::npos) << what;
  }
}

TEST(Validate, RecursiveShapesOnAcyclicDataTerminate) {
  Report r = check_one(R"(
ex:List a sh:NodeShape ; sh:targetNode ex:l1 ;
  sh:property [ sh:path ex:next ; sh:maxCount 1 ; sh:node ex:List ] .
ex:l1 ex:next ex:l2 . ex:l2 ex:next ex:l3 . ex:l3 ex:next ex:l4, ex:l5 .
)");
  // l3 has two ex:next values: reported when l3 is a focus (reached via
  // sh:property), and sh:node fails upwards for l2 and l1.
  std::string t = text(r);
  EXPECT_EQ(r.results.size(), 1u) << t;
  EXPECT_EQ(r.results[0].component, Component::Node) << t;
}

TEST(Validate, FocusNodesAreLocatedAndResultsSorted) {
  auto shapes = turtle(
      "ex:S a sh:NodeShape ; sh:targetClass ex:C ; sh:property [ sh:path ex:p ; "
      "sh:minCount 1 ] .");
  auto data = turtle(R"(ex:z a ex:C .
ex:y a ex:C .
ex:x a ex:C .
)",
                     "data.ttl");
  Shapes compiled = Shapes::compile(shapes->data, &shapes->files);
  Report r = validate(compiled, data->data);
  ASSERT_EQ(r.results.size(), 3u);
  // In the order the nodes are written, not by IRI.
  EXPECT_EQ(r.terms[r.results[0].focus].value, "http://example.org/z");
  EXPECT_EQ(r.results[0].focus_loc.line, kPrefixLines + 1);
  EXPECT_EQ(r.terms[r.results[2].focus].value, "http://example.org/x");
  EXPECT_EQ(r.results[2].focus_loc.line, kPrefixLines + 3);

  // A caller-supplied locator wins; unlocated results sort last by IRI.
  ValidateOptions options;
  options.locate = [](rdf::TermId) -> std::optional<SourceLoc> { return std::nullopt; };
  Report unlocated = validate(compiled, data->data, options);
  EXPECT_EQ(unlocated.terms[unlocated.results[0].focus].value, "http://example.org/x");
}

TEST(Validate, SharedPropertyShapeReportsOncePerRoute) {
  Report r = check_one(R"(
ex:s1 a sh:NodeShape ; sh:targetNode ex:i ; sh:property ex:s2, ex:s3 .
ex:s2 sh:path ex:p ; sh:property ex:s4 .
ex:s3 sh:path ex:q ; sh:property ex:s4 .
ex:s4 sh:path ex:r ; sh:class ex:C .
ex:i ex:p ex:j ; ex:q ex:j . ex:j ex:r ex:k .
)");
  EXPECT_EQ(r.results.size(), 2u) << text(r);
}

TEST(Validate, QualifiedValueShapesDisjoint) {
  Report r = check_one(R"(
ex:Hand a sh:NodeShape ; sh:targetNode ex:h ;
  sh:property [ sh:path ex:digit ; sh:qualifiedValueShape [ sh:class ex:Thumb ] ;
                sh:qualifiedMinCount 1 ; sh:qualifiedMaxCount 1 ; sh:qualifiedValueShapesDisjoint true ] ;
  sh:property [ sh:path ex:digit ; sh:qualifiedValueShape [ sh:class ex:Finger ] ;
                sh:qualifiedMinCount 4 ; sh:qualifiedMaxCount 4 ; sh:qualifiedValueShapesDisjoint true ] .
ex:h ex:digit ex:t, ex:f1, ex:f2, ex:f3, ex:f4 .
ex:t a ex:Thumb, ex:Finger . ex:f1 a ex:Finger . ex:f2 a ex:Finger . ex:f3 a ex:Finger . ex:f4 a ex:Finger .
)");
  // The thumb is also a finger: it counts for neither.
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  EXPECT_EQ(r.results[0].component, Component::QualifiedMinCount);
}

TEST(Validate, ManyFocusNodesScale) {
  // 20k entities x 5 triples against a typical shape: index lookups only.
  std::string data;
  for (int i = 0; i < 20000; ++i) {
    std::string n = "ex:n" + std::to_string(i);
    data += n + " a ex:Thing ; ex:name \"n" + std::to_string(i) + "\" ; ex:size " +
            std::to_string(i % 100) + " ; ex:next ex:n" + std::to_string(i + 1) + " ; ex:tag ex:t" +
            std::to_string(i % 7) + " .\n";
  }
  auto shapes = turtle(R"(
ex:S a sh:NodeShape ; sh:targetClass ex:Thing ; sh:closed true ; sh:ignoredProperties ( rdf:type ) ;
  sh:property [ sh:path ex:name ; sh:minCount 1 ; sh:maxCount 1 ; sh:datatype xsd:string ; sh:minLength 2 ] ;
  sh:property [ sh:path ex:size ; sh:datatype xsd:integer ; sh:maxInclusive 98 ] ;
  sh:property [ sh:path ex:next ; sh:nodeKind sh:IRI ; sh:maxCount 1 ] ;
  sh:property [ sh:path ex:tag ; sh:in ( ex:t0 ex:t1 ex:t2 ex:t3 ex:t4 ex:t5 ex:t6 ) ] .
)");
  auto d = turtle(data, "data.ttl");
  Shapes compiled = Shapes::compile(shapes->data, &shapes->files);
  auto start = std::chrono::steady_clock::now();
  Report r = validate(compiled, d->data);
  auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() -
                                                                  start)
                .count();
  // ex:size 99 appears for every 100th node.
  EXPECT_EQ(r.count(Level::Violation), 200u);
  std::cout << d->data.size() << " triples validated in " << ms << " ms\n";
}

}  // namespace

namespace {

TEST(Validate, RecursionAlongALongChainStopsWithAnErrorInsteadOfOverflowingTheStack) {
  std::string body =
      "ex:List a sh:NodeShape ; sh:targetNode ex:n0 ;\n"
      "  sh:property [ sh:path ex:next ; sh:node ex:List ] .\n";
  for (int i = 0; i < 5000; ++i)
    body += "ex:n" + std::to_string(i) + " ex:next ex:n" + std::to_string(i + 1) + " .\n";
  auto g = turtle(body);
  Shapes shapes = Shapes::compile(g->data, &g->files);
  try {
    validate(shapes, g->data);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "shacl-recursion");
    EXPECT_NE(std::string(e.what()).find("deeper than"), std::string::npos) << e.what();
  }
}

TEST(Validate, ClosedShapesReportEachExtraTripleOnce) {
  auto g = turtle(R"(
ex:S a sh:NodeShape ; sh:targetNode ex:a ; sh:closed true ; sh:property [ sh:path ex:p ] .
)");
  rdf::Dataset data;
  auto& t = data.terms();
  rdf::TermId a = t.iri("http://example.org/a"), p = t.iri("http://example.org/p"),
              q = t.iri("http://example.org/q"), g1 = t.iri("http://example.org/g1"),
              g2 = t.iri("http://example.org/g2");
  data.add({a, p, a, g1});
  data.add({a, q, a, g1});
  data.add({a, q, a, g2});
  Shapes shapes = Shapes::compile(g->data, &g->files);
  Report r = validate(shapes, data);
  ASSERT_EQ(r.results.size(), 1u) << to_text(r, nullptr);
  EXPECT_EQ(r.results[0].component, Component::Closed);
  EXPECT_EQ(r.terms[r.results[0].path->predicate].value, "http://example.org/q");
}

}  // namespace
