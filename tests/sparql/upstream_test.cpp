// The authors' SHACL-SPARQL constraints (comp-rob2b metamodels) evaluated per
// focus node over the flattened app graphs, as the SHACL validator will do:
// parse once, pre-bind $this, collect the rows. Also a timing check that the
// evaluation scales linearly with the data (about 100k triples).
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rdf/nquads.hpp"
#include "test_util.hpp"

namespace mospec::sparql::test {
namespace {

namespace fs = std::filesystem;

const fs::path kShared = MOSPEC_SHARED_DIR;
const fs::path kMetamodels = kShared / "upstream/motion-spec-ral/comp-rob2b/metamodels";
constexpr std::string_view kSh = "http://www.w3.org/ns/shacl#";

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Constraint {
  std::string name;
  rdf::TermId shape;  // in the shapes dataset
  Query query;
};

class Upstream : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kMetamodels)) GTEST_SKIP() << "no upstream metamodels at " << kMetamodels;
    for (const auto& entry : fs::recursive_directory_iterator(kMetamodels))
      if (entry.path().extension() == ".ttl")
        rdf::read_turtle(read(entry.path()), "file://" + entry.path().string(), shapes_);
    auto& t = shapes_.terms();
    const rdf::TermId declare = t.find_iri(std::string(kSh) + "declare");
    const rdf::TermId prefix = t.find_iri(std::string(kSh) + "prefix");
    const rdf::TermId ns = t.find_iri(std::string(kSh) + "namespace");
    for (uint32_t i : shapes_.match(rdf::TermId::any(), declare, rdf::TermId::any())) {
      const rdf::TermId d = shapes_.quads()[i].object;
      auto p = shapes_.match(d, prefix, rdf::TermId::any());
      auto n = shapes_.match(d, ns, rdf::TermId::any());
      if (p.size() == 1 && n.size() == 1)
        prefixes_[std::string(t[shapes_.quads()[p[0]].object].value)] =
            std::string(t[shapes_.quads()[n[0]].object].value);
    }
    const rdf::TermId sparql = t.find_iri(std::string(kSh) + "sparql");
    const rdf::TermId select = t.find_iri(std::string(kSh) + "select");
    for (uint32_t i : shapes_.match(rdf::TermId::any(), sparql, rdf::TermId::any())) {
      const rdf::Quad& q = shapes_.quads()[i];
      for (uint32_t j : shapes_.match(q.object, select, rdf::TermId::any())) {
        const std::string text(t[shapes_.quads()[j].object].value);
        constraints_.push_back(
            Constraint{rdf::to_ntriples(t, q.object), q.subject, parse_query(text, prefixes_)});
      }
    }
  }

  // Focus nodes of a shape: instances of it (implicit class target) and of
  // every class shape that reaches it through sh:node, possibly inside
  // sh:and/sh:or/sh:xone lists. The shapes graph is queried with the engine.
  std::vector<rdf::TermId> focus_nodes(Evaluator& ev, rdf::TermId shape) {
    static const Query users = parse_query(
        "PREFIX sh: <http://www.w3.org/ns/shacl#> "
        "PREFIX rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> "
        "SELECT DISTINCT ?c { ?c (sh:node|((sh:and|sh:or|sh:xone)/rdf:rest*/rdf:first/sh:node))* "
        "$s }");
    static const Query targets = parse_query(
        "SELECT DISTINCT ?x { ?x a/<http://www.w3.org/2000/01/rdf-schema#subClassOf>* $cls }");
    Evaluator on_shapes(shapes_);
    ResultSet classes;
    on_shapes.select(users, std::vector<Binding>{{"s", shape}}, classes);
    std::vector<rdf::TermId> out;
    ResultSet rs;
    for (size_t c = 0; c < classes.size(); ++c) {
      auto [table, id] = on_shapes.locate(classes.at(c, 0));
      ev.select(targets, std::vector<Binding>{{"cls", ev.import(*table, id)}}, rs);
      for (size_t r = 0; r < rs.size(); ++r) out.push_back(rs.at(r, 0));
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  struct Outcome {
    size_t evaluations = 0, violations = 0;
    double seconds = 0;
  };
  Outcome validate(const rdf::Dataset& data) {
    Evaluator ev(data);
    std::vector<std::vector<rdf::TermId>> focus;
    for (const Constraint& c : constraints_) focus.push_back(focus_nodes(ev, c.shape));
    Outcome o;
    ResultSet rs;
    const auto start = std::chrono::steady_clock::now();
    for (size_t k = 0; k < constraints_.size(); ++k) {
      for (rdf::TermId node : focus[k]) {
        ev.select(constraints_[k].query, std::vector<Binding>{{"this", node}}, rs);
        ++o.evaluations;
        o.violations += rs.size();
      }
    }
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return o;
  }

  rdf::Dataset shapes_;
  PrefixMap prefixes_;
  std::vector<Constraint> constraints_;
};

TEST_F(Upstream, EveryConstraintParsesAndPassesOnTheAppGraphs) {
  EXPECT_EQ(constraints_.size(), 19u);
  for (const char* app : {"sc0a-right-arm", "sc0b-dual-arm", "sc1", "sc2"}) {
    rdf::Dataset data;
    rdf::read_nquads(read(kShared / "upstream/expected" / (std::string(app) + ".nt")), data);
    Outcome o = validate(data);
    // Four independent validators agree: no SPARQL-based violation in these apps.
    EXPECT_EQ(o.violations, 0u) << app;
    EXPECT_GT(o.evaluations, 0u) << app;
    std::printf("%-16s %6zu triples, %4zu evaluations, %.3f ms\n", app, data.size(), o.evaluations,
                o.seconds * 1e3);
  }
}

TEST_F(Upstream, BrokenModelsAreReported) {
  // Swap the direction cosines of one frame so that the determinant is -1 and
  // point a pose's as-seen-by away from its with-respect-to frame.
  std::string nt = read(kShared / "upstream/expected/sc1.nt");
  rdf::Dataset data;
  rdf::read_nquads(nt, data);
  const rdf::TermId cosx = data.terms().find_iri(
      "https://comp-rob2b.github.io/metamodels/geometry/coordinates#direction-cosine-x");
  const rdf::TermId cosy = data.terms().find_iri(
      "https://comp-rob2b.github.io/metamodels/geometry/coordinates#direction-cosine-y");
  ASSERT_FALSE(cosx.is_any());
  rdf::TermId victim = rdf::TermId::any();
  for (const rdf::Quad& q : data.quads())
    if (q.predicate == cosx && victim.is_any()) victim = q.subject;
  rdf::Dataset rebuilt;
  auto& t = rebuilt.terms();
  for (rdf::Quad q : data.quads()) {
    if (q.subject == victim && (q.predicate == cosx || q.predicate == cosy))
      q.predicate = q.predicate == cosx ? cosy : cosx;
    rebuilt.add({t.import(data.terms(), q.subject), t.import(data.terms(), q.predicate),
                 t.import(data.terms(), q.object)});
  }
  Outcome o = validate(rebuilt);
  EXPECT_EQ(o.violations, 1u);
}

TEST_F(Upstream, EvaluationScalesLinearly) {
  const std::string nt = read(kShared / "upstream/expected/sc1.nt");
  auto copies = [&](int n) {
    rdf::Dataset data;
    for (int i = 0; i < n; ++i) {
      std::string text = nt;
      const std::string from = "https://secorolab.github.io/models/";
      const std::string to = from + "copy" + std::to_string(i) + "/";
      for (size_t at = text.find(from); at != std::string::npos;
           at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
      rdf::read_nquads(text, data);
    }
    return data;
  };
  rdf::Dataset small = copies(1);
  rdf::Dataset large = copies(75);
  Outcome s = validate(small);
  Outcome l = validate(large);
  ASSERT_GT(s.evaluations, 0u);
  const double per_small = s.seconds / static_cast<double>(s.evaluations);
  const double per_large = l.seconds / static_cast<double>(l.evaluations);
  std::printf(
      "1x: %zu triples %.3f ms; 75x: %zu triples %.3f ms (%.2f us vs %.2f us per focus node)\n",
      small.size(), s.seconds * 1e3, large.size(), l.seconds * 1e3, per_small * 1e6,
      per_large * 1e6);
  EXPECT_EQ(l.evaluations, 75 * s.evaluations);
  // Linear: the cost per focus node must not grow with the data (generous
  // bound for noisy, shared machines).
  EXPECT_LT(per_large, 10 * per_small + 50e-6);
}

}  // namespace
}  // namespace mospec::sparql::test
