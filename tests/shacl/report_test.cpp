// Report writers: Turtle (parses back to the report graph), text lines.
#include <gtest/gtest.h>

#include "rdf/isomorphism.hpp"
#include "test_util.hpp"

using namespace mospec;
using namespace mospec::shacl;
using mospec::shacl::test_util::kPrefixLines;
using mospec::shacl::test_util::turtle;

namespace {

const char* kShapes = R"(ex:S a sh:NodeShape ;
  sh:targetClass ex:C ;
  sh:property [ sh:path ( ex:p [ sh:inversePath ex:q ] ) ; sh:minCount 1 ] ;
  sh:property [ sh:path ex:name ; sh:datatype xsd:string ; sh:severity sh:Warning ;
                sh:message "bad name"@en, "schlechter Name"@de ] ;
  sh:property [ sh:path [ sh:alternativePath ( ex:a ex:b ) ] ; sh:maxCount 0 ; sh:severity sh:Info ] .
)";

const char* kData = R"(ex:one a ex:C ;
  ex:name 42 ;
  ex:a "quote \" and \\ backslash" .
ex:two a ex:C ; ex:p ex:x . ex:w ex:q ex:x .
)";

struct Fixture {
  std::unique_ptr<test_util::Graph> shapes = turtle(kShapes);
  std::unique_ptr<test_util::Graph> data = turtle(kData, "data.ttl");
  Shapes compiled = Shapes::compile(shapes->data, &shapes->files);
  Report report = validate(compiled, data->data);
};

TEST(Report, CountsPerSeverity) {
  Fixture f;
  EXPECT_EQ(f.report.count(Level::Violation), 1u);  // ex:one has no p/^q value
  EXPECT_EQ(f.report.count(Level::Warning), 1u);
  EXPECT_EQ(f.report.count(Level::Info), 1u);
  EXPECT_FALSE(f.report.conforms());
}

TEST(Report, TurtleParsesBackToTheReportGraph) {
  Fixture f;
  std::string ttl = to_turtle(f.report);
  rdf::Dataset parsed;
  rdf::read_turtle(ttl, "http://example.org/report", parsed);
  rdf::Dataset expected = to_dataset(f.report);
  EXPECT_TRUE(rdf::isomorphic(parsed, expected)) << ttl << "\n"
                                                 << rdf::describe_difference(parsed, expected);
  EXPECT_EQ(ttl, to_turtle(f.report)) << "deterministic";
  EXPECT_NE(ttl.find("sh:resultPath ( <http://example.org/p> [ sh:inversePath "
                     "<http://example.org/q> ] )"),
            std::string::npos)
      << ttl;
  EXPECT_NE(ttl.find("\"bad name\"@en"), std::string::npos) << ttl;
}

TEST(Report, ConformingReportInTurtle) {
  auto shapes = turtle("ex:S a sh:NodeShape ; sh:targetNode ex:a .");
  Shapes compiled = Shapes::compile(shapes->data, &shapes->files);
  rdf::Dataset empty;
  Report r = validate(compiled, empty);
  EXPECT_TRUE(r.conforms());
  EXPECT_NE(to_turtle(r).find("sh:conforms true ."), std::string::npos) << to_turtle(r);
  EXPECT_EQ(to_text(r, nullptr), "shacl: 0 violations, 0 warnings, 0 infos\n");
}

TEST(Report, TextLinesNameTheFocusNodesLocation) {
  Fixture f;
  std::string text = to_text(f.report, &f.data->files, &f.shapes->files);
  const std::string l1 = std::to_string(kPrefixLines + 1);
  // ex:one is written first: its three results come first, sorted by shape,
  // then component.
  EXPECT_NE(text.find("data.ttl:" + l1 + ":"), std::string::npos) << text;
  EXPECT_NE(text.find(": warning: <http://example.org/one>: bad name [sh:"), std::string::npos)
      << text;
  EXPECT_NE(text.find("]\nshapes.ttl:"), std::string::npos) << text;
  EXPECT_NE(text.find("sh:DatatypeConstraintComponent, path <http://example.org/name>, value "
                      "\"42\"^^<http://www.w3.org/2001/XMLSchema#integer>]"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("path <http://example.org/p>/(^<http://example.org/q>)]"), std::string::npos)
      << text;
  EXPECT_NE(text.find("path <http://example.org/a>|<http://example.org/b>]"), std::string::npos)
      << text;
  EXPECT_TRUE(text.ends_with("\nshacl: 1 violation, 1 warning, 1 info\n")) << text;
  // Two lines per result (the finding, the note at its shape) plus the summary.
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 7);
}

}  // namespace
