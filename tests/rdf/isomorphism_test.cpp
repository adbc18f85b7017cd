#include "rdf/isomorphism.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <string>

#include "rdf/nquads.hpp"
#include "test_util.hpp"

namespace mospec::rdf {
namespace {

using testing::numbered;

Dataset nq(std::string_view text) {
  Dataset d;
  read_nquads(text, d);
  return d;
}

// A directed cycle of `n` blank nodes, labels starting at `first`.
std::string cycle(int n, int first) {
  std::string out;
  for (int i = 0; i < n; ++i) {
    out += numbered("_:n", first + i);
    out += numbered(" <http://ex.org/next> _:n", first + (i + 1) % n);
    out += " .\n";
  }
  return out;
}

TEST(Isomorphic, GroundDatasets) {
  const std::string text =
      "<http://ex.org/s> <http://ex.org/p> \"1\" .\n"
      "<http://ex.org/s> <http://ex.org/p> \"x\"@en <http://ex.org/g> .\n";
  EXPECT_TRUE(isomorphic(nq(text), nq(text)));
  EXPECT_FALSE(isomorphic(nq(text), nq("<http://ex.org/s> <http://ex.org/p> \"1\" .\n"
                                       "<http://ex.org/s> <http://ex.org/p> \"x\"@EN "
                                       "<http://ex.org/g> .\n")));
  EXPECT_FALSE(isomorphic(nq(text), nq("<http://ex.org/s> <http://ex.org/p> \"1\" .\n"
                                       "<http://ex.org/s> <http://ex.org/p> \"x\"@en .\n")));
  EXPECT_FALSE(isomorphic(
      nq(text), nq("<http://ex.org/s> <http://ex.org/p> "
                   "\"1\"^^<http://www.w3.org/2001/XMLSchema#integer> .\n"
                   "<http://ex.org/s> <http://ex.org/p> \"x\"@en <http://ex.org/g> .\n")));
  EXPECT_FALSE(isomorphic(nq(text), nq("<http://ex.org/s> <http://ex.org/p> \"1\" .\n")));
  EXPECT_TRUE(isomorphic(nq(""), nq("# nothing\n")));
}

TEST(Isomorphic, BlankNodesAreMatchedByStructure) {
  Dataset a =
      nq("_:a <http://ex.org/p> _:b .\n"
         "_:b <http://ex.org/q> \"v\" .\n"
         "_:a <http://ex.org/r> _:a _:g .\n");
  Dataset b =
      nq("_:x <http://ex.org/r> _:x _:h .\n"
         "_:y <http://ex.org/q> \"v\" .\n"
         "_:x <http://ex.org/p> _:y .\n");
  EXPECT_TRUE(isomorphic(a, b));
  EXPECT_TRUE(isomorphic(b, a));
  EXPECT_EQ(describe_difference(a, b), "");
  // Swapping which node carries the self loop breaks it.
  Dataset c =
      nq("_:x <http://ex.org/p> _:y .\n"
         "_:y <http://ex.org/q> \"v\" .\n"
         "_:y <http://ex.org/r> _:y _:h .\n");
  EXPECT_FALSE(isomorphic(a, c));
}

TEST(Isomorphic, BlankNodeIsNotAnIri) {
  EXPECT_FALSE(isomorphic(nq("_:a <http://ex.org/p> \"v\" .\n"),
                          nq("<http://ex.org/a> <http://ex.org/p> \"v\" .\n")));
}

// Colour refinement alone cannot tell these apart: every node has one
// incoming and one outgoing edge of the same predicate.
TEST(Isomorphic, SymmetricCyclesNeedBacktracking) {
  Dataset six = nq(cycle(6, 0));
  Dataset two_threes = nq(cycle(3, 0) + cycle(3, 10));
  Dataset three_twos = nq(cycle(2, 0) + cycle(2, 10) + cycle(2, 20));
  EXPECT_FALSE(isomorphic(six, two_threes));
  EXPECT_FALSE(isomorphic(two_threes, six));
  EXPECT_FALSE(isomorphic(six, three_twos));
  EXPECT_FALSE(isomorphic(two_threes, three_twos));
  EXPECT_TRUE(isomorphic(six, nq(cycle(6, 40))));
  EXPECT_TRUE(isomorphic(two_threes, nq(cycle(3, 7) + cycle(3, 100))));
  EXPECT_NE(describe_difference(six, two_threes).find("no blank-node bijection"),
            std::string::npos);
}

TEST(Isomorphic, IndistinguishablePairsWithOneDifference) {
  // Two blank nodes with identical neighbourhoods, once each with a different
  // label on an otherwise symmetric structure.
  const std::string common =
      "_:a <http://ex.org/p> _:c .\n"
      "_:b <http://ex.org/p> _:c .\n"
      "_:c <http://ex.org/p> _:a .\n"
      "_:c <http://ex.org/p> _:b .\n";
  EXPECT_TRUE(isomorphic(nq(common + "_:a <http://ex.org/v> \"1\" .\n"),
                         nq(common + "_:b <http://ex.org/v> \"1\" .\n")));
  EXPECT_FALSE(isomorphic(nq(common + "_:a <http://ex.org/v> \"1\" .\n"),
                          nq(common + "_:c <http://ex.org/v> \"1\" .\n")));
}

TEST(Isomorphic, BlankGraphNames) {
  EXPECT_TRUE(isomorphic(nq("_:s <http://ex.org/p> \"o\" _:g1 .\n_:s <http://ex.org/p> \"o\" .\n"),
                         nq("_:t <http://ex.org/p> \"o\" .\n_:t <http://ex.org/p> \"o\" _:h .\n")));
  EXPECT_FALSE(isomorphic(nq("_:s <http://ex.org/p> \"o\" _:g1 .\n"),
                          nq("_:s <http://ex.org/p> \"o\" _:s .\n")));
}

// About 2000 quads: a long RDF list plus a tree of blank nodes, re-read with
// other labels and another quad order.
std::string big_document(int n, std::mt19937& rng, bool shuffle, int label_offset) {
  std::vector<std::string> lines;
  auto label = [&](int i) { return numbered("_:x", i * 7 + label_offset); };
  const std::string first = " <http://www.w3.org/1999/02/22-rdf-syntax-ns#first> ";
  const std::string rest = " <http://www.w3.org/1999/02/22-rdf-syntax-ns#rest> ";
  for (int i = 0; i < n; ++i) {
    lines.push_back(label(i) + first + numbered("\"", i % 10) + "\" .\n");
    lines.push_back(label(i) + rest +
                    (i + 1 < n ? label(i + 1)
                               : std::string("<http://www.w3.org/1999/02/22-rdf-syntax-ns#nil>")) +
                    " .\n");
    if (i > 0)
      lines.push_back(label(n + i) + " <http://ex.org/child> " + label(n + (i - 1) / 2) + " .\n");
  }
  if (shuffle) std::shuffle(lines.begin(), lines.end(), rng);
  std::string out;
  for (const std::string& line : lines) out += line;
  return out;
}

TEST(Isomorphic, TwoThousandQuadsQuickly) {
  std::mt19937 rng(5);
  Dataset a = nq(big_document(700, rng, false, 0));
  Dataset b = nq(big_document(700, rng, true, 3));
  ASSERT_GT(a.size(), 2000u);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(isomorphic(a, b));
  // One literal changed deep inside the list.
  std::string text = big_document(700, rng, true, 1);
  const std::string needle = "\"3\" .";
  text.replace(text.find(needle), needle.size(), "\"33\" .");
  EXPECT_FALSE(isomorphic(a, nq(text)));
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_LT(std::chrono::duration_cast<std::chrono::milliseconds>(elapsed).count(), 5000);
}

TEST(Isomorphic, ManyIdenticalComponents) {
  std::string a, b;
  for (int i = 0; i < 300; ++i) {
    a += cycle(2, 2 * i);
    b += cycle(2, 5000 + 2 * (299 - i));
  }
  EXPECT_TRUE(isomorphic(nq(a), nq(b)));
}

TEST(DescribeDifference, ListsQuadsWithoutCounterpart) {
  Dataset a =
      nq("_:b <http://ex.org/p> \"1\" .\n"
         "<http://ex.org/s> <http://ex.org/p> \"same\" .\n");
  Dataset b =
      nq("_:b <http://ex.org/p> \"2\" .\n"
         "<http://ex.org/s> <http://ex.org/p> \"same\" .\n");
  EXPECT_EQ(describe_difference(a, b),
            "first has 2 quads, second has 2\n"
            "only in first:  _:* <http://ex.org/p> \"1\" .\n"
            "only in second: _:* <http://ex.org/p> \"2\" .\n");
  EXPECT_EQ(describe_difference(a, b, 1),
            "first has 2 quads, second has 2\n"
            "only in first:  _:* <http://ex.org/p> \"1\" .\n"
            "...\n");
}

}  // namespace
}  // namespace mospec::rdf
