#include "rdf/dataset.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "test_util.hpp"

namespace mospec::rdf {
namespace {

using testing::numbered;

// Term pools sized so that subjects, predicates, objects and graphs have very
// different selectivities (the index must pick the right posting list).
struct Pools {
  std::vector<TermId> s, p, o, g;
};

Pools make_pools(TermTable& t) {
  Pools pools;
  for (int i = 0; i < 300; ++i) pools.s.push_back(t.iri(numbered("http://ex.org/s", i)));
  for (int i = 0; i < 7; ++i) pools.p.push_back(t.iri(numbered("http://ex.org/p", i)));
  for (int i = 0; i < 40; ++i) pools.o.push_back(t.literal(std::to_string(i)));
  for (int i = 0; i < 10; ++i) pools.o.push_back(t.blank(numbered("o", i)));
  pools.g = {TermId::default_graph(), t.iri("http://ex.org/g1"), t.blank("g2")};
  return pools;
}

void add_random(Dataset& d, const Pools& pools, std::mt19937& rng, size_t n) {
  auto pick = [&](const std::vector<TermId>& v) { return v[rng() % v.size()]; };
  for (size_t i = 0; i < n; ++i)
    d.add(Quad{pick(pools.s), pick(pools.p), pick(pools.o), pick(pools.g)},
          SourceLoc{1, static_cast<uint32_t>(i + 1), 1});
}

std::vector<uint32_t> brute_force(const Dataset& d, TermId s, TermId p, TermId o, TermId g) {
  std::vector<uint32_t> out;
  for (uint32_t i = 0; i < d.size(); ++i) {
    const Quad& q = d.quads()[i];
    if ((s.is_any() || q.subject == s) && (p.is_any() || q.predicate == p) &&
        (o.is_any() || q.object == o) && (g.is_any() || q.graph == g))
      out.push_back(i);
  }
  return out;
}

// Every combination of bound positions, with patterns taken from existing quads
// (non-empty results) and from random terms (often empty).
void check_all_patterns(const Dataset& d, const Pools& pools, std::mt19937& rng) {
  auto pick = [&](const std::vector<TermId>& v) { return v[rng() % v.size()]; };
  for (unsigned mask = 0; mask < 16; ++mask) {
    for (int trial = 0; trial < 20; ++trial) {
      Quad src = trial % 2 == 0 ? d.quads()[rng() % d.size()]
                                : Quad{pick(pools.s), pick(pools.p), pick(pools.o), pick(pools.g)};
      TermId s = mask & 1 ? src.subject : TermId::any();
      TermId p = mask & 2 ? src.predicate : TermId::any();
      TermId o = mask & 4 ? src.object : TermId::any();
      TermId g = mask & 8 ? src.graph : TermId::any();
      const auto expected = brute_force(d, s, p, o, g);
      ASSERT_EQ(d.match(s, p, o, g), expected) << "mask " << mask << " trial " << trial;
      ASSERT_EQ(d.count(s, p, o, g), expected.size());
      std::vector<uint32_t> visited;
      d.for_each(s, p, o, g, [&](const Quad& q, uint32_t i) {
        EXPECT_EQ(q, d.quads()[i]);
        visited.push_back(i);
        return true;
      });
      ASSERT_EQ(visited, expected);
    }
  }
}

TEST(Dataset, AddDeduplicatesAndKeepsFirstLocation) {
  Dataset d;
  TermTable& t = d.terms();
  Quad q{t.iri("http://ex.org/s"), t.iri("http://ex.org/p"), t.literal("o")};
  EXPECT_TRUE(d.add(q, SourceLoc{1, 3, 4}));
  EXPECT_FALSE(d.add(q, SourceLoc{2, 9, 9}));
  EXPECT_EQ(d.size(), 1u);
  EXPECT_EQ(d.location(0), (SourceLoc{1, 3, 4}));
  EXPECT_TRUE(d.contains(q));
  Quad in_graph = q;
  in_graph.graph = t.iri("http://ex.org/g");
  EXPECT_FALSE(d.contains(in_graph));
  EXPECT_TRUE(d.add(in_graph));
  EXPECT_EQ(d.size(), 2u);
  EXPECT_EQ(d.find(in_graph), 1u);
}

TEST(Dataset, RejectsIdsOfOtherTables) {
  Dataset d;
  TermId p = d.terms().iri("http://ex.org/p");
  try {
    d.add(Quad{p, p, TermId::any()});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid-term");
    EXPECT_EQ(e.diagnostic().message,
              "Dataset::add: object id 4294967295 is not a term of this dataset (5 terms)");
  }
  EXPECT_EQ(d.size(), 0u);
  EXPECT_TRUE(d.match(TermId::any(), TermId::any(), TermId::any()).empty());
}

// erase() keeps the other quads in order with their locations, and every
// index answers as if they had been the only ones added.
TEST(Dataset, EraseKeepsTheRestInOrderAndIndexed) {
  Dataset d;
  Pools pools = make_pools(d.terms());
  std::mt19937 rng(5);
  add_random(d, pools, rng, 3000);
  std::vector<Quad> kept;
  std::vector<SourceLoc> kept_at;
  std::vector<uint32_t> gone;
  for (uint32_t i = 0; i < d.size(); ++i) {
    if (i % 3 == 1) {
      gone.push_back(i);
      gone.push_back(i);  // duplicates are allowed
    } else {
      kept.push_back(d.quads()[i]);
      kept_at.push_back(d.location(i));
    }
  }
  d.erase(gone);
  ASSERT_EQ(d.size(), kept.size());
  for (uint32_t i = 0; i < d.size(); ++i) {
    EXPECT_EQ(d.quads()[i], kept[i]);
    EXPECT_EQ(d.location(i), kept_at[i]);
    EXPECT_EQ(d.find(kept[i]), i);
  }
  check_all_patterns(d, pools, rng);
  // An erased quad can be added again (it is gone from the deduplication set).
  const Quad back{pools.s[0], pools.p[0], pools.o[0], pools.g[0]};
  d.erase(d.match(back.subject, back.predicate, back.object, back.graph));
  EXPECT_FALSE(d.contains(back));
  EXPECT_TRUE(d.add(back));
  check_all_patterns(d, pools, rng);
}

TEST(Dataset, EveryPatternMatchesBruteForceSmall) {
  Dataset d;
  Pools pools = make_pools(d.terms());
  std::mt19937 rng(7);
  add_random(d, pools, rng, 200);  // stays in the chained tail
  check_all_patterns(d, pools, rng);
}

TEST(Dataset, EveryPatternMatchesBruteForceAcrossCompaction) {
  Dataset d;
  Pools pools = make_pools(d.terms());
  std::mt19937 rng(11);
  add_random(d, pools, rng, 5000);  // compacted several times, plus a tail
  check_all_patterns(d, pools, rng);
  // Terms interned after the last compaction must be found in the tail.
  TermId late = d.terms().iri("http://ex.org/late");
  d.add(Quad{late, pools.p[0], late});
  pools.s.push_back(late);
  check_all_patterns(d, pools, rng);
  EXPECT_EQ(d.match(late, TermId::any(), TermId::any()).size(), 1u);
  d.compact();
  check_all_patterns(d, pools, rng);
}

// Without automatic compaction the whole dataset is one chained tail (a bulk
// loader's state until it compacts); it answers every pattern, before and
// after compact(), and keeps doing so once automatic compaction is back.
TEST(Dataset, EveryPatternMatchesBruteForceWithoutAutoCompaction) {
  Dataset d;
  d.set_auto_compact(false);
  Pools pools = make_pools(d.terms());
  std::mt19937 rng(13);
  add_random(d, pools, rng, 3000);
  check_all_patterns(d, pools, rng);
  d.compact();
  check_all_patterns(d, pools, rng);
  d.set_auto_compact(true);
  add_random(d, pools, rng, 3000);
  check_all_patterns(d, pools, rng);
}

// Quads added while automatic compaction is off are not indexed; lookups must
// still see them after it is turned back on, and the next add() must index
// them (chained behind earlier compacted quads) without losing any.
TEST(Dataset, QuadsAddedWithoutIndexingAreFoundAndIndexedLater) {
  Dataset d;
  Pools pools = make_pools(d.terms());
  std::mt19937 rng(17);
  add_random(d, pools, rng, 2000);  // compacted, plus a chained tail
  d.set_auto_compact(false);
  add_random(d, pools, rng, 100);  // not indexed
  check_all_patterns(d, pools, rng);
  d.set_auto_compact(true);
  check_all_patterns(d, pools, rng);
  add_random(d, pools, rng, 1);  // indexes the 100 pending quads first
  check_all_patterns(d, pools, rng);
  d.reserve(d.size() + 1000);
  add_random(d, pools, rng, 1000);
  check_all_patterns(d, pools, rng);
}

TEST(Dataset, UnknownTermsMatchNothing) {
  Dataset d;
  TermTable& t = d.terms();
  d.add(Quad{t.iri("http://ex.org/s"), t.iri("http://ex.org/p"), t.literal("o")});
  EXPECT_TRUE(d.match(TermId{12345}, TermId::any(), TermId::any()).empty());
  TermId unused = t.iri("http://ex.org/unused");
  EXPECT_TRUE(d.match(TermId::any(), unused, TermId::any()).empty());
  EXPECT_EQ(d.match(TermId::any(), TermId::any(), TermId::any()).size(), 1u);
  EXPECT_EQ(d.match(TermId::any(), TermId::any(), TermId::any(), TermId::default_graph()).size(),
            1u);
}

TEST(Dataset, ForEachStopsWhenAsked) {
  Dataset d;
  TermTable& t = d.terms();
  TermId p = t.iri("http://ex.org/p");
  for (int i = 0; i < 10; ++i) d.add(Quad{t.blank(numbered("s", i)), p, t.literal("v")});
  int seen = 0;
  d.for_each(TermId::any(), p, TermId::any(), TermId::any(),
             [&](const Quad&, uint32_t) { return ++seen < 3; });
  EXPECT_EQ(seen, 3);
  EXPECT_EQ(d.count(TermId::any(), p, TermId::any(), TermId::any(), 4), 4u);
}

TEST(Dataset, FlattenedUnionDropsGraphsAndDuplicates) {
  Dataset d;
  TermTable& t = d.terms();
  TermId s = t.iri("http://ex.org/s"), p = t.iri("http://ex.org/p"), o = t.literal("o");
  d.add(Quad{s, p, o, t.iri("http://ex.org/g1")}, SourceLoc{1, 1, 1});
  d.add(Quad{s, p, o, t.blank("g2")}, SourceLoc{1, 2, 1});
  d.add(Quad{s, p, o}, SourceLoc{1, 3, 1});
  d.add(Quad{s, p, t.literal("o2"), t.blank("g2")}, SourceLoc{1, 4, 1});
  Dataset flat = d.flattened_union();
  ASSERT_EQ(flat.size(), 2u);
  for (const Quad& q : flat.quads()) EXPECT_EQ(q.graph, TermId::default_graph());
  EXPECT_EQ(flat.location(0), (SourceLoc{1, 1, 1}));
  EXPECT_EQ(flat.location(1), (SourceLoc{1, 4, 1}));
  EXPECT_EQ(flat.terms()[flat.quads()[1].object].value, "o2");
}

TEST(Dataset, MergeReinternsAndKeepsBlankLabels) {
  Dataset a, b;
  a.add(Quad{a.terms().blank("x"), a.terms().iri("http://ex.org/p"), a.terms().literal("1")},
        SourceLoc{1, 1, 1});
  // b's table has different ids for the same terms.
  b.terms().iri("http://ex.org/unrelated");
  b.add(Quad{b.terms().blank("x"), b.terms().iri("http://ex.org/p"), b.terms().literal("2"),
             b.terms().iri("http://ex.org/g")},
        SourceLoc{2, 5, 7});
  b.add(Quad{b.terms().blank("y"), b.terms().iri("http://ex.org/p"), b.terms().literal("1")},
        SourceLoc{2, 6, 1});
  a.merge(b);
  ASSERT_EQ(a.size(), 3u);
  TermId x = a.terms().find_blank("x");
  EXPECT_EQ(a.match(x, TermId::any(), TermId::any()).size(), 2u);
  EXPECT_EQ(a.location(1), (SourceLoc{2, 5, 7}));
  EXPECT_EQ(a.terms()[a.quads()[1].graph].value, "http://ex.org/g");
  a.merge(a);  // merging with itself changes nothing
  EXPECT_EQ(a.size(), 3u);
}

TEST(Dataset, MoveKeepsIndexesWorking) {
  Dataset d;
  Pools pools = make_pools(d.terms());
  std::mt19937 rng(3);
  add_random(d, pools, rng, 1500);
  Dataset moved = std::move(d);
  check_all_patterns(moved, pools, rng);
}

// A guard against accidental blow-ups of the per-quad footprint; the bound is
// generous (the design is about 60 bytes per quad plus terms).
TEST(Dataset, MemoryPerQuadIsBounded) {
  Dataset d;
  TermTable& t = d.terms();
  std::vector<TermId> preds;
  for (int i = 0; i < 20; ++i) preds.push_back(t.iri(numbered("http://ex.org/p", i)));
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    TermId s = t.blank(numbered("s", i / 5));
    d.add(Quad{s, preds[i % 20], t.literal(std::to_string(i % 1000))});
  }
  d.compact();
  const double per_quad = static_cast<double>(d.memory_bytes()) / n;
  EXPECT_LT(per_quad, 150.0) << d.memory_bytes() << " bytes";
}

}  // namespace
}  // namespace mospec::rdf
