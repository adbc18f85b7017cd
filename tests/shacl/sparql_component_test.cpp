// SPARQL-based constraint components (SHACL 6): parameters, ASK validators
// per value node, node and property SELECT validators ($PATH), optional
// parameters, messages and label templates, and the errors for components
// mospec would otherwise have to ignore. The W3C SHACL-SPARQL suite is not in
// ../shared, so these are our own cases.
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

std::string message(const Report& r, const Result& x) {
  return x.messages.empty() ? x.default_message : std::string(r.terms[x.messages[0]].value);
}

// SHACL's own example (6.2.3): values must be literals in one language.
const std::string kAskComponent = R"(
ex:LanguageComponent a sh:ConstraintComponent ;
  sh:parameter [ sh:path ex:lang ; sh:datatype xsd:string ; sh:minLength 2 ] ;
  sh:labelTemplate "Values are literals with language \"{$lang}\"" ;
  sh:validator ex:hasLang .
ex:hasLang a sh:SPARQLAskValidator ;
  sh:message "{$value} is not in language {$lang}" ;
  sh:ask """ASK { FILTER (isLiteral($value) && langMatches(lang($value), $lang)) }""" .
)";

TEST(SparqlComponent, AskValidatorChecksEachValueNode) {
  Report r = check_one(kAskComponent + R"(
ex:S a sh:NodeShape ; sh:targetNode ex:a, ex:b ;
  sh:property [ sh:path ex:label ; ex:lang "de" ] .
ex:a ex:label "Hallo"@de, "Hello"@en, ex:notALiteral .
ex:b ex:label "Tschuess"@de .
)");
  ASSERT_EQ(r.results.size(), 2u) << text(r);
  std::vector<std::string> messages;
  for (const Result& x : r.results) {
    EXPECT_EQ(x.component, Component::SparqlComponent);
    EXPECT_EQ(r.terms[x.component_node].value, "http://example.org/LanguageComponent");
    EXPECT_EQ(r.terms[x.focus].value, "http://example.org/a");
    EXPECT_TRUE(x.source_constraint.is_any());  // sh:sourceConstraint is for sh:sparql only
    ASSERT_NE(x.path, nullptr);
    EXPECT_EQ(r.terms[x.path->predicate].value, "http://example.org/label");
    messages.push_back(message(r, x));
  }
  std::sort(messages.begin(), messages.end());
  EXPECT_EQ(messages[0], "<http://example.org/notALiteral> is not in language de");
  EXPECT_EQ(messages[1], "Hello is not in language de");
  std::string turtle_report = to_turtle(r);
  EXPECT_NE(
      turtle_report.find("sh:sourceConstraintComponent <http://example.org/LanguageComponent>"),
      std::string::npos)
      << turtle_report;
  EXPECT_EQ(turtle_report.find("sh:sourceConstraint "), std::string::npos) << turtle_report;
  EXPECT_NE(text(r).find("<http://example.org/LanguageComponent>, path"), std::string::npos)
      << text(r);
  // The RDF form names the component too (the W3C suite compares this one).
  rdf::Dataset ds = to_dataset(r);
  EXPECT_FALSE(ds.terms().find_iri("http://example.org/LanguageComponent").is_any());
}

TEST(SparqlComponent, AShapeThatConformsHasNoResults) {
  Report r = check_one(kAskComponent + R"(
ex:S a sh:NodeShape ; sh:targetNode ex:a ; sh:property [ sh:path ex:label ; ex:lang "de" ] .
ex:a ex:label "Hallo"@de, "Guten Tag"@de-AT .
)");
  EXPECT_TRUE(r.conforms()) << text(r);
}

TEST(SparqlComponent, AskValidatorOnNodeShapesAndDeactivatedShapes) {
  Report r = check_one(kAskComponent + R"(
ex:S a sh:NodeShape ; sh:targetNode "Hi"@en, "Hallo"@de ; ex:lang "en" .
ex:Off a sh:NodeShape ; sh:targetNode "Hallo"@de ; ex:lang "en" ; sh:deactivated true .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  EXPECT_EQ(r.terms[r.results[0].value].value, "Hallo");
  EXPECT_EQ(r.results[0].path, nullptr);
}

TEST(SparqlComponent, NodeSelectValidatorWithThisAndParameters) {
  Report r2 = check_one(R"(
ex:Forbidden a sh:ConstraintComponent ;
  sh:parameter [ sh:path ex:forbidden ] ;
  sh:nodeValidator [ a sh:SPARQLSelectValidator ;
    sh:message "{$this} uses {$forbidden}, with value {?value}" ;
    sh:select "SELECT $this ?value WHERE { $this ?p ?value . FILTER(?p = $forbidden) }" ] .
ex:S a sh:NodeShape ; sh:targetNode ex:a, ex:b ; ex:forbidden ex:secret .
ex:a ex:secret 1 . ex:b ex:public 2 .
)");
  ASSERT_EQ(r2.results.size(), 1u) << text(r2);
  const Result& x = r2.results[0];
  EXPECT_EQ(r2.terms[x.focus].value, "http://example.org/a");
  EXPECT_EQ(r2.terms[x.value].value, "1");
  EXPECT_EQ(x.path, nullptr);
  EXPECT_EQ(message(r2, x),
            "<http://example.org/a> uses <http://example.org/secret>, with value 1");
}

TEST(SparqlComponent, PropertySelectValidatorSubstitutesPath) {
  const std::string component = R"(
ex:Below a sh:ConstraintComponent ;
  sh:parameter [ sh:path ex:below ] ;
  sh:message "a value is not below {$below}" ;
  sh:propertyValidator [ a sh:SPARQLSelectValidator ;
    sh:select "SELECT $this ?value WHERE { $this $PATH ?value . FILTER(?value >= $below) }" ] ;
  sh:validator [ a sh:SPARQLAskValidator ; sh:ask "ASK { FILTER($value < $below) }" ] .
)";
  Report r = check_one(component + R"(
ex:S a sh:NodeShape ; sh:targetNode ex:a ;
  sh:property [ sh:path ( ex:p ex:q ) ; ex:below 10 ] .
ex:a ex:p ex:m . ex:m ex:q 5, 12 .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  const Result& x = r.results[0];
  EXPECT_EQ(r.terms[x.value].value, "12");
  ASSERT_NE(x.path, nullptr);
  EXPECT_EQ(x.path->kind, sparql::Path::Kind::Sequence);
  EXPECT_EQ(message(r, x), "a value is not below 10");  // the component's sh:message
  // On a node shape the same component uses its ASK validator.
  Report n = check_one(component + "ex:N a sh:NodeShape ; sh:targetNode 3, 30 ; ex:below 10 .\n");
  ASSERT_EQ(n.results.size(), 1u) << text(n);
  EXPECT_EQ(n.terms[n.results[0].value].value, "30");
}

TEST(SparqlComponent, OptionalParametersAreUnboundWhenAbsent) {
  const std::string component = R"(
ex:Pattern a sh:ConstraintComponent ;
  sh:parameter [ sh:path ex:regex ] , [ sh:path ex:regexFlags ; sh:optional true ] ;
  sh:validator [ a sh:SPARQLAskValidator ;
    sh:message "{$value} does not match {$regex}" ;
    sh:ask """ASK { FILTER(IF(bound($regexFlags), regex(str($value), $regex, $regexFlags),
                                regex(str($value), $regex))) }""" ] .
)";
  Report r = check_one(component + R"(
ex:Plain a sh:NodeShape ; sh:targetNode "abc", "ABC" ; ex:regex "^a" .
ex:Flags a sh:NodeShape ; sh:targetNode "abc", "ABC", "xyz" ; ex:regex "^a" ; ex:regexFlags "i" .
)");
  ASSERT_EQ(r.results.size(), 2u) << text(r);
  for (const Result& x : r.results) {
    const std::string shape(r.terms[x.shape].value);
    const std::string value(r.terms[x.value].value);
    EXPECT_TRUE((shape == "http://example.org/Plain" && value == "ABC") ||
                (shape == "http://example.org/Flags" && value == "xyz"))
        << shape << " " << value;
  }
}

TEST(SparqlComponent, EachValueOfAParameterIsAConstraint) {
  Report r = check_one(kAskComponent + R"(
ex:S a sh:NodeShape ; sh:targetNode "Hallo"@de ; ex:lang "de", "en" .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  EXPECT_EQ(message(r, r.results[0]), "Hallo is not in language en");
}

TEST(SparqlComponent, LabelTemplateIsTheDefaultMessage) {
  Report r = check_one(R"(
ex:C a sh:ConstraintComponent ;
  sh:parameter [ sh:path ex:notEqualTo ] ;
  sh:labelTemplate "Value must differ from {$notEqualTo}" ;
  sh:validator [ sh:ask "ASK { FILTER($value != $notEqualTo) }" ] .
ex:S a sh:NodeShape ; sh:targetNode 1, 2 ; ex:notEqualTo 2 .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  EXPECT_TRUE(r.results[0].messages.empty());
  EXPECT_EQ(r.results[0].default_message, "Value must differ from 2");
}

TEST(SparqlComponent, TheShapesMessageWhenTheComponentHasNone) {
  Report r = check_one(R"(
ex:C a sh:ConstraintComponent ;
  sh:parameter [ sh:path ex:notEqualTo ] ;
  sh:validator [ sh:ask "ASK { FILTER($value != $notEqualTo) }" ] .
ex:S a sh:NodeShape ; sh:targetNode 1, 2 ; ex:notEqualTo 2 ; sh:message "not two"@en .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  EXPECT_EQ(message(r, r.results[0]), "not two");
  EXPECT_EQ(r.terms[r.results[0].messages[0]].language, "en");
}

// W3C SHACL-SPARQL test sparql/component/validator-001: the component and
// its validator are typed with subclasses of sh:ConstraintComponent and
// sh:SPARQLAskValidator. mospec looked for rdf:type sh:ConstraintComponent
// only, so the component was never declared, its parameters on the shape
// meant nothing and "Hallo Welt" conformed (issue #32).
TEST(SparqlComponent, AComponentTypedWithASubclassIsDeclared) {
  Report r = check_one(R"(
ex:ConstraintComponent a rdfs:Class ; rdfs:subClassOf sh:ConstraintComponent .
ex:MyComponent rdfs:subClassOf ex:ConstraintComponent .
ex:SPARQLAskValidator rdfs:subClassOf sh:SPARQLAskValidator .
ex:TestConstraintComponent a ex:MyComponent ;
  sh:parameter ex:TestParameter1 , ex:TestParameter2 ;
  sh:validator [ a ex:SPARQLAskValidator ;
    sh:ask "ASK { FILTER (?value = CONCAT($test1, $test2)) }" ] .
ex:TestParameter1 a sh:Parameter ; sh:path ex:test1 ; sh:datatype xsd:string .
ex:TestParameter2 a sh:Parameter ; sh:path ex:test2 ; sh:datatype xsd:string .
ex:TestShape a sh:NodeShape ; ex:test1 "Hello " ; ex:test2 "World" ;
  sh:targetNode "Hallo Welt" , "Hello World" .
)");
  ASSERT_EQ(r.results.size(), 1u) << text(r);
  EXPECT_EQ(r.terms[r.results[0].focus].value, "Hallo Welt");
  EXPECT_EQ(r.terms[r.results[0].value].value, "Hallo Welt");
  EXPECT_EQ(r.terms[r.results[0].component_node].value,
            "http://example.org/TestConstraintComponent");
}

// W3C sparql/component/optional-001: a shape declares a component's
// constraint when it has values for all mandatory parameters; a value of an
// optional parameter alone declares nothing (it was refused, as if the
// parameter were mandatory).
TEST(SparqlComponent, OptionalParametersMayBeLeftOutAndAloneDeclareNothing) {
  Report r = check_one(R"(
ex:TestConstraintComponent a sh:ConstraintComponent ;
  sh:parameter [ sh:path ex:optionalParam ; sh:optional "true"^^xsd:boolean ] ;
  sh:parameter [ sh:path ex:requiredParam ] ;
  sh:validator [ a sh:SPARQLAskValidator ;
    sh:ask "ASK { FILTER ($value != $requiredParam && $value != COALESCE(?optionalParam, 'Three')) }" ] .
ex:IncompleteShape a sh:NodeShape ; ex:optionalParam "Some" ;
  sh:targetNode "One" , "Two" , "Three" .
ex:TestShape1 a sh:NodeShape ; ex:requiredParam "One" ;
  sh:targetNode "One" , "Two" , "Three" .
ex:TestShape2 a sh:NodeShape ; ex:requiredParam "One" ; ex:optionalParam "Two" ;
  sh:targetNode "One" , "Two" , "Three" .
)");
  std::vector<std::string> got;
  for (const Result& x : r.results)
    got.push_back(std::string(r.terms[x.shape].value.substr(19)) + " " +
                  std::string(r.terms[x.focus].value));
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, (std::vector<std::string>{"TestShape1 One", "TestShape1 Three", "TestShape2 One",
                                           "TestShape2 Two"}))
      << text(r);
}

// sh:prefixes on the validator (SHACL 5.2.1) and, as an extension, on the
// shape that uses the component; conflicting declarations are ill-formed.
TEST(SparqlComponent, PrefixesOfValidatorsAndShapes) {
  const std::string component = R"(
ex:decls sh:declare [ sh:prefix "ex" ; sh:namespace "http://example.org/"^^xsd:anyURI ] .
ex:other sh:declare [ sh:prefix "ex" ; sh:namespace "http://example.com/"^^xsd:anyURI ] .
ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:forbidden ] ;
  sh:validator [ sh:ask "ASK { FILTER NOT EXISTS { $value ex:tag $forbidden } }" ] .
ex:a ex:tag ex:bad .
)";
  Report r = check_one(component +
                       "ex:S a sh:NodeShape ; sh:prefixes ex:decls ; sh:targetNode ex:a ; "
                       "ex:forbidden ex:bad .\n");
  EXPECT_EQ(r.results.size(), 1u) << text(r);
  Error e = refused(component +
                    "ex:S a sh:NodeShape ; sh:prefixes ex:decls , ex:other ; sh:targetNode ex:a ; "
                    "ex:forbidden ex:bad .\n");
  EXPECT_EQ(e.code(), "shacl-ill-formed") << e.what();
  EXPECT_NE(std::string(e.what()).find("declared with two namespaces"), std::string::npos)
      << e.what();
}

TEST(SparqlComponent, ComponentsMospecWouldHaveToIgnoreAreErrors) {
  struct Case {
    std::string body, code, needle;
    uint32_t line;  // of the body, 0: not checked
  };
  const std::vector<Case> cases{
      // Only a node validator, used in a property shape (SHACL: ignored).
      {"ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:x ] ;\n"
       "  sh:nodeValidator [ sh:select \"SELECT $this WHERE { }\" ] .\n"
       "ex:S sh:targetNode ex:a ; sh:property [ sh:path ex:p ;\n"
       "  ex:x 1 ] .\n",
       "unsupported-shacl", "no validator for property shapes", 4},
      // A JavaScript validator.
      {"ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:x ] ;\n"
       "  sh:validator [ ex:jsFunction \"f\" ] .\n",
       "unsupported-shacl", "neither sh:ask nor sh:select", 2},
      // SELECT where ASK belongs.
      {"ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:x ] ;\n"
       "  sh:validator [ sh:select \"SELECT $this WHERE { }\" ] .\n",
       "shacl-ill-formed", "must be an ASK-based validator", 2},
      // Reserved and duplicate parameter names.
      {"ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:value ] ;\n"
       "  sh:validator [ sh:ask \"ASK {}\" ] .\n",
       "shacl-ill-formed", "may not be named \"value\"", 1},
      {"ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:x ] , [ sh:path <urn:x> ] ;\n"
       "  sh:validator [ sh:ask \"ASK {}\" ] .\n",
       "shacl-ill-formed", "two parameters are named \"x\"", 1},
      {"ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:x ; sh:optional true ] ;\n"
       "  sh:validator [ sh:ask \"ASK {}\" ] .\n",
       "shacl-ill-formed", "at least one sh:parameter that is not sh:optional", 1},
      // A parameter value that breaks the parameter's declaration.
      {kAskComponent + "ex:S sh:targetNode ex:a ;\n  ex:lang \"d\" .\n", "shacl-ill-formed",
       "does not conform to the parameter's declaration", 10},
      // A syntax error in the ASK query, and $shapesGraph.
      {"ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:x ] ;\n"
       "  sh:validator [ sh:ask \"ASK { FILTER( }\" ] .\n"
       "ex:S sh:targetNode ex:a ; ex:x 1 .\n",
       "shacl-ill-formed", "sh:ask of validator", 0},
      {"ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:x ] ;\n"
       "  sh:validator [ sh:ask \"ASK { FILTER(BOUND($shapesGraph)) }\" ] .\n"
       "ex:S sh:targetNode ex:a ; ex:x 1 .\n",
       "unsupported-shacl", "shapesGraph", 0},
  };
  for (const Case& c : cases) {
    Error e = refused(c.body);
    EXPECT_EQ(e.code(), c.code) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.needle), std::string::npos) << e.what();
    EXPECT_EQ(e.diagnostic().file, "shapes.ttl") << e.what();
    if (c.line != 0) {
      EXPECT_EQ(e.diagnostic().line, kPrefixLines + c.line) << e.what();
    }
  }
}

}  // namespace

namespace {

// Validators run under the same SPARQL limits as sh:sparql constraints; the
// error names the validator and the component and points at the constraint.
TEST(SparqlComponent, ValidatorsThatExceedTheSparqlLimitsAreLocatedErrors) {
  std::string data;
  for (int i = 0; i < 100; ++i)
    data += "ex:n" + std::to_string(i) + " ex:next ex:n" + std::to_string(i + 1) + " .\n";
  const std::string join = "?a ?p ?b . ?c ?q ?d . ?e ?r ?f";
  const std::vector<std::pair<std::string, std::string>> validators{
      // (ASK stops at the first solution: this one has none.)
      {"sh:validator", "sh:ask \"ASK { " + join + " FILTER(STR(?f) = 'none') }\""},
      {"sh:nodeValidator", "sh:select \"SELECT $this WHERE { " + join + " }\""},
  };
  for (const auto& [predicate, query] : validators) {
    SCOPED_TRACE(predicate);
    auto g = turtle(data + "ex:C a sh:ConstraintComponent ; sh:parameter [ sh:path ex:x ] ;\n  " +
                    predicate + " [ " + query + " ] .\n" +
                    "ex:S a sh:NodeShape ; sh:targetNode ex:n0 ;\n  ex:x 1 .\n");
    Shapes shapes = Shapes::compile(g->data, &g->files);
    ValidateOptions options;
    options.sparql_limits = sparql::Limits{0, 100000, 0};
    try {
      validate(shapes, g->data, options);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), "sparql-limit") << e.what();
      EXPECT_EQ(e.diagnostic().file, "shapes.ttl") << e.what();
      EXPECT_EQ(e.diagnostic().line, kPrefixLines + 100 + 4) << e.what();  // ex:x 1
      const std::string& message = e.diagnostic().message;
      EXPECT_EQ(message.substr(0, 12), "validator _:") << message;
      EXPECT_NE(message.find(" of constraint component <http://example.org/C> of shape "
                             "<http://example.org/S> on focus node <http://example.org/n0>"),
                std::string::npos)
          << message;
    }
  }
}

}  // namespace
