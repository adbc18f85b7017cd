// Shapes graph compilation: what becomes a shape, targets, paths, and
// ill-formed shapes reported with the shape and file:line.
#include <gtest/gtest.h>

#include "test_util.hpp"

using namespace mospec;
using namespace mospec::shacl;
using mospec::shacl::test_util::kPrefixLines;
using mospec::shacl::test_util::turtle;

namespace {

Shapes compile(const test_util::Graph& g) {
  return Shapes::compile(g.data, &g.files);
}

// Compiles and returns the error (fails the test when there is none).
Error ill_formed(const std::string& body) {
  auto g = turtle(body);
  try {
    compile(*g);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << body;
  return Error(DiagnosticCode(), "");  // no error: no code
}

const Shape* find(const Shapes& shapes, const rdf::TermTable& t, std::string_view iri) {
  for (const Shape& s : shapes.shapes())
    if (t[s.node].is_iri() && t[s.node].value == iri) return &s;
  return nullptr;
}

TEST(Shapes, FindsShapesByTypeTargetsParametersAndReferences) {
  auto g = turtle(R"(
ex:A a sh:NodeShape .
ex:B sh:targetNode ex:x .
ex:C sh:class ex:K .
ex:D sh:node ex:E .
ex:F sh:and ( ex:G [ sh:datatype xsd:string ] ) .
ex:NotAShape ex:p ex:q .
)");
  Shapes shapes = compile(*g);
  const auto& t = g->data.terms();
  for (const char* name : {"A", "B", "C", "D", "E", "F", "G"})
    EXPECT_NE(find(shapes, t, std::string("http://example.org/") + name), nullptr) << name;
  EXPECT_EQ(find(shapes, t, "http://example.org/NotAShape"), nullptr);
  EXPECT_EQ(shapes.shapes().size(), 8u);  // plus the blank node in the sh:and list
}

TEST(Shapes, TargetsIncludingImplicitClassTargets) {
  auto g = turtle(R"(
ex:Person a rdfs:Class, sh:NodeShape ; sh:targetSubjectsOf ex:knows ; sh:targetObjectsOf ex:likes .
ex:S a sh:PropertyShape ; sh:path ex:p ; sh:targetClass ex:Thing ; sh:targetNode ex:n, "lit" .
)");
  Shapes shapes = compile(*g);
  const auto& t = g->data.terms();
  const Shape* person = find(shapes, t, "http://example.org/Person");
  ASSERT_NE(person, nullptr);
  ASSERT_EQ(person->target_classes.size(), 1u);
  EXPECT_EQ(person->target_classes[0], person->node);
  EXPECT_EQ(person->target_subjects_of.size(), 1u);
  EXPECT_EQ(person->target_objects_of.size(), 1u);
  EXPECT_FALSE(person->is_property);
  const Shape* s = find(shapes, t, "http://example.org/S");
  ASSERT_NE(s, nullptr);
  EXPECT_TRUE(s->is_property);
  EXPECT_EQ(s->target_nodes.size(), 2u);
  EXPECT_EQ(s->target_classes.size(), 1u);
}

TEST(Shapes, EveryPathForm) {
  auto g = turtle(R"(
ex:S a sh:PropertyShape ; sh:path ( ex:a [ sh:inversePath ex:b ]
    [ sh:alternativePath ( ex:c [ sh:zeroOrMorePath ex:d ] ) ]
    [ sh:oneOrMorePath ex:e ] [ sh:zeroOrOnePath ex:f ] ) .
)");
  Shapes shapes = compile(*g);
  const Shape* s = find(shapes, g->data.terms(), "http://example.org/S");
  ASSERT_NE(s, nullptr);
  ASSERT_TRUE(s->path);
  EXPECT_EQ(path_to_sparql(g->data.terms(), *s->path),
            "<http://example.org/a>/(^<http://example.org/b>)/(<http://example.org/c>|(<http://"
            "example.org/d>*))/(<http://example.org/e>+)/(<http://example.org/f>?)");
}

TEST(Shapes, NonIntegerMinCountNamesShapeAndLine) {
  Error e = ill_formed(R"(ex:S a sh:NodeShape ;
  sh:targetNode ex:a ;
  sh:property [ sh:path ex:p ;
    sh:minCount "one" ] .
)");
  EXPECT_EQ(e.code(), "shacl-ill-formed");
  EXPECT_EQ(e.diagnostic().file, "shapes.ttl");
  EXPECT_EQ(e.diagnostic().line, kPrefixLines + 4);
  EXPECT_NE(std::string(e.what()).find("sh:minCount"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("sh:path <http://example.org/p>"), std::string::npos)
      << e.what();
  EXPECT_NE(std::string(e.what()).find("\"one\""), std::string::npos) << e.what();
}

TEST(Shapes, IllFormedParameters) {
  struct Case {
    const char* body;
    const char* mention;
  };
  const Case cases[] = {
      {"ex:S sh:targetNode ex:a ; sh:in ex:notAList .", "sh:in"},
      {"ex:S sh:targetNode ex:a ; sh:in ( ex:a ex:b ) , ( ex:c ) .", "more than one value"},
      {"ex:S sh:path [ ex:foo ex:p ] ; sh:minCount 1 .", "path node"},
      {"ex:S sh:path ( ex:p ) ; sh:minCount 1 .", "at least two members"},
      {"ex:S sh:path \"p\" ; sh:minCount 1 .", "is not a path"},
      {"ex:S a sh:PropertyShape ; sh:path _:p . _:p sh:zeroOrMorePath _:p .", "refers to itself"},
      {"ex:S a sh:PropertyShape ; sh:path [ sh:inversePath ex:p ; sh:zeroOrOnePath ex:q ] .",
       "more than one path form"},
      {"ex:S a sh:PropertyShape ; sh:path [ sh:alternativePath ( ex:p ) ] .",
       "at least two members"},
      {"ex:S a sh:NodeShape ; sh:minCount 1 .", "only allowed in property shapes"},
      {"ex:S a sh:NodeShape ; sh:nodeKind ex:Thing .", "sh:nodeKind"},
      {"ex:S a sh:NodeShape ; sh:datatype xsd:string, xsd:integer .", "more than one value"},
      {"ex:S a sh:NodeShape ; sh:class \"C\" .", "must be an IRI"},
      {"ex:S a sh:NodeShape ; sh:pattern \"(\" .",
       "sh:pattern: invalid regular expression \"(\": missing ): ("},
      {"ex:S a sh:NodeShape ; sh:pattern \"(a)\\\\1\" .",
       "sh:pattern: invalid regular expression \"(a)\\1\": invalid escape sequence: \\1"},
      {"ex:S a sh:NodeShape ; sh:pattern \"a\" ; sh:flags \"g\" .",
       "sh:flags: invalid regular expression flag 'g' (allowed: s, m, i, x, q)"},
      {"ex:S a sh:NodeShape ; sh:maxLength -1 .", "non-negative"},
      {"ex:S a sh:NodeShape ; sh:closed \"yes\" .", "xsd:boolean"},
      {"ex:S a sh:NodeShape ; sh:property ex:T . ex:T sh:class ex:C .", "has no sh:path"},
      {"ex:S a sh:NodeShape ; sh:languageIn ( ex:en ) .", "must be strings"},
      {"ex:S a sh:NodeShape ; sh:node \"x\" .", "must name a shape"},
  };
  for (const Case& c : cases) {
    Error e = ill_formed(c.body);
    EXPECT_EQ(e.code(), "shacl-ill-formed") << c.body;
    EXPECT_NE(std::string(e.what()).find(c.mention), std::string::npos)
        << c.body << "\n  -> " << e.what();
    EXPECT_NE(std::string(e.what()).find("shapes.ttl:"), std::string::npos) << e.what();
  }
}

TEST(Shapes, UnusedIllFormedPathsAndInactiveParametersAreIgnored) {
  auto g = turtle(R"(
ex:S a sh:PropertyShape ; sh:path ex:p ; sh:targetNode ex:a ;
  sh:uniqueLang "1"^^xsd:boolean ;
  sh:qualifiedMinCount 1 .
_:p1 sh:inversePath _:p2 .
_:p2 sh:zeroOrMorePath ( _:p2 ) .
)");
  Shapes shapes = compile(*g);
  const Shape* s = find(shapes, g->data.terms(), "http://example.org/S");
  ASSERT_NE(s, nullptr);
  EXPECT_TRUE(s->constraints.empty());
}

TEST(Shapes, SeverityDeactivationAndMessages) {
  auto g = turtle(R"(
ex:S a sh:NodeShape ; sh:severity sh:Warning ; sh:message "m"@en, "n" ; sh:deactivated true .
ex:T a sh:NodeShape ; sh:severity ex:Custom .
)");
  Shapes shapes = compile(*g);
  const Shape* s = find(shapes, g->data.terms(), "http://example.org/S");
  const Shape* t = find(shapes, g->data.terms(), "http://example.org/T");
  ASSERT_TRUE(s && t);
  EXPECT_EQ(s->level, Level::Warning);
  EXPECT_TRUE(s->deactivated);
  EXPECT_EQ(s->messages.size(), 2u);
  EXPECT_EQ(t->level, Level::Other);
  EXPECT_EQ(g->data.terms()[t->severity].value, "http://example.org/Custom");
}

TEST(Shapes, ClosedShapesAllowThePropertyShapesPredicates) {
  auto g = turtle(R"(
ex:S a sh:NodeShape ; sh:closed true ; sh:ignoredProperties ( rdf:type ) ;
  sh:property [ sh:path ex:p ] , [ sh:path ( ex:q ex:r ) ] .
)");
  Shapes shapes = compile(*g);
  const Shape* s = find(shapes, g->data.terms(), "http://example.org/S");
  ASSERT_NE(s, nullptr);
  const Constraint* closed = nullptr;
  for (const Constraint& c : s->constraints)
    if (c.component == Component::Closed) closed = &c;
  ASSERT_NE(closed, nullptr);
  EXPECT_EQ(closed->terms.size(), 2u);  // rdf:type and ex:p; sequence paths do not count
}

}  // namespace
