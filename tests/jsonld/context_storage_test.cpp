// The containers context processing keeps its state in (context_processing.hpp):
// the term map of layers, overlays and deltas, and the shared base-IRI string.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>

#include "jsonld/context_processing.hpp"

namespace mospec::jsonld {
namespace {

using detail::SharedString;
using detail::TermMap;

// term_name(i), written so that GCC 12 does not warn (-Wrestrict,
// a false positive of operator+ on a literal and a temporary).
std::string term_name(int i) {
  std::string s = "t";
  s += std::to_string(i);
  return s;
}

TermPtr def(std::string iri) {
  auto d = std::make_shared<TermDefinition>();
  d->iri = std::move(iri);
  return d;
}

// The map against std::map as a reference, through growth, lookups by text and
// by pre-hashed key, and emplace that never overwrites.
TEST(TermMap, AgreesWithAnOrderedMapThroughGrowth) {
  TermMap map;
  std::map<std::string, std::string> expected;
  for (int i = 0; i < 300; ++i) {
    const std::string term = term_name(i * 7919 % 1000);
    const auto [it, fresh] = map.emplace(term, def("iri:" + term_name(i)));
    const bool expected_fresh = expected.emplace(term, "iri:" + term_name(i)).second;
    ASSERT_EQ(fresh, expected_fresh) << term;
    EXPECT_EQ(it->first, term);
  }
  ASSERT_EQ(map.size(), expected.size());
  for (const auto& [term, iri] : expected) {
    auto it = map.find(term);
    ASSERT_NE(it, map.end()) << term;
    EXPECT_EQ(*it->second->iri, iri) << "emplace kept the first definition";
    const detail::HashedKey key{term, detail::StringHash{}(term)};
    EXPECT_EQ(map.find(key), it);
  }
  EXPECT_EQ(map.find("absent"), map.end());
  EXPECT_EQ(map.find(""), map.end());
}

TEST(TermMap, IteratesInTheOrderTermsWereAdded) {
  TermMap map;
  for (const char* t : {"zeta", "alpha", "mu", "beta"}) map.emplace(t, def(t));
  std::string order;
  for (const auto& [k, v] : map) order += k + " ";
  EXPECT_EQ(order, "zeta alpha mu beta ");
}

// Builder::freeze erases while it iterates: every entry is still visited once,
// and the ones left are all found.
TEST(TermMap, EraseWhileIteratingVisitsEveryEntryOnce) {
  TermMap map;
  for (int i = 0; i < 40; ++i) map.emplace(term_name(i), i % 3 == 0 ? nullptr : def("x"));
  std::map<std::string, int> visits;
  for (auto it = map.begin(); it != map.end();) {
    ++visits[it->first];
    it = it->second ? std::next(it) : map.erase(it);
  }
  EXPECT_EQ(visits.size(), 40u);
  for (const auto& [term, n] : visits) EXPECT_EQ(n, 1) << term;
  EXPECT_EQ(map.size(), 26u);
  for (int i = 0; i < 40; ++i) {
    const std::string term = term_name(i);
    EXPECT_EQ(map.find(term) != map.end(), i % 3 != 0) << term;
  }
}

TEST(TermMap, EraseIfKeepsTheRestFindable) {
  TermMap map;
  for (int i = 0; i < 20; ++i) map.emplace(term_name(i), i < 10 ? nullptr : def("x"));
  EXPECT_EQ(erase_if(map, [](const auto& kv) { return !kv.second; }), 10u);
  EXPECT_EQ(map.size(), 10u);
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(map.find(term_name(i)) != map.end(), i >= 10);
  }
  EXPECT_EQ(erase_if(map, [](const auto&) { return true; }), 10u);
  EXPECT_TRUE(map.empty());
  EXPECT_EQ(map.find("t15"), map.end());
  EXPECT_TRUE(map.emplace("again", def("y")).second);  // usable after emptying
  EXPECT_NE(map.find("again"), map.end());
}

// Few entries are found by a scan, more through a table: across that line in
// both directions every entry stays findable.
TEST(TermMap, ShrinkingBelowTheTableAndGrowingPastItAgain) {
  TermMap map;
  for (int i = 0; i < 12; ++i) map.emplace(term_name(i), def("x"));
  EXPECT_EQ(erase_if(map, [](const auto& kv) { return kv.first.size() > 2; }), 2u);  // t10, t11
  for (auto it = map.begin(); it != map.end();) {
    it = it->first < "t5" ? map.erase(it) : std::next(it);
  }
  ASSERT_EQ(map.size(), 5u);  // t5 .. t9
  for (int i = 12; i < 30; ++i) map.emplace(term_name(i), def("y"));
  for (int i = 0; i < 30; ++i) {
    const bool present = (i >= 5 && i <= 9) || i >= 12;
    EXPECT_EQ(map.find(term_name(i)) != map.end(), present) << term_name(i);
  }
  EXPECT_FALSE(map.emplace(term_name(7), def("z")).second);
}

TEST(SharedString, CopiesShareOneStringAndCompareByContent) {
  SharedString a("https://example.org/base/");
  SharedString b = a;
  EXPECT_EQ(&a.str(), &b.str());
  EXPECT_EQ(a, SharedString("https://example.org/base/"));  // another string, same text
  EXPECT_NE(a, SharedString("https://example.org/other/"));
  SharedString empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.str(), "");
  EXPECT_EQ(empty, SharedString(""));
  b = "https://example.org/changed/";
  EXPECT_EQ(a.str(), "https://example.org/base/");  // a copy is never written through
  b.clear();
  EXPECT_TRUE(b.empty());
}

}  // namespace
}  // namespace mospec::jsonld
