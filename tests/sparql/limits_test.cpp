// Bounded work: step, row and time limits end runaway evaluations with a
// "sparql-limit" error instead of running for minutes. The inputs are small
// and the limits set low, so nothing here depends on the machine's speed.
#include "sparql/limits.hpp"

#include "sparql/path.hpp"
#include "test_util.hpp"

namespace mospec::sparql::test {
namespace {

// `n` triples ex:s<i> ex:p ex:o<i>.
std::string triples(size_t n) {
  std::string out;
  for (size_t i = 0; i < n; ++i) {
    const std::string k = std::to_string(i);
    out.append("ex:s").append(k).append(" ex:p ex:o").append(k).append(" .\n");
  }
  return out;
}

// An RDF list of `n` members as the value of ex:head ex:list.
std::string list(size_t n) {
  std::string out = "ex:head ex:list (";
  for (size_t i = 0; i < n; ++i) out.append(" ").append(std::to_string(i));
  return out.append(" ) .\n");
}

// The message of the sparql-limit error `f` throws.
template <class F>
std::string limit_error(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "sparql-limit") << e.what();
    return e.diagnostic().message;
  }
  ADD_FAILURE() << "no sparql-limit error";
  return {};
}

constexpr const char* kJoinAll = "SELECT * { ?a ?p ?b . ?c ?q ?d . ?e ?r ?f }";

TEST(SparqlLimits, AThreeWayJoinOfEveryTripleStopsAtTheStepLimit) {
  Data d(triples(200));  // 8 million solutions
  d.eval().set_limits(Limits{0, 100000, 0});
  EXPECT_EQ(limit_error([&] { d.run(kJoinAll); }),
            "SPARQL evaluation stopped after 100000 steps (its step limit; a step is a matched "
            "triple, a node reached by a path or a solution passed on): the query does too much "
            "work on this data; make it more selective or raise the limit");
  // Within the limit the same evaluator answers, with its state reset.
  d.eval().set_limits(Limits{});
  EXPECT_EQ(d.run("SELECT ?o { ex:s7 ex:p ?o }"), Rows{"<http://example.org/o7>"});
}

TEST(SparqlLimits, ATimeBudgetEndsEvaluation) {
  Data d(triples(200));
  d.eval().set_limits(Limits{1e-9, 0, 0});  // spent by the first clock check
  const std::string message = limit_error([&] { d.run(kJoinAll); });
  EXPECT_EQ(message.substr(0, message.find(" s (")), "SPARQL evaluation stopped after 1e-09");
  EXPECT_NE(message.find("(its time budget) and "), std::string::npos) << message;
}

TEST(SparqlLimits, ResultRowsAreBounded) {
  Data d(triples(50));
  d.eval().set_limits(Limits{0, 0, 1000});
  EXPECT_EQ(limit_error([&] { d.run("SELECT * { ?a ?p ?b . ?c ?q ?d }"); }),
            "SPARQL evaluation stopped at 1001 result rows (its row limit is 1000): make the "
            "query more selective or raise the limit");
  EXPECT_EQ(d.run("SELECT * { ?a ?p ?b . ?c ?q ?d } LIMIT 1000").size(), 1000u);
}

TEST(SparqlLimits, ZeroOrMoreAfterZeroOrMoreOverALongListIsBounded) {
  Data d(list(3000));  // from every node, O(n) per start: 9 million steps
  d.eval().set_limits(Limits{0, 1000000, 0});
  const std::string message =
      limit_error([&] { d.run("SELECT ?x ?y { ?x rdf:rest*/rdf:rest* ?y }"); });
  EXPECT_EQ(message.substr(0, 48), "SPARQL evaluation stopped after 1000000 steps (i");
  // A bound start is cheap.
  EXPECT_EQ(d.run("SELECT ?y { ex:head ex:list/rdf:rest* ?y FILTER(?y = rdf:nil) }").size(), 1u);
}

TEST(SparqlLimits, NestedZeroOrMorePathsCountTheirWork) {
  // (p*)* from the head of a chain: each node reached starts a new walk.
  std::string chain;
  for (int i = 0; i < 3000; ++i)
    chain.append("ex:n")
        .append(std::to_string(i))
        .append(" ex:p ex:n")
        .append(std::to_string(i + 1))
        .append(" .\n");
  Data d(chain);
  const PathPtr star = Path::make(Path::Kind::ZeroOrMore,
                                  {Path::make(Path::Kind::ZeroOrMore, {Path::iri(d.iri("p"))})});
  std::vector<rdf::TermId> out;
  Budget small(Limits{0, 100000, 0});
  EXPECT_EQ(limit_error([&] {
              evaluate_path(d.data(), *star, d.iri("n0"), out, rdf::TermId::any(), &small);
            }).substr(0, 46),
            "SPARQL evaluation stopped after 100000 steps (");
  // Unlimited, the answer is the whole chain.
  Budget unlimited(Limits{0, 0, 0});
  evaluate_path(d.data(), *star, d.iri("n0"), out, rdf::TermId::any(), &unlimited);
  EXPECT_EQ(out.size(), 3001u);
  EXPECT_GT(unlimited.steps(), 3001u * 3001u / 2);
}

}  // namespace
}  // namespace mospec::sparql::test
