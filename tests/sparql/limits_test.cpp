// Bounded work: step, row and time limits end runaway evaluations with a
// "sparql-limit" error instead of running for minutes. The inputs are small
// and the limits set low, so nothing here depends on the machine's speed.
#include "sparql/limits.hpp"

#include "sparql/path.hpp"
#include "sparql/regex.hpp"
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
            "SPARQL evaluation stopped after 100000 steps (the command's step limit; a step is a "
            "matched triple, a node reached by a path, a solution passed on or 64 bytes a string "
            "function reads): the queries do too much work on this data; make them more "
            "selective or raise the limit");
  // Within the limit the same evaluator answers, with its state reset.
  d.eval().set_limits(Limits{});
  EXPECT_EQ(d.run("SELECT ?o { ex:s7 ex:p ?o }"), Rows{"<http://example.org/o7>"});
}

TEST(SparqlLimits, ATimeBudgetEndsEvaluation) {
  Data d(triples(200));
  d.eval().set_limits(Limits{1e-9, 0, 0});  // spent by the first clock check
  const std::string message = limit_error([&] { d.run(kJoinAll); });
  EXPECT_EQ(message.substr(0, message.find(" s (")), "SPARQL evaluation stopped after 1e-09");
  EXPECT_NE(message.find("(the command's time budget) and "), std::string::npos) << message;
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
  EXPECT_EQ(message.substr(0, 48), "SPARQL evaluation stopped after 1000000 steps (t");
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

// `n` subjects, each with one literal of `bytes` bytes ("aaa...a" then its
// index, so that no two are the same term).
std::string long_literals(size_t n, size_t bytes) {
  std::string out;
  const std::string body(bytes, 'a');
  for (size_t i = 0; i < n; ++i)
    out.append("ex:s")
        .append(std::to_string(i))
        .append(" ex:text \"")
        .append(body)
        .append(std::to_string(i) + "\" .\n");
  return out;
}

// A clock that reads the regex work charged to a budget: 1 ns per byte of
// text its REGEXes were given (Budget::regex_bytes()), times `scale`. Time
// then is exactly proportional to the regex work, whatever the Budget charged
// for it, and no test depends on the machine's speed. `budget` is set once
// the budget it clocks exists (the clock reads 0 until then).
struct RegexWorkClock {
  const Budget* budget = nullptr;
  double scale = 1;
  double seconds() const { return static_cast<double>(bytes()) * 1e-9 * scale; }
  uint64_t bytes() const { return budget != nullptr ? budget->regex_bytes() : 0; }
  Budget::Clock clock() const {
    return [this] { return seconds(); };
  }
};

TEST(SparqlLimits, OneBudgetIsSharedByEveryEvaluationOfACommand) {
  Data d(triples(100));
  Budget budget(Limits{0, 2000, 0});
  d.eval().set_budget(&budget);
  // Each evaluation scans 100 triples: within the limit alone, not 20 together.
  size_t evaluations = 0;
  const std::string message = limit_error([&] {
    for (; evaluations < 100; ++evaluations) d.run("SELECT ?s { ?s ex:p ?o }");
  });
  EXPECT_EQ(message.substr(0, 42), "SPARQL evaluation stopped after 2000 steps");
  EXPECT_GE(evaluations, 15u);
  EXPECT_LE(evaluations, 20u);
  // Without a shared budget each evaluation has its own.
  d.eval().set_budget(nullptr);
  d.eval().set_limits(Limits{0, 2000, 0});
  for (int i = 0; i < 100; ++i) EXPECT_EQ(d.run("SELECT ?s { ?s ex:p ?o }").size(), 100u);
}

TEST(SparqlLimits, RegexIsChargedByTheBytesItReads) {
  Data d(long_literals(1, 1 << 20));
  Budget budget(Limits{0, 0, 0});
  d.eval().set_budget(&budget);
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:text ?t FILTER(REGEX(?t, \"b$\")) }").size(), 0u);
  EXPECT_GE(budget.steps(), (uint64_t{1} << 20) / Budget::kBytesPerStep);
  EXPECT_EQ(budget.regex_bytes(), (uint64_t{1} << 20) + 1);
  // The count belongs to the budget, not to the thread: another evaluation
  // on this thread, with its own budget, neither sees nor adds to it.
  Data other(long_literals(1, 1000));
  Budget other_budget(Limits{0, 0, 0});
  other.eval().set_budget(&other_budget);
  EXPECT_EQ(other.run("SELECT ?s { ?s ex:text ?t FILTER(REGEX(?t, \"b$\")) }").size(), 0u);
  EXPECT_EQ(other_budget.regex_bytes(), 1001u);
  EXPECT_EQ(budget.regex_bytes(), (uint64_t{1} << 20) + 1);
  // And so are string functions.
  const uint64_t before = budget.steps();
  EXPECT_EQ(d.run("SELECT ?s { ?s ex:text ?t FILTER(CONTAINS(?t, \"b\")) }").size(), 0u);
  EXPECT_GE(budget.steps() - before, (uint64_t{1} << 20) / Budget::kBytesPerStep);
}

TEST(SparqlLimits, RegexesOverrunTheTimeBudgetByAtMostTenPercent) {
  // 200 texts of 64 KiB, a budget of 100 texts' worth of regex work (6.6 ms
  // at 1 ns per byte). Charged one step per REGEX, the clock was read once
  // per ~2000 of them (issue #32), so all 200 ran.
  constexpr size_t kBytes = 64 * 1024;
  Data d(long_literals(200, kBytes));
  RegexWorkClock work;
  const double budget_seconds = 100 * kBytes * 1e-9;
  Budget budget(Limits{budget_seconds, 0, 0}, work.clock());
  work.budget = &budget;
  d.eval().set_budget(&budget);
  const std::string message =
      limit_error([&] { d.run("SELECT ?s { ?s ex:text ?t FILTER(REGEX(?t, \"b$\")) }"); });
  EXPECT_NE(message.find("time budget"), std::string::npos) << message;
  EXPECT_GE(work.seconds(), budget_seconds * 0.9);
  EXPECT_LE(work.seconds(), budget_seconds * 1.1) << work.bytes() << " bytes searched";
}

TEST(SparqlLimits, ARegexThatWouldEndPastTheBudgetDoesNotStart) {
  // One REGEX over 4 MiB: at 1 ns per byte it takes 4.2 ms against a 2 ms
  // budget, so it must not start (afterwards would be 110 % over).
  Data d(long_literals(1, 4 << 20));
  RegexWorkClock work;
  Budget budget(Limits{0.002, 0, 0}, work.clock());
  work.budget = &budget;
  d.eval().set_budget(&budget);
  const std::string message =
      limit_error([&] { d.run("SELECT ?s { ?s ex:text ?t FILTER(REGEX(?t, \"b$\")) }"); });
  EXPECT_NE(message.find("the next REGEX (65537 steps, about"), std::string::npos) << message;
  EXPECT_EQ(work.bytes(), 0u);
  // The estimate learns the slowest rate it measured. Four texts at 8 ns per
  // byte (twice the default estimate) and a budget for 3.6 of them: after the
  // first, the fourth is known not to fit (at the default rate it would seem
  // to, and end 11 % over).
  Data e(long_literals(4, 4 << 20));
  RegexWorkClock slow{nullptr, 8};
  const double per_text = 8e-9 * (4 << 20);
  Budget learning(Limits{3.6 * per_text, 0, 0}, slow.clock());
  slow.budget = &learning;
  e.eval().set_budget(&learning);
  limit_error([&] { e.run("SELECT ?s { ?s ex:text ?t FILTER(REGEX(?t, \"b$\")) }"); });
  EXPECT_EQ(slow.bytes(), 3u * ((4u << 20) + 1));
  EXPECT_NEAR(learning.seconds_per_step(Budget::Bulk::Regex), 8e-9 * Budget::kBytesPerStep, 1e-10);
}

TEST(SparqlLimits, AStringFunctionThatWouldEndPastTheBudgetDoesNotStart) {
  // 1 ms of a 1 s budget left, CONTAINS over 4 MiB estimated at 8 ms: refused
  // before it starts (the clock then stands still, so only that check can stop it).
  Data d(long_literals(1, 4 << 20));
  Budget budget(Limits{1.0, 0, 0}, [reads = 0]() mutable { return reads++ == 0 ? 0.0 : 0.999; });
  d.eval().set_budget(&budget);
  const std::string message =
      limit_error([&] { d.run("SELECT ?s { ?s ex:text ?t FILTER(CONTAINS(?t, \"b\")) }"); });
  EXPECT_NE(message.find("the next string function (65537 steps, about"), std::string::npos)
      << message;
}

TEST(SparqlLimits, TheClockIsReadAtLeastEveryKCheckEverySteps) {
  Data d(triples(100));
  Budget budget(Limits{1e9, 0, 0}, [] { return 0.0; });
  d.eval().set_budget(&budget);
  // A million combinations, no solution.
  d.run("SELECT * { ?a ?p ?b . ?c ?q ?d . ?e ?r ?f FILTER(?f = ?a) }");
  EXPECT_GT(budget.steps(), 1000000u);
  EXPECT_GE(budget.clock_reads(), budget.steps() / Budget::kCheckEvery);
  EXPECT_LE(budget.clock_reads(), budget.steps() / Budget::kCheckEvery + 2);
}

}  // namespace
}  // namespace mospec::sparql::test
