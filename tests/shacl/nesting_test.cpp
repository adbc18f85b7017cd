// Shapes graphs that nest deeper than the compiler and validator allow are
// refused with a located error naming the shape, never a stack overflow. The
// inputs are generated here (flat Turtle with labelled nodes, so the Turtle
// reader's own nesting does not matter).
#include <gtest/gtest.h>

#include <functional>

#include "test_util.hpp"

using namespace mospec;
using namespace mospec::shacl;
using mospec::shacl::test_util::kPrefixLines;
using mospec::shacl::test_util::refused;
using mospec::shacl::test_util::turtle;

namespace {

// `n` links written by `link(i)` (each a full Turtle statement on one line),
// after `head` (one line).
std::string chain(const std::string& head, int n, const std::function<std::string(int)>& link) {
  std::string body = head + "\n";
  for (int i = 0; i < n; ++i) body += link(i) + "\n";
  return body;
}

void expect_too_deep(const Error& e, const std::string& what) {
  EXPECT_EQ(e.code(), "shacl-too-deep") << e.what();
  EXPECT_EQ(e.diagnostic().file, "shapes.ttl") << e.what();
  EXPECT_NE(e.diagnostic().line, 0u) << e.what();
  EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("256"), std::string::npos) << e.what();
}

const std::string kHead = "ex:S0 a sh:NodeShape ; sh:targetNode ex:a .";

TEST(ShapeNesting, TenThousandChainedNodeShapes) {
  Error e = refused(chain(kHead, 10000, [](int i) {
    return "ex:S" + std::to_string(i) + " sh:node ex:S" + std::to_string(i + 1) + " .";
  }));
  expect_too_deep(e, "nest deeper than 256 levels");
  // The innermost shape that did not fit: S256, written on its own line.
  EXPECT_NE(std::string(e.what()).find("<http://example.org/S256>"), std::string::npos) << e.what();
  EXPECT_EQ(e.diagnostic().line, kPrefixLines + 1 + 256 + 1) << e.what();
}

TEST(ShapeNesting, NestedLogicalAndShapeComponents) {
  // Each link nests one blank-node shape inside the previous one.
  const std::vector<std::pair<std::string, std::function<std::string(int)>>> cases{
      {"sh:not",
       [](int i) {
         return "_:n" + std::to_string(i) + " sh:not _:n" + std::to_string(i + 1) + " .";
       }},
      {"sh:and",
       [](int i) {
         return "_:n" + std::to_string(i) + " sh:and ( _:n" + std::to_string(i + 1) + " ) .";
       }},
      {"sh:or",
       [](int i) {
         return "_:n" + std::to_string(i) + " sh:or ( _:n" + std::to_string(i + 1) + " ) .";
       }},
      {"sh:xone",
       [](int i) {
         return "_:n" + std::to_string(i) + " sh:xone ( _:n" + std::to_string(i + 1) + " ) .";
       }},
      {"sh:qualifiedValueShape",
       [](int i) {
         return "_:n" + std::to_string(i) + " sh:path ex:p ; sh:qualifiedMinCount 1 ; " +
                "sh:qualifiedValueShape _:n" + std::to_string(i + 1) + " .";
       }},
      {"sh:property",
       [](int i) {
         return "_:n" + std::to_string(i) + " sh:path ex:p ; sh:property _:n" +
                std::to_string(i + 1) + " .";
       }},
  };
  for (const auto& [name, link] : cases) {
    SCOPED_TRACE(name);
    std::string head = "ex:S0 a sh:NodeShape ; sh:targetNode ex:a ; sh:node _:n0 .";
    expect_too_deep(refused(chain(head, 10000, link)), "nest deeper than 256 levels");
  }
}

TEST(ShapeNesting, FiftyThousandChainedInversePaths) {
  std::string head =
      "ex:S0 a sh:NodeShape ; sh:targetNode ex:a ; sh:property ex:P .\n"
      "ex:P sh:path _:i0 ; sh:minCount 1 .";
  Error e = refused(chain(head, 50000, [](int i) {
    return "_:i" + std::to_string(i) + " sh:inversePath _:i" + std::to_string(i + 1) + " .";
  }));
  expect_too_deep(e, "sh:path nests deeper than 256 levels");
  EXPECT_NE(std::string(e.what()).find("<http://example.org/P>"), std::string::npos) << e.what();
}

TEST(ShapeNesting, NestedSequenceAndAlternativePaths) {
  // A sequence whose first member is a sequence, ...; an alternative whose
  // first member is an alternative, ...
  auto sequence = [](int i) {
    return "_:i" + std::to_string(i) + " rdf:first _:i" + std::to_string(i + 1) +
           " ; rdf:rest ( ex:p ) .";
  };
  auto alternative = [](int i) {
    return "_:i" + std::to_string(i) + " sh:alternativePath ( _:i" + std::to_string(i + 1) +
           " ex:p ) .";
  };
  for (const auto& link :
       {std::function<std::string(int)>(sequence), std::function<std::string(int)>(alternative)}) {
    std::string head =
        "ex:S0 a sh:NodeShape ; sh:targetNode ex:a ; sh:property ex:P .\n"
        "ex:P sh:path _:i0 ; sh:minCount 1 .";
    expect_too_deep(refused(chain(head, 20000, link)), "sh:path nests deeper than 256 levels");
  }
}

TEST(ShapeNesting, NestingWithinTheLimitsStillValidates) {
  // 200 chained sh:node shapes and a 200-deep inverse path are fine.
  std::string body = chain(kHead, 200, [](int i) {
    return "ex:S" + std::to_string(i) + " sh:node ex:S" + std::to_string(i + 1) + " .";
  });
  body += "ex:S200 sh:property [ sh:path _:i0 ; sh:maxCount 0 ] .\n";
  for (int i = 0; i < 200; ++i)
    body += "_:i" + std::to_string(i) + " sh:inversePath _:i" + std::to_string(i + 1) + " .\n";
  body += "_:i200 sh:inversePath ex:p .\n";
  auto g = turtle(body);
  Shapes shapes = Shapes::compile(g->data, &g->files);
  Report r = validate(shapes, g->data);
  EXPECT_TRUE(r.conforms()) << to_text(r, nullptr);
}

TEST(ShapeNesting, ChainsWrittenInnermostFirstStopInTheValidator) {
  // Written innermost shape first, each shape compiles without nesting; the
  // validator then nests one level per shape and stops with its own error.
  std::string body;
  for (int i = 10000; i-- > 0;)
    body += "ex:S" + std::to_string(i) + " sh:node ex:S" + std::to_string(i + 1) + " .\n";
  body += kHead + "\n";
  Error e = refused(body);
  EXPECT_EQ(e.code(), "shacl-recursion") << e.what();
  EXPECT_NE(std::string(e.what()).find("deeper than"), std::string::npos) << e.what();
  EXPECT_EQ(e.diagnostic().file, "shapes.ttl") << e.what();
}

}  // namespace
