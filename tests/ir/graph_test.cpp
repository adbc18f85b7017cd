// ir::Graph reads a model's quads in place as their flattened union: every
// answer must equal the one read from an explicit Dataset::flattened_union()
// copy (what lowering read before the reader existed), on a generated model
// whose files restate each other's triples with and without locations.
#include "ir/graph.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "app/app.hpp"
#include "description/chain_rdf.hpp"
#include "rdf/xsd.hpp"

namespace mospec::ir {
namespace {

using rdf::Quad;
using rdf::TermId;

const std::string kEx = "https://example.org/";
const std::string kType = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type";
const std::string kFirst = "http://www.w3.org/1999/02/22-rdf-syntax-ns#first";
const std::string kRest = "http://www.w3.org/1999/02/22-rdf-syntax-ns#rest";
const std::string kNil = "http://www.w3.org/1999/02/22-rdf-syntax-ns#nil";
const std::string kDouble = "http://www.w3.org/2001/XMLSchema#double";

// Three "files" (graphs). Subjects s0..s29 each get a type, objects spread over
// the files (some triples stated twice: first without a location, then with
// one), a number, and s0 an RDF list.
rdf::Dataset model() {
  rdf::Dataset d;
  rdf::TermTable& t = d.terms();
  const TermId type = t.iri(kType), p = t.iri(kEx + "p"), q = t.iri(kEx + "q");
  const TermId dbl = t.iri(kDouble);
  const TermId files[3] = {t.iri(kEx + "file-c"), t.iri(kEx + "file-a"), t.iri(kEx + "file-b")};
  uint32_t line = 1;
  auto at = [&](uint32_t file) { return SourceLoc{file, line++, 1}; };
  for (int i = 0; i < 30; ++i) {
    const TermId s = t.iri(kEx + "s" + std::to_string(i));
    const TermId g = files[i % 3];
    // Objects named so that id order and lexical order disagree.
    for (int k : {7, 2, 9, 2}) {
      const TermId o = t.iri(kEx + "o" + std::to_string((k * 13 + i) % 10));
      d.add(Quad{s, p, o, g}, i % 4 == 0 ? SourceLoc{} : at(1 + i % 3));
      d.add(Quad{s, p, o, files[(i + 1) % 3]}, at(2));  // restated in another file
    }
    d.add(Quad{s, type, t.iri(kEx + (i % 2 ? "Odd" : "Even")), g},
          i % 5 == 0 ? SourceLoc{} : at(3));
    d.add(Quad{s, q, t.literal(std::to_string(i) + ".5", dbl), g}, at(1));
  }
  // s0's list (1.5 "x" o3) in file-a.
  const TermId s0 = t.iri(kEx + "s0"), l = t.iri(kEx + "list");
  const TermId first = t.iri(kFirst), rest = t.iri(kRest), nil = t.iri(kNil);
  const TermId cells[3] = {t.blank("c1"), t.blank("c2"), t.blank("c3")};
  d.add(Quad{s0, l, cells[0], files[1]}, at(2));
  const TermId items[3] = {t.literal("1.5", dbl), t.literal("x"), t.iri(kEx + "o3")};
  for (int k = 0; k < 3; ++k) {
    d.add(Quad{cells[k], first, items[k], files[1]}, at(2));
    d.add(Quad{cells[k], rest, k < 2 ? cells[k + 1] : nil, files[1]}, at(2));
  }
  return d;
}

std::vector<std::string> names(const rdf::TermTable& t, const std::vector<TermId>& ids) {
  std::vector<std::string> out;
  for (TermId id : ids) out.emplace_back(t[id].value);
  return out;
}

// What lowering computed on its flattened copy: objects sorted by lexical form.
std::vector<std::string> reference_objects(const rdf::Dataset& flat, TermId s, TermId p) {
  std::vector<std::string> out;
  for (uint32_t i : flat.match(s, p, TermId::any()))
    out.emplace_back(flat.terms()[flat.quads()[i].object].value);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

SourceLoc reference_where(const rdf::Dataset& flat, TermId s) {
  for (uint32_t i : flat.match(s, TermId::any(), TermId::any()))
    if (flat.location(i).known()) return flat.location(i);
  return {};
}

TEST(IrGraph, AnswersAsTheFlattenedUnion) {
  const rdf::Dataset d = model();
  const rdf::Dataset flat = d.flattened_union();
  const Graph g(d);
  const rdf::TermTable& ft = flat.terms();
  for (int i = 0; i < 30; ++i) {
    const std::string s = kEx + "s" + std::to_string(i);
    SCOPED_TRACE(s);
    EXPECT_EQ(names(d.terms(), g.objects(g.term(s), g.term(kEx + "p"))),
              reference_objects(flat, ft.find_iri(s), ft.find_iri(kEx + "p")));
    EXPECT_EQ(g.where(g.term(s)), reference_where(flat, ft.find_iri(s)));
    EXPECT_TRUE(g.defined(g.term(s)));
    EXPECT_EQ(g.has_type(g.term(s), g.term(kEx + "Odd")), i % 2 == 1);
    EXPECT_EQ(g.number(g.term(s), g.term(kEx + "q")), i + 0.5);
  }
  std::vector<std::string> odd;
  for (int i = 1; i < 30; i += 2) odd.push_back(kEx + "s" + std::to_string(i));
  std::sort(odd.begin(), odd.end());
  EXPECT_EQ(names(d.terms(), g.instances(g.term(kEx + "Odd"))), odd);
  EXPECT_FALSE(g.defined(g.term(kEx + "o3")));
  EXPECT_TRUE(g.instances(g.term(kEx + "Missing")).empty());
}

// single_object() and read() (lowering's one-pass reads) answer as objects(),
// has_type() and defined() do: a triple restated in another file is one value,
// two distinct objects are "several".
TEST(IrGraph, OnePassReadsAnswerAsObjects) {
  rdf::Dataset d = model();
  const TermId lone = d.terms().iri(kEx + "lone"), p = d.terms().iri(kEx + "p");
  const TermId q = d.terms().iri(kEx + "q");
  d.add(Quad{d.terms().iri(kEx + "s0"), lone, d.terms().iri(kEx + "o1"), TermId::default_graph()},
        {});
  const Graph g(d);
  const TermId even = g.term(kEx + "Even"), odd = g.term(kEx + "Odd");
  const TermId missing = g.term(kEx + "Missing");  // any(): never stated
  const TermId predicates[4] = {p, q, lone, missing};
  const TermId types[3] = {odd, even, missing};
  for (int i = 0; i < 31; ++i) {
    const TermId s = g.term(kEx + "s" + std::to_string(i));  // s30: not in the model
    SCOPED_TRACE(i);
    Graph::Value values[4];
    const Graph::Reading r = g.read(s, predicates, values, types);
    EXPECT_EQ(r.defined, g.defined(s));
    if (s.is_any()) {
      EXPECT_EQ(r.types, 0U);  // has_type(any(), t) asks for any instance; read() says nothing
    } else {
      EXPECT_EQ(r.types, (g.has_type(s, odd) ? 1U : 0U) | (g.has_type(s, even) ? 2U : 0U));
    }
    for (int k = 0; k < 4; ++k) {
      const std::vector<TermId> all = g.objects(s, predicates[k]);
      bool several = true;
      const TermId one = g.single_object(s, predicates[k], several);
      EXPECT_EQ(several, all.size() > 1) << k;
      EXPECT_EQ(values[k].several, all.size() > 1) << k;
      if (all.size() == 1) {
        EXPECT_EQ(one, all[0]) << k;
        EXPECT_EQ(values[k].first, all[0]) << k;
      }
      if (all.empty()) {
        EXPECT_TRUE(one.is_any()) << k;
        EXPECT_TRUE(values[k].first.is_any()) << k;
      }
    }
  }
  // s0's `lone` is one value, and each `q` one number; every `p` has several.
  bool several = true;
  EXPECT_EQ(g.single_object(g.term(kEx + "s0"), lone, several), g.term(kEx + "o1"));
  EXPECT_FALSE(several);
  g.single_object(g.term(kEx + "s3"), p, several);
  EXPECT_TRUE(several);
}

TEST(IrGraph, WhereOfATripleSkipsRestatements) {
  const rdf::Dataset d = model();
  const Graph g(d);
  // s0's first statement of (s0 p o) has no location; its restatement in
  // another file has one, but the flattened union keeps the first: so the
  // triple's location falls back to where(s0).
  const TermId s0 = g.term(kEx + "s0"), p = g.term(kEx + "p");
  const TermId o = g.objects(s0, p).front();
  EXPECT_EQ(g.where(s0, p, o), g.where(s0));
  // s1's first statement is located.
  const TermId s1 = g.term(kEx + "s1");
  const TermId o1 = g.object(s1, p).value();
  const uint32_t first = d.match(s1, p, o1).front();
  EXPECT_EQ(g.where(s1, p, o1), d.location(first));
}

TEST(IrGraph, ListsAndNumbers) {
  const rdf::Dataset d = model();
  const Graph g(d);
  const auto head = g.object(g.term(kEx + "s0"), g.term(kEx + "list"));
  ASSERT_TRUE(head.has_value());
  const std::vector<TermId> items = g.list(*head);
  EXPECT_EQ(names(d.terms(), items), (std::vector<std::string>{"1.5", "x", kEx + "o3"}));
  EXPECT_EQ(g.number(items[0]), 1.5);
  EXPECT_EQ(g.number(items[1]), std::nullopt);  // "x" is no number
  EXPECT_EQ(g.number(items[2]), std::nullopt);  // an IRI
  EXPECT_EQ(rdf::xsd::number("1.0E-3", "http://www.w3.org/2001/XMLSchema#decimal"), 1.0e-3);
  EXPECT_EQ(rdf::xsd::number("1e", kDouble), std::nullopt);
}

TEST(IrGraph, GraphsDescribingCopiesOnlyTheSubjectsFiles) {
  const rdf::Dataset d = model();
  const Graph g(d);
  // s2 is stated in file-b (its own) and, by restatement, in file-c.
  const rdf::Dataset copy = g.graphs_describing(g.term(kEx + "s2"));
  size_t n = 0;
  for (uint32_t i = 0; i < d.size(); ++i) {
    const std::string graph(d.terms()[d.quads()[i].graph].value);
    if (graph == kEx + "file-b" || graph == kEx + "file-c") ++n;
  }
  EXPECT_GT(copy.size(), 0u);
  EXPECT_LE(copy.size(), n);
  for (const Quad& q : copy.quads()) EXPECT_EQ(q.graph, TermId::default_graph());
  const TermId s2 = copy.terms().find_iri(kEx + "s2");
  EXPECT_EQ(copy.count(s2, TermId::any(), TermId::any()), 5u);  // 3 objects, type, number
  EXPECT_TRUE(copy.terms().find_iri(kEx + "list").is_any());    // file-a's only
  EXPECT_TRUE(g.graphs_describing(g.term(kEx + "absent")).size() == 0);
}

// Lowering reads a robot's chain from its description's graphs in place
// (description::describe_chain over Graph::graphs_of) instead of from their
// copy (graphs_describing): the same chain and frames, bit for bit, also when
// another graph restates part of the description (a triple counts once) and
// when a further graph poses a frame relative to the chain's last link (not
// read: it states nothing about the chain).
TEST(IrGraph, ChainReadInPlaceEqualsTheCopy) {
  const std::filesystem::path source = MOSPEC_SOURCE_DIR;
  app::LoadOptions options;
  options.root = source.string();
  const app::LoadedModel model = app::load({(source / "models" / "sc1.json").string()}, options);
  rdf::Dataset d;
  d.merge(model.dataset());
  rdf::TermTable& t = d.terms();
  const std::string base = "https://mospec.example/robots/kinova-gen3/";
  const std::string chain = base + "chain";
  const TermId chain_id = t.find_iri(chain);
  ASSERT_FALSE(chain_id.is_any());
  // Restate the chain's joints and one joint's statements in a graph of their own.
  const TermId restated = t.iri(kEx + "restated"), stray = t.iri(kEx + "stray");
  std::vector<Quad> extra;
  for (const Quad& q : d.quads()) {
    const std::string_view s = t[q.subject].value;
    if (q.subject == chain_id || s == base + "joint-Actuator1")
      extra.push_back({q.subject, q.predicate, q.object, restated});
  }
  ASSERT_GT(extra.size(), 2u);
  for (const Quad& q : extra) d.add(q, SourceLoc{1, 1, 1});
  // Poses of both attachment frames of a joint, in a graph that does not
  // mention the chain: read, they would make the joint ambiguous (an error).
  const std::string geom_rel =
      "https://comp-rob2b.github.io/metamodels/geometry/spatial-relations#";
  int strays = 0;
  for (const Quad& q : extra) {
    if (!t[q.predicate].value.ends_with("between-attachments")) continue;
    const TermId pose = t.iri(kEx + "stray-pose-" + std::to_string(strays++));
    d.add({pose, t.iri(kType), t.iri(geom_rel + "Pose"), stray});
    d.add({pose, t.iri(geom_rel + "of"), q.object, stray});
  }
  ASSERT_EQ(strays, 2);
  const Graph g(d);
  const std::vector<TermId> graphs = g.graphs_of(g.term(chain));
  ASSERT_EQ(graphs.size(), 2u);
  const description::ChainDescription copied =
      description::describe_chain(g.graphs_describing(g.term(chain)), chain);
  const description::ChainDescription in_place = description::describe_chain(d, graphs, chain);
  const runtime::Chain& a = copied.chain;
  const runtime::Chain& b = in_place.chain;
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 0);
  for (int i = 0; i < a.size(); ++i) {
    const runtime::Segment& x = a.segment(i);
    const runtime::Segment& y = b.segment(i);
    EXPECT_EQ(x.joint, y.joint);
    EXPECT_EQ(x.link, y.link);
    EXPECT_EQ(x.X_PJ.R, y.X_PJ.R);
    EXPECT_EQ(x.X_PJ.p, y.X_PJ.p);
    EXPECT_EQ(x.axis_J, y.axis_J);
    EXPECT_EQ(x.inertia.mass, y.inertia.mass);
    EXPECT_EQ(x.inertia.I_Scm_S, y.inertia.I_Scm_S);
    EXPECT_EQ(x.inertia.p_SoScm_S, y.inertia.p_SoScm_S);
    EXPECT_EQ(x.folded_links, y.folded_links);
  }
  const auto same = [](const description::FrameEntities& x, const description::FrameEntities& y) {
    return x.frame == y.frame && x.origin == y.origin && x.body == y.body;
  };
  EXPECT_TRUE(same(copied.frames.root, in_place.frames.root));
  ASSERT_EQ(copied.frames.segments.size(), in_place.frames.segments.size());
  for (size_t i = 0; i < copied.frames.segments.size(); ++i)
    EXPECT_TRUE(same(copied.frames.segments[i], in_place.frames.segments[i])) << i;
}

}  // namespace
}  // namespace mospec::ir
