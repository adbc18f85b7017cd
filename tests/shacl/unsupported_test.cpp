// What mospec does not implement in a shapes graph is a located error
// ("unsupported-shacl"), never silently ignored: SHACL Advanced Features
// (rules, custom targets, functions), SHACL-JS, entailment, unknown sh:
// properties on shapes and unknown sh: classes. The non-validating
// properties (sh:name, sh:description, ...) are accepted.
#include <gtest/gtest.h>

#include "test_util.hpp"

using namespace mospec;
using namespace mospec::shacl;
using mospec::shacl::test_util::kPrefixLines;
using mospec::shacl::test_util::turtle;

namespace {

TEST(Unsupported, ConstructsMospecDoesNotImplementAreRefusedWithTheirLocation) {
  struct Case {
    std::string body;  // the offending triple is on the last line
    std::string needle;
  };
  const std::vector<Case> cases{
      {"ex:S a sh:NodeShape ; sh:targetClass ex:K ;\n"
       "  sh:rule [ a sh:TripleRule ; sh:subject sh:this ; sh:predicate ex:p ; sh:object 1 ] .",
       "sh:"},
      {"ex:S a sh:NodeShape ; sh:class ex:K ;\n"
       "  sh:target [ ex:custom 1 ] .",
       "sh:target is not supported: custom targets"},
      {"ex:S a sh:NodeShape ; sh:class ex:K .\n"
       "ex:T a sh:SPARQLTarget .",
       "sh:SPARQLTarget is not supported"},
      {"ex:S a sh:NodeShape ; sh:class ex:K .\n"
       "ex:T a sh:SPARQLTargetType .",
       "sh:SPARQLTargetType is not supported"},
      {"ex:S a sh:NodeShape ; sh:targetNode ex:a ;\n"
       "  sh:js [ sh:jsFunctionName \"f\" ] .",
       "SHACL-JS"},
      {"ex:S a sh:NodeShape ; sh:class ex:K .\n"
       "ex:J a sh:JSConstraint .",
       "sh:JSConstraint is not supported"},
      {"ex:S a sh:NodeShape ; sh:class ex:K .\n"
       "<> sh:entailment <http://www.w3.org/ns/entailment/RDFS> .",
       "sh:entailment is not supported"},
      {"ex:S a sh:NodeShape ; sh:targetNode ex:a ; sh:property [ sh:path ex:p ;\n"
       "  sh:minCont 1 ] .",
       "sh:minCont is not a SHACL property that mospec implements"},
      {"ex:S a sh:NodeShape ; sh:targetNode ex:a ;\n"
       "  sh:closed true ; sh:ignoredProperties ( ex:p ) ; sh:inversePath ex:q .",
       "sh:inversePath is not a SHACL property"},
      {"ex:S a sh:NodeShap ; sh:targetNode ex:a ; sh:class ex:K .",
       "sh:NodeShap is not a SHACL class"},
      {"ex:S a sh:NodeShape ; sh:targetNode ex:a ;\n"
       "  sh:sparql [ sh:select \"SELECT $this WHERE { }\" ; sh:ask \"ASK {}\" ] .",
       "sh:ask is not a SHACL property"},
      {"ex:C a sh:ConstraintComponent ; sh:validator [ sh:ask \"ASK {}\" ] ;\n"
       "  sh:parameter [ sh:path ex:x ; sh:optinal true ] .",
       "sh:optinal is not a SHACL property"},
  };
  for (const Case& c : cases) {
    auto g = turtle(c.body);
    try {
      Shapes::compile(g->data, &g->files);
      ADD_FAILURE() << "no error for\n" << c.body;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), "unsupported-shacl") << e.what();
      EXPECT_NE(std::string(e.what()).find(c.needle), std::string::npos) << e.what();
      EXPECT_EQ(e.diagnostic().file, "shapes.ttl") << e.what();
      const auto lines = static_cast<uint32_t>(std::count(c.body.begin(), c.body.end(), '\n'));
      EXPECT_EQ(e.diagnostic().line, kPrefixLines + 1 + lines) << e.what();
    }
  }
}

TEST(Unsupported, NonValidatingPropertiesAndDeclarationsAreAccepted) {
  auto g = turtle(R"(
ex: sh:declare [ sh:prefix "ex" ; sh:namespace "http://example.org/"^^xsd:anyURI ] .
ex:G a sh:PropertyGroup ; rdfs:label "group" .
ex:S a sh:NodeShape ; sh:targetNode ex:a ; sh:name "S" ; sh:description "a shape" ;
  sh:property [ sh:path ex:p ; sh:name "p" ; sh:description "d" ; sh:order 1 ; sh:group ex:G ;
                sh:defaultValue 3 ; sh:minCount 1 ] ;
  sh:sparql [ a sh:SPARQLConstraint ; sh:prefixes ex: ; sh:message "m" ;
              sh:select "SELECT $this WHERE { $this ex:q ?x }" ] .
ex:a ex:p 1 .
)");
  Shapes shapes = Shapes::compile(g->data, &g->files);
  EXPECT_TRUE(validate(shapes, g->data).conforms());
}

}  // namespace
