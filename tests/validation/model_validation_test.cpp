// The validation pipeline that `mospec validate` runs (validation/model_validation):
// the authors' scenario verdicts through the library, shape files in the
// model's SourceFiles, JSON-LD shape files, errors, strict checks, and the
// JSON-LD report writer.
#include "validation/model_validation.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>

#include "app/app.hpp"
#include "rdf/nquads.hpp"
#include "shacl/report.hpp"
#include "shacl/validate.hpp"

namespace fs = std::filesystem;
using namespace mospec;

namespace {

const fs::path kUpstream = fs::path(MOSPEC_SHARED_DIR) / "upstream" / "motion-spec-ral";

// A scratch directory with files written by the test.
class Scratch {
 public:
  Scratch() {
    dir_ = fs::temp_directory_path() /
           ("mospec-mv-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }

 private:
  fs::path dir_;
};

const char* const kModel = R"({
  "@context": { "ex": "http://example.org/", "name": "ex:name", "Person": "ex:Person" },
  "@graph": [
    { "@id": "ex:alice", "@type": "Person", "name": "Alice" },
    { "@id": "ex:bob", "@type": "Person" }
  ] })";

const char* const kShapes = R"(@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:PersonShape a sh:NodeShape ; sh:targetClass ex:Person ;
  sh:property [ sh:path ex:name ; sh:minCount 1 ] .
ex:DroneShape a sh:NodeShape ; sh:targetClass ex:Drone .
)";

TEST(ModelValidation, UpstreamScenarioVerdicts) {
  if (!fs::exists(kUpstream / "models"))
    GTEST_SKIP() << "../shared/upstream/motion-spec-ral is absent (" << kUpstream.string()
                 << "); the authors' models and shapes are needed for this test";
  const std::pair<const char*, size_t> cases[] = {
      {"sc0a-right-arm", 1}, {"sc0b-dual-arm", 2}, {"sc1", 2}, {"sc2", 2}};
  for (auto [name, expected] : cases) {
    SCOPED_TRACE(name);
    app::LoadOptions options;
    options.root = kUpstream.string();
    app::LoadedModel model =
        app::load({(kUpstream / "models" / (std::string(name) + ".json")).string()}, options);
    validation::ModelValidation v = validation::validate_model(model, {});
    EXPECT_EQ(v.files.size(), 9u);
    const std::string text = shacl::to_text(v.report, &model.files(), &model.files());
    ASSERT_EQ(v.report.results.size(), expected) << text;
    EXPECT_EQ(v.report.count(shacl::Level::Violation), expected);
    for (const shacl::Result& r : v.report.results) {
      EXPECT_EQ(r.component, shacl::Component::Xone) << text;
      EXPECT_EQ(v.report.terms[r.shape].value,
                "https://comp-rob2b.github.io/metamodels/geometry/coordinates#DirectionCosineXYZ");
      const std::string focus(v.report.terms[r.focus].value);
      EXPECT_TRUE(focus.ends_with("-platform-shoulder")) << focus;
      // Located where the focus node's @id is written, in the model's files.
      ASSERT_TRUE(r.focus_loc.known());
      EXPECT_EQ(r.focus_loc.line, 59u);
      EXPECT_TRUE(model.files().path(r.focus_loc.file).ends_with("-arm/00-misc.json"));
      // Shapes are located in the same file table.
      EXPECT_TRUE(model.files().path(r.shape_loc.file).ends_with("geometry/coordinates.ttl"));
    }
  }
}

TEST(ModelValidation, ShapeFilesFromTurtleAndJsonLdShareTheFileTable) {
  Scratch dir;
  const std::string model_path = dir.write("model.json", kModel);
  const std::string ttl = dir.write("shapes.ttl", kShapes);
  const std::string jsonld = dir.write("shapes.jsonld", R"({
  "@context": { "sh": "http://www.w3.org/ns/shacl#", "ex": "http://example.org/" },
  "@id": "ex:NameShape", "@type": "sh:NodeShape",
  "sh:targetNode": { "@id": "ex:alice" },
  "sh:property": { "sh:path": { "@id": "ex:name" },
    "sh:maxCount": { "@value": "0", "@type": "http://www.w3.org/2001/XMLSchema#integer" } } })");
  app::LoadedModel model = app::load({model_path});
  validation::ModelValidationOptions options;
  options.extra_shapes = {ttl, jsonld};
  validation::ModelValidation v = validation::validate_model(model, options);
  ASSERT_EQ(v.report.results.size(), 2u) << shacl::to_text(v.report, &model.files());
  // bob: minCount (Turtle shape); alice: maxCount 0 (JSON-LD shape).
  const std::string text = shacl::to_text(v.report, &model.files(), &model.files());
  EXPECT_NE(text.find(model_path + ":4:14: error: <http://example.org/alice>"), std::string::npos)
      << text;
  EXPECT_NE(text.find(model_path + ":5:14: error: <http://example.org/bob>"), std::string::npos)
      << text;
  // Each finding is followed by a note at the shape that fired.
  EXPECT_NE(text.find("\n" + ttl + ":4:"), std::string::npos) << text;
  EXPECT_NE(text.find("\n" + jsonld + ":"), std::string::npos) << text;
  EXPECT_NE(text.find(": note: the shape that fired: []\n"), std::string::npos) << text;
}

TEST(ModelValidation, BadShapeFilesAreHardErrors) {
  Scratch dir;
  app::LoadedModel model = app::load({dir.write("model.json", kModel)});
  auto error_of = [&](const std::string& shapes_path) -> std::string {
    validation::ModelValidationOptions options;
    options.extra_shapes = {shapes_path};
    try {
      validation::validate_model(model, options);
    } catch (const Error& e) {
      return format(e.diagnostic());
    }
    return "no error";
  };
  const std::string missing = (fs::path(dir.write("x", "")).parent_path() / "nope.ttl").string();
  EXPECT_EQ(error_of(missing),
            "mospec: error: cannot read shape file '" + missing + "': No such file or directory");
  const std::string syntax =
      dir.write("syntax.ttl", "@prefix ex: <http://example.org/> .\nex:a ex:b .\n");
  EXPECT_EQ(error_of(syntax).rfind(syntax + ":2:", 0), 0u) << error_of(syntax);
  const std::string sparql =
      dir.write("sparql.ttl",
                "@prefix sh: <http://www.w3.org/ns/shacl#> .\n"
                "<http://example.org/S> sh:targetNode <http://example.org/a> ;\n"
                "  sh:sparql [ sh:select \"\"\"\n"
                "SELECT $this WHERE {\n"
                "  $this ?p ?o FILTER(\n"
                "}\"\"\" ] .\n");
  const std::string e = error_of(sparql);
  // Query line 4 ("}": the query starts with the newline after """) is file line 6; the message
  // names the shape and the position inside the query.
  EXPECT_EQ(e.rfind(sparql + ":6:1: error: shape <http://example.org/S>: ", 0), 0u) << e;
  EXPECT_NE(e.find("line 4, column 1 of the query"), std::string::npos) << e;
  const std::string ill =
      dir.write("ill.ttl",
                "@prefix sh: <http://www.w3.org/ns/shacl#> .\n"
                "<http://example.org/S> sh:targetNode <http://example.org/a> ;\n"
                "  sh:nodeKind sh:Nothing .\n");
  EXPECT_EQ(error_of(ill).rfind(ill + ":3:", 0), 0u) << error_of(ill);
  // No shapes at all.
  try {
    validation::validate_model(model, {});
    ADD_FAILURE() << "no error without shapes";
  } catch (const Error& err) {
    EXPECT_EQ(err.code(), "usage");
  }
}

TEST(ModelValidation, StrictChecks) {
  Scratch dir;
  const std::string model_path = dir.write("model.json", R"({
  "@context": { "ex": "http://example.org/", "name": "ex:name", "Person": "ex:Person" },
  "@graph": [
    { "@id": "ex:alice", "@type": "Person", "name": "Alice" },
    { "@id": "ex:bot", "@type": "ex:Robot", "name": "R2" }
  ] })");
  app::LoadedModel model = app::load({model_path});
  validation::ModelValidationOptions options;
  options.extra_shapes = {dir.write("shapes.ttl", kShapes)};
  options.strict = true;
  validation::ModelValidation v = validation::validate_model(model, options);
  EXPECT_TRUE(v.report.conforms());
  ASSERT_EQ(v.strict_findings.size(), 2u);
  std::vector<std::string> lines;
  for (const Diagnostic& d : v.strict_findings) lines.push_back(format(d));
  // Person is defined by the context (and the shapes), ex:Robot by nothing;
  // DroneShape targets a class with no instances.
  EXPECT_EQ(lines[0].rfind(model_path + ":5:", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("type <http://example.org/Robot> is defined by no loaded JSON-LD "
                          "context or shape (used 1 time)"),
            std::string::npos)
      << lines[0];
  EXPECT_NE(lines[1].find(":5:"), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find("shape <http://example.org/DroneShape> has targets but selects no "
                          "focus node"),
            std::string::npos)
      << lines[1];

  std::vector<size_t> counts = shacl::count_focus_nodes(*v.shapes, model.dataset());
  size_t with_focus = 0;
  for (size_t n : counts) with_focus += n;
  EXPECT_EQ(with_focus, 1u);  // PersonShape -> alice

  std::vector<std::string> iris = validation::context_term_iris(model);
  EXPECT_TRUE(std::binary_search(iris.begin(), iris.end(), "http://example.org/Person"));
  EXPECT_TRUE(std::binary_search(iris.begin(), iris.end(), "http://example.org/name"));
  EXPECT_FALSE(std::binary_search(iris.begin(), iris.end(), "http://example.org/Robot"));
}

TEST(ModelValidation, JsonLdReportReadsBackAsTheReportGraph) {
  Scratch dir;
  app::LoadedModel model = app::load({dir.write("model.json", kModel)});
  validation::ModelValidationOptions options;
  options.extra_shapes = {dir.write("shapes.ttl", kShapes)};
  validation::ModelValidation v = validation::validate_model(model, options);
  const std::string jsonld = shacl::to_jsonld(v.report);
  EXPECT_EQ(jsonld, shacl::to_jsonld(v.report));  // deterministic
  // mospec's own JSON-LD loader turns it into the same graph as to_dataset.
  app::LoadedModel back = app::load({dir.write("report.jsonld", jsonld)});
  rdf::Dataset expected = shacl::to_dataset(v.report);
  rdf::Dataset got = back.flattened();
  EXPECT_EQ(got.size(), expected.size()) << rdf::to_nquads(got, rdf::Format::NTriples) << "\nvs\n"
                                         << rdf::to_nquads(expected, rdf::Format::NTriples);
  EXPECT_NE(jsonld.find("\"sh:sourceConstraintComponent\": {\n        \"@id\": "
                        "\"sh:MinCountConstraintComponent\""),
            std::string::npos)
      << jsonld;
}

// vocabulary_shape_files copies each selected file over from the copy it read
// to look at its targets instead of reading it a second time: `into` must hold
// exactly what reading the files into it in turn gives (term ids, blank-node
// labels, quads and their locations), after shapes already read.
TEST(ModelValidation, VocabularyShapeFilesLandAsIfReadIntoTheGraph) {
  const fs::path source = MOSPEC_SOURCE_DIR;
  app::LoadOptions options;
  options.root = source.string();
  app::LoadedModel model = app::load({(source / "models" / "sc1.json").string()}, options);
  Scratch dir;
  const validation::ShapeFile first{dir.write("first.ttl", kShapes), "", {}};

  rdf::Dataset got;
  validation::read_shape_file(first, model.loader(), got);
  const std::vector<validation::ShapeFile> files = validation::vocabulary_shape_files(model, got);
  ASSERT_GE(files.size(), 2u);

  rdf::Dataset expected;
  validation::read_shape_file(first, model.loader(), expected);
  for (const validation::ShapeFile& f : files)
    validation::read_shape_file(f, model.loader(), expected);

  ASSERT_EQ(got.terms().size(), expected.terms().size());
  for (uint32_t i = 0; i < got.terms().size(); ++i) {
    const rdf::Term& a = got.terms()[rdf::TermId{i}];
    const rdf::Term& b = expected.terms()[rdf::TermId{i}];
    ASSERT_EQ(static_cast<int>(a.kind), static_cast<int>(b.kind)) << i;
    ASSERT_EQ(a.value, b.value) << i;
    ASSERT_EQ(a.datatype, b.datatype) << i;
    ASSERT_EQ(a.language, b.language) << i;
  }
  ASSERT_EQ(got.size(), expected.size());
  for (size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got.quads()[i], expected.quads()[i]) << i;
    const SourceLoc a = got.location(i), b = expected.location(i);
    ASSERT_EQ(std::tie(a.file, a.line, a.column), std::tie(b.file, b.line, b.column)) << i;
  }
}

// A manifest file among `read_before` (the files the app lists, read already)
// is skipped without being read again.
TEST(ModelValidation, VocabularyShapeFilesSkipFilesReadBefore) {
  const fs::path source = MOSPEC_SOURCE_DIR;
  app::LoadOptions options;
  options.root = source.string();
  app::LoadedModel model = app::load({(source / "models" / "sc1.json").string()}, options);
  rdf::Dataset all;
  const std::vector<validation::ShapeFile> files = validation::vocabulary_shape_files(model, all);
  ASSERT_GE(files.size(), 2u);
  // Claim the first one was read before (it was not: `none` stays without it).
  rdf::Dataset none;
  const std::vector<validation::ShapeFile> rest =
      validation::vocabulary_shape_files(model, none, nullptr, {files.data(), 1});
  ASSERT_EQ(rest.size(), files.size() - 1);
  for (size_t i = 0; i < rest.size(); ++i) EXPECT_EQ(rest[i].path, files[i + 1].path);
  EXPECT_LT(none.size(), all.size());
}

}  // namespace
