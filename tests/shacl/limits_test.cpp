// Bounded work in validation: sh:pattern runs in RE2 (linear time), and a
// SPARQL constraint or a path that exceeds its limits ends validation with a
// located "sparql-limit" error, never a crash and never "conforms".
#include <gtest/gtest.h>

#include "test_util.hpp"

using namespace mospec;
using namespace mospec::shacl;
using mospec::shacl::test_util::kPrefixLines;
using mospec::shacl::test_util::turtle;

namespace {

// The Error validating `body` (shapes and data in one graph) throws.
Error validation_error(const std::string& body, const sparql::Limits& limits) {
  auto g = turtle(body);
  Shapes shapes = Shapes::compile(g->data, &g->files);
  ValidateOptions options;
  options.sparql_limits = limits;
  try {
    Report r = validate(shapes, g->data, options);
    ADD_FAILURE() << "validated; conforms: " << r.conforms();
  } catch (const Error& e) {
    return e;
  }
  return Error(DiagnosticCode(), "");  // no error: no code
}

std::string chain(size_t n) {
  std::string out;
  for (size_t i = 0; i < n; ++i)
    out.append("ex:n")
        .append(std::to_string(i))
        .append(" ex:next ex:n")
        .append(std::to_string(i + 1))
        .append(" .\n");
  return out;
}

TEST(ValidateLimits, PatternsThatBacktrackedRunInLinearTime) {
  const std::string shapes =
      "ex:S a sh:NodeShape ; sh:targetSubjectsOf ex:v ;\n"
      "  sh:property [ sh:path ex:v ; sh:pattern \"^(a|b)*$\" ] ;\n"
      "  sh:property [ sh:path ex:w ; sh:pattern \"^(a|a)*$\" ] .\n";
  const std::string data =
      "ex:x ex:v \"" + std::string(20000, 'a') + "\" ; ex:w \"" + std::string(35, 'a') + "b\" .\n";
  Report r = test_util::check(shapes, data);
  ASSERT_EQ(r.results.size(), 1u) << to_text(r, nullptr);
  EXPECT_EQ(r.results[0].component, Component::Pattern);
}

TEST(ValidateLimits, ASparqlConstraintThatJoinsEveryTripleIsALocatedError) {
  const std::string body = chain(100) +
                           "ex:S a sh:NodeShape ; sh:targetNode ex:n0 ;\n"
                           "  sh:sparql [ sh:select \"\"\"\n"
                           "    SELECT $this WHERE { ?a ?p ?b . ?c ?q ?d . ?e ?r ?f }\"\"\" ] .\n";
  const Error e = validation_error(body, sparql::Limits{0, 100000, 0});
  EXPECT_EQ(e.code(), "sparql-limit");
  EXPECT_EQ(e.diagnostic().file, "shapes.ttl");
  EXPECT_EQ(e.diagnostic().line, kPrefixLines + 100 + 2);  // the sh:sparql line
  const std::string& message = e.diagnostic().message;
  EXPECT_EQ(message.substr(0, 20), "SPARQL constraint _:") << message;
  EXPECT_NE(message.find(" of shape <http://example.org/S> on focus node <http://example.org/n0>: "
                         "SPARQL evaluation stopped after 100000 steps ("),
            std::string::npos)
      << message;
}

TEST(ValidateLimits, ANestedZeroOrMorePathIsALocatedError) {
  const std::string body = chain(2000) +
                           "ex:S a sh:NodeShape ; sh:targetNode ex:n0 ;\n"
                           "  sh:property ex:P .\n"
                           "ex:P sh:path [ sh:zeroOrMorePath [ sh:zeroOrMorePath ex:next ] ] ;\n"
                           "  sh:minCount 1 .\n";
  const Error e = validation_error(body, sparql::Limits{0, 100000, 0});
  EXPECT_EQ(e.code(), "sparql-limit");
  EXPECT_EQ(e.diagnostic().file, "shapes.ttl");
  const std::string expected =
      "sh:path (<http://example.org/next>*)* of shape <http://example.org/P> from focus node "
      "<http://example.org/n0>: SPARQL evaluation stopped after 100000 steps (";
  EXPECT_EQ(e.diagnostic().message.substr(0, expected.size()), expected);
  EXPECT_EQ(e.diagnostic().line, kPrefixLines + 2000 + 3);  // the property shape
}

TEST(ValidateLimits, OneBudgetCoversEveryFocusNodeAndShape) {
  // 2000 focus nodes, each SPARQL evaluation scanning the 2000 ex:next
  // triples: cheap alone (2000 steps), 4 million steps together. Each
  // evaluation had a budget of its own, so validation finished (issue #32).
  const std::string body = chain(2000) +
                           "ex:S a sh:NodeShape ; sh:targetSubjectsOf ex:next ;\n"
                           "  sh:sparql [ sh:select \"\"\"\n"
                           "    SELECT $this WHERE { ?a <http://example.org/next> ?b FILTER(?a = "
                           "<urn:none>) }\"\"\" ] .\n"
                           "ex:P a sh:PropertyShape ; sh:targetSubjectsOf ex:next ;\n"
                           "  sh:path ( ex:next ex:next ) ; sh:maxCount 1 .\n";
  const Error e = validation_error(body, sparql::Limits{0, 1000000, 0});
  EXPECT_EQ(e.code(), "sparql-limit");
  EXPECT_NE(e.diagnostic().message.find("SPARQL evaluation stopped after 1000000 steps (the "
                                        "command's step limit"),
            std::string::npos)
      << e.diagnostic().message;
  // Paths and queries draw on the caller's budget when it has one.
  auto g = turtle(body);
  Shapes shapes = Shapes::compile(g->data, &g->files);
  sparql::Budget budget(sparql::Limits{0, 0, 0});
  ValidateOptions options;
  options.sparql_budget = &budget;
  EXPECT_TRUE(validate(shapes, g->data, options).conforms());
  EXPECT_GT(budget.steps(), 2000u * 2000u);
}

}  // namespace
