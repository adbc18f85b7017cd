// The operator registry (src/ir/operators.*): every kind is complete — a
// name, a vocabulary class, typed ports, parsed frame rules, a kernel the
// interpreter calls and codegen names — and comes with what a user of its
// class needs: a JSON-LD context term, a SHACL shape, and a conforming and a
// violating shape test case. A kind that lacks any of them fails here.
#include "ir/operators.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "source_tree.hpp"

namespace mospec::ir {
namespace {

namespace fs = std::filesystem;

// A prefixed name of the class in a file that declares the prefix for the
// class's namespace: `geom-op:ComposePose` where geom-op is the namespace.
bool names_class(const std::string& text, const OperatorKind& k) {
  if (text.find(std::string(k.vocabulary)) == std::string::npos) return false;
  const std::regex name("[A-Za-z_-]+:" + std::string(k.type) + "\\b");
  return std::regex_search(text, name);
}

TEST(OperatorRegistry, EveryKindIsComplete) {
  std::set<std::string> names, classes;
  for (const OperatorKind& k : operator_kinds()) {
    SCOPED_TRACE(std::string(k.name));
    EXPECT_FALSE(k.name.empty());
    EXPECT_TRUE(names.insert(std::string(k.name)).second) << "two kinds named " << k.name;
    EXPECT_TRUE(classes.insert(k.class_iri()).second) << "two kinds lower " << k.class_iri();
    EXPECT_TRUE(k.vocabulary.starts_with("https://") && k.vocabulary.ends_with("#"));
    EXPECT_FALSE(k.type.empty());
    EXPECT_FALSE(k.out.property.empty());
    for (const OperatorPort& p : k.in) EXPECT_FALSE(p.property.empty());
    EXPECT_FALSE(k.kernel.empty());
    EXPECT_NE(k.interpret, nullptr);
    EXPECT_FALSE(k.summary.empty());
    EXPECT_EQ(operator_index(k.name), &k - operator_kinds().data());
    for (const FrameRule& r : k.frames) {
      EXPECT_LE(r.lhs_port, static_cast<int>(k.in.size()));
      EXPECT_LE(r.rhs_port, static_cast<int>(k.in.size()));
    }
  }
}

TEST(OperatorRegistry, EveryClassHasAContextTermAShapeAndShapeTests) {
  const fs::path src = MOSPEC_SOURCE_DIR;
  const auto contexts = mospec::test::texts_of_files(src / "metamodels", ".json");
  const auto shapes = mospec::test::texts_of_files(src / "metamodels", ".ttl");
  const auto good = mospec::test::texts_of_files(src / "tests/models/data", "-good.json");
  const auto bad = mospec::test::texts_of_files(src / "tests/models/data", "-bad.json");
  for (const OperatorKind& k : operator_kinds()) {
    SCOPED_TRACE(k.class_iri());
    bool context = false, shape = false, conforming = false, violating = false;
    for (const std::string& text : contexts) {
      context = context || (text.find(std::string(k.vocabulary)) != std::string::npos &&
                            text.find('"' + std::string(k.type) + "\": {") != std::string::npos);
    }
    for (const std::string& text : shapes) {
      shape = shape || (text.find("sh:targetClass") != std::string::npos && names_class(text, k));
    }
    // A node typed with the class (prefixed or in full, alone or in a list).
    const std::regex typed("\"([A-Za-z_-]+:|[^\"]*#)" + std::string(k.type) + "\"");
    for (const std::string& text : good) conforming = conforming || std::regex_search(text, typed);
    for (const std::string& text : bad) violating = violating || std::regex_search(text, typed);
    EXPECT_TRUE(context) << "no JSON-LD context in metamodels/ defines the term " << k.type;
    EXPECT_TRUE(shape) << "no shape in metamodels/ targets " << k.type;
    EXPECT_TRUE(conforming) << "no tests/models/data/*-good.json has an instance of " << k.type;
    EXPECT_TRUE(violating) << "no tests/models/data/*-bad.json has an instance of " << k.type;
  }
}

TEST(OperatorRegistry, FrameRulesNamePortsAndFields) {
  const OperatorKind& k =
      operator_kinds()[static_cast<size_t>(operator_index("transform-wrench-to-proximal"))];
  ASSERT_EQ(k.frames.size(), 4u);
  EXPECT_EQ(k.frames[1].text, "from.reference-point = origin(pose.of)");
  EXPECT_EQ(k.frames[1].lhs_port, k.port("from"));
  EXPECT_EQ(k.frames[1].lhs_field, FrameField::ReferencePoint);
  EXPECT_EQ(k.frames[1].rhs_port, k.port("pose"));
  EXPECT_EQ(k.frames[1].rhs_field, FrameField::Of);
  EXPECT_TRUE(k.frames[1].rhs_origin);
  EXPECT_EQ(k.port("to"), 2);
  EXPECT_EQ(k.port("nothing"), -1);
}

}  // namespace
}  // namespace mospec::ir
