// Property paths: the evaluator shared with SHACL, and paths inside queries.
#include "sparql/path.hpp"

#include "test_util.hpp"

namespace mospec::sparql::test {
namespace {

class Paths : public ::testing::Test {
 protected:
  // a -p-> b -p-> c -p-> a (a cycle), c -q-> d, d -p-> d (a self loop), e isolated.
  Paths()
      : d_(R"(ex:a ex:p ex:b . ex:b ex:p ex:c . ex:c ex:p ex:a . ex:c ex:q ex:d . ex:d ex:p ex:d .
              ex:e ex:r "lit" .)") {}

  PathPtr p(const char* local) { return Path::iri(d_.iri(local)); }
  std::vector<std::string> from(const Path& path, const char* start, bool inverse = false) {
    std::vector<rdf::TermId> out;
    if (inverse) {
      evaluate_path_inverse(d_.data(), path, d_.iri(start), out);
    } else {
      evaluate_path(d_.data(), path, d_.iri(start), out);
    }
    std::vector<std::string> names;
    for (rdf::TermId t : out) {
      std::string iri(d_.data().terms()[t].value);
      names.push_back(iri.substr(iri.rfind('/') + 1));
    }
    return names;
  }
  using Names = std::vector<std::string>;
  Data d_;
};

TEST_F(Paths, PredicateAndInverse) {
  EXPECT_EQ(from(*p("p"), "a"), Names{"b"});
  EXPECT_EQ(from(*p("p"), "a", true), Names{"c"});
  EXPECT_EQ(from(*Path::make(Path::Kind::Inverse, {p("p")}), "a"), Names{"c"});
  EXPECT_EQ(from(*Path::make(Path::Kind::Inverse, {p("p")}), "a", true), Names{"b"});
}

TEST_F(Paths, SequenceAndAlternative) {
  auto seq = Path::make(Path::Kind::Sequence, {p("p"), p("p"), p("q")});
  EXPECT_EQ(from(*seq, "a"), Names{"d"});
  EXPECT_EQ(from(*seq, "d", true), Names{"a"});
  auto alt = Path::make(Path::Kind::Alternative, {p("q"), p("p")});
  EXPECT_EQ(from(*alt, "c"), (Names{"d", "a"}));
  EXPECT_EQ(from(*alt, "d", true), (Names{"c", "d"}));
}

TEST_F(Paths, ArbitraryLengthTerminatesOnCyclesAndIncludesStart) {
  auto star = Path::make(Path::Kind::ZeroOrMore, {p("p")});
  EXPECT_EQ(from(*star, "a"), (Names{"a", "b", "c"}));
  auto plus = Path::make(Path::Kind::OneOrMore, {p("p")});
  EXPECT_EQ(from(*plus, "a"), (Names{"b", "c", "a"}));  // a is reached again by the cycle
  EXPECT_EQ(from(*plus, "d"), Names{"d"});              // self loop
  EXPECT_EQ(from(*star, "e"), Names{"e"});              // zero length only
  EXPECT_EQ(from(*plus, "e"), Names{});
  auto opt = Path::make(Path::Kind::ZeroOrOne, {p("p")});
  EXPECT_EQ(from(*opt, "a"), (Names{"a", "b"}));
  auto any =
      Path::make(Path::Kind::ZeroOrMore, {Path::make(Path::Kind::Alternative, {p("p"), p("q")})});
  EXPECT_EQ(from(*any, "a"), (Names{"a", "b", "c", "d"}));
  EXPECT_EQ(from(*any, "d", true), (Names{"d", "c", "b", "a"}));
  auto seq_star =
      Path::make(Path::Kind::OneOrMore, {Path::make(Path::Kind::Sequence, {p("p"), p("p")})});
  EXPECT_EQ(from(*seq_star, "a"), (Names{"c", "b", "a"}));
}

TEST_F(Paths, NegatedPropertySets) {
  auto neg = std::make_shared<Path>();
  neg->kind = Path::Kind::NegatedSet;
  neg->negated = {d_.iri("p")};
  EXPECT_EQ(from(*neg, "c"), Names{"d"});
  neg->negated_inverse = {d_.iri("q")};
  // forward over !p from c: d; backward over !^q from c: b -p-> c is not q: b.
  EXPECT_EQ(from(*neg, "c"), (Names{"b", "d"}));
  auto only_inverse = std::make_shared<Path>();
  only_inverse->kind = Path::Kind::NegatedSet;
  only_inverse->negated_inverse = {d_.iri("q")};
  EXPECT_EQ(from(*only_inverse, "d"), Names{"d"});  // d -p-> d, followed backwards
}

// One PathWorkspace serves calls over different paths and datasets in turn
// (its visited sets are sized and reset per call, nested paths take their own):
// each call gives what a call with buffers of its own gives.
TEST_F(Paths, AWorkspaceIsReusedAcrossPathsAndDatasets) {
  std::string chain;
  for (int i = 0; i < 50; ++i) {
    chain += "ex:n" + std::to_string(i) + " ex:p ex:n" + std::to_string(i + 1) + " . ";
    if (i % 7 == 0)
      chain += "ex:n" + std::to_string(i) + " ex:q ex:n" + std::to_string(i / 2) + " . ";
  }
  Data big(chain);
  PathWorkspace workspace;
  size_t compared = 0;
  auto compare = [&](Data& d, const char* start) {
    const PathPtr p = Path::iri(d.iri("p")), q = Path::iri(d.iri("q"));
    const PathPtr star = Path::make(Path::Kind::ZeroOrMore, {p});
    const std::vector<PathPtr> paths = {
        star,
        Path::make(Path::Kind::Sequence,
                   {star, Path::make(Path::Kind::Alternative,
                                     {q, Path::make(Path::Kind::OneOrMore, {q})})}),
        Path::make(Path::Kind::OneOrMore, {Path::make(Path::Kind::Sequence, {q, star})}),
        Path::make(Path::Kind::Inverse, {star}),
    };
    for (const PathPtr& path : paths) {
      for (bool inverse : {false, true}) {
        std::vector<rdf::TermId> own, shared;
        (inverse ? evaluate_path_inverse : evaluate_path)(d.data(), *path, d.iri(start), own,
                                                          rdf::TermId::any(), nullptr, nullptr);
        (inverse ? evaluate_path_inverse : evaluate_path)(d.data(), *path, d.iri(start), shared,
                                                          rdf::TermId::any(), nullptr, &workspace);
        EXPECT_EQ(shared, own) << start << (inverse ? " inverse" : "");
        ++compared;
      }
    }
  };
  for (int round = 0; round < 2; ++round) {
    compare(big, "n0");
    compare(d_, "a");
    compare(big, "n49");
    compare(d_, "d");
  }
  EXPECT_EQ(compared, 64u);
  std::vector<rdf::TermId> out;
  evaluate_path(big.data(), *Path::make(Path::Kind::ZeroOrMore, {Path::iri(big.iri("p"))}),
                big.iri("n0"), out, rdf::TermId::any(), nullptr, &workspace);
  EXPECT_EQ(out.size(), 51u);
}

TEST_F(Paths, InQueries) {
  EXPECT_EQ(d_.sorted("SELECT ?x { ex:a ex:p* ?x }"),
            (Rows{"<http://example.org/a>", "<http://example.org/b>", "<http://example.org/c>"}));
  EXPECT_EQ(d_.sorted("SELECT ?x { ?x ex:p+ ex:a }"),
            (Rows{"<http://example.org/a>", "<http://example.org/b>", "<http://example.org/c>"}));
  EXPECT_EQ(d_.run("SELECT ?x { ex:a ex:p/ex:p/ex:q ?x }"), (Rows{"<http://example.org/d>"}));
  EXPECT_EQ(d_.run("SELECT ?x { ex:d ^ex:q/^ex:p ?x }"), (Rows{"<http://example.org/b>"}));
  EXPECT_EQ(d_.run("SELECT ?x { ex:d ^(ex:p/ex:q) ?x }"), (Rows{"<http://example.org/b>"}));
  EXPECT_EQ(d_.sorted("SELECT ?x { ex:c (ex:q|ex:p) ?x }"),
            (Rows{"<http://example.org/a>", "<http://example.org/d>"}));
  EXPECT_EQ(d_.run("SELECT ?x { ex:c !ex:p ?x }"), (Rows{"<http://example.org/d>"}));
  EXPECT_EQ(d_.run("SELECT ?x { ex:e !(ex:p|ex:q) ?x }"), (Rows{R"("lit")"}));
  EXPECT_EQ(d_.run("SELECT ?x { ?x ex:p ?x }"), (Rows{"<http://example.org/d>"}));
  EXPECT_EQ(d_.sorted("SELECT ?x { ?x ex:p+ ?x }"),
            (Rows{"<http://example.org/a>", "<http://example.org/b>", "<http://example.org/c>",
                  "<http://example.org/d>"}));
  // Both ends unbound: zero-length matches every node of the graph.
  EXPECT_EQ(d_.run("SELECT ?x ?y { ?x ex:q? ?y }").size(), 6u + 1u);  // 6 nodes, 1 q edge
  // Sequences keep duplicates (translation to a join), arbitrary paths do not.
  Data dup("ex:s ex:p ex:m1 , ex:m2 . ex:m1 ex:q ex:o . ex:m2 ex:q ex:o .");
  EXPECT_EQ(dup.run("SELECT ?o { ex:s ex:p/ex:q ?o }").size(), 2u);
  EXPECT_EQ(dup.run("SELECT ?o { ex:s (ex:p/ex:q)+ ?o }").size(), 1u);
}

}  // namespace
}  // namespace mospec::sparql::test
