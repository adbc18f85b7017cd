// Reads real documents from ../shared: the W3C expectations (N-Quads), the
// upstream flattened graphs (N-Triples) and SHACL's own Turtle files. Skips
// when ../shared is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "rdf/isomorphism.hpp"
#include "rdf/nquads.hpp"
#include "rdf/turtle.hpp"

namespace mospec::rdf {
namespace {

namespace fs = std::filesystem;

const fs::path kShared = MOSPEC_SHARED_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Reading what we wrote gives back the same dataset.
void expect_round_trip(const Dataset& d, const std::string& what) {
  Dataset again;
  read_nquads(to_nquads(d), again);
  EXPECT_TRUE(isomorphic(d, again)) << what << "\n" << describe_difference(d, again);
}

TEST(SharedData, UpstreamFlattenedGraphs) {
  const fs::path dir = kShared / "upstream" / "expected";
  if (!fs::is_directory(dir)) GTEST_SKIP() << dir << " not found (../shared is absent)";
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".nt") continue;
    const std::string text = slurp(entry.path());
    Dataset d;
    read_nquads(text, d, 1, entry.path().string());
    const auto lines = static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
    EXPECT_EQ(d.size(), lines) << entry.path();
    expect_round_trip(d, entry.path().string());
    if (entry.path().filename() == "sc1.nt") {
      EXPECT_EQ(d.size(), 1334u);
    }
    ++files;
  }
  EXPECT_EQ(files, 4u);
}

TEST(SharedData, JsonLdToRdfExpectationsParse) {
  const fs::path dir = kShared / "conformance" / "jsonld" / "toRdf";
  if (!fs::is_directory(dir)) GTEST_SKIP() << dir << " not found (../shared is absent)";
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".nq") continue;
    Dataset d;
    // A few expectations (produceGeneralizedRdf) have blank-node predicates.
    EXPECT_NO_THROW(read_nquads(slurp(entry.path()), d, NQuadsOptions{.generalized = true}, 1,
                                entry.path().string()))
        << entry.path();
    Dataset again;
    read_nquads(to_nquads(d), again, NQuadsOptions{.generalized = true});
    EXPECT_TRUE(isomorphic(d, again)) << entry.path() << "\n" << describe_difference(d, again);
    ++files;
  }
  EXPECT_GT(files, 300u);
}

TEST(SharedData, ShaclTurtleFilesParse) {
  const fs::path shsh = kShared / "spec" / "shacl-shacl.ttl";
  const fs::path core = kShared / "conformance" / "shacl" / "tests" / "core";
  if (!fs::exists(shsh) || !fs::is_directory(core))
    GTEST_SKIP() << "SHACL files not found (../shared is absent)";
  Dataset d;
  read_turtle(slurp(shsh), "http://www.w3.org/ns/shacl-shacl#", d, 1, shsh.string());
  const TermTable& t = d.terms();
  const TermId shape_shape = t.find_iri("http://www.w3.org/ns/shacl-shacl#ShapeShape");
  const TermId type = t.find_iri("http://www.w3.org/1999/02/22-rdf-syntax-ns#type");
  const TermId node_shape = t.find_iri("http://www.w3.org/ns/shacl#NodeShape");
  ASSERT_FALSE(shape_shape.is_any());
  EXPECT_EQ(d.count(shape_shape, type, node_shape), 1u);
  expect_round_trip(d, shsh.string());

  size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(core)) {
    if (entry.path().extension() != ".ttl") continue;
    Dataset g;
    const std::string base = "file://" + entry.path().string();
    EXPECT_NO_THROW(read_turtle(slurp(entry.path()), base, g, 1, entry.path().string()))
        << entry.path();
    EXPECT_GT(g.size(), 0u) << entry.path();
    ++files;
  }
  EXPECT_GT(files, 100u);
}

}  // namespace
}  // namespace mospec::rdf
