// Loading a large app's imports on two threads must give the model a load on
// one thread gives: the same quads with the same term ids, locations, files,
// warnings and errors, whichever document lands on which thread.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "app/app.hpp"
#include "support/io.hpp"

namespace fs = std::filesystem;
using namespace mospec;

namespace {

const fs::path kSource = MOSPEC_SOURCE_DIR;

struct Loaded {
  std::optional<app::LoadedModel> model;
  std::string error;  // format() of the error, when loading threw
};

Loaded load(const std::vector<std::string>& inputs, app::LoadOptions options, bool parallel) {
  options.parallel = parallel;
  Loaded out;
  try {
    out.model.emplace(app::load(inputs, options));
  } catch (const Error& e) {
    out.error = e.code() + ": " + format(e.diagnostic());
  }
  return out;
}

std::string describe(const rdf::Term& t) {
  return std::to_string(static_cast<int>(t.kind)) + " " + std::string(t.value) + " " +
         std::to_string(t.datatype.index) + " " + std::string(t.language) + " " +
         std::string(t.direction);
}

// Everything a later stage can read from a loaded model, compared exactly.
void expect_same(const app::LoadedModel& one, const app::LoadedModel& two) {
  const rdf::TermTable& a = one.dataset().terms();
  const rdf::TermTable& b = two.dataset().terms();
  ASSERT_EQ(a.size(), b.size());
  for (uint32_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(describe(a[rdf::TermId{i}]), describe(b[rdf::TermId{i}])) << "term " << i;
  }
  ASSERT_EQ(one.dataset().size(), two.dataset().size());
  for (size_t i = 0; i < one.dataset().size(); ++i) {
    ASSERT_EQ(one.dataset().quads()[i], two.dataset().quads()[i]) << "quad " << i;
    ASSERT_EQ(one.dataset().location(i), two.dataset().location(i)) << "quad " << i;
  }
  ASSERT_EQ(one.files().size(), two.files().size());
  for (uint32_t i = 0; i < one.files().size(); ++i) {
    EXPECT_EQ(one.files().path(i), two.files().path(i)) << "file " << i;
  }
  ASSERT_EQ(one.model_files().size(), two.model_files().size());
  for (size_t i = 0; i < one.model_files().size(); ++i) {
    const app::ModelFile& x = one.model_files()[i];
    const app::ModelFile& y = two.model_files()[i];
    EXPECT_EQ(x.iri, y.iri);
    EXPECT_EQ(x.path, y.path);
    EXPECT_EQ(x.file_id, y.file_id) << x.path;
    EXPECT_EQ(x.is_app, y.is_app) << x.path;
    EXPECT_EQ(x.imported_at, y.imported_at) << x.path;
  }
  ASSERT_EQ(one.apps().size(), two.apps().size());
  for (size_t i = 0; i < one.apps().size(); ++i) {
    EXPECT_EQ(one.apps()[i].file, two.apps()[i].file);
    EXPECT_EQ(one.apps()[i].imports, two.apps()[i].imports);
    EXPECT_EQ(one.apps()[i].constraints, two.apps()[i].constraints);
    EXPECT_EQ(one.apps()[i].iri_map, two.apps()[i].iri_map);
  }
  const auto& da = one.diagnostics().diagnostics();
  const auto& db = two.diagnostics().diagnostics();
  ASSERT_EQ(da.size(), db.size());
  for (size_t i = 0; i < da.size(); ++i) {
    EXPECT_EQ(format(da[i]), format(db[i]));
    EXPECT_EQ(da[i].code, db[i].code);
  }
}

app::LoadOptions in_source_tree() {
  app::LoadOptions options;
  options.root = kSource.string();
  return options;
}

class ShippedApp : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedApp, LoadsTheSameOnTwoThreadsAsOnOne) {
  const std::string app = (kSource / GetParam()).string();
  Loaded one = load({app}, in_source_tree(), /*parallel=*/false);
  Loaded two = load({app}, in_source_tree(), /*parallel=*/true);
  ASSERT_TRUE(one.model) << one.error;
  ASSERT_TRUE(two.model) << two.error;
  EXPECT_EQ(one.model->forked_documents(), 0u);
  expect_same(*one.model, *two.model);
}

INSTANTIATE_TEST_SUITE_P(Models, ShippedApp,
                         ::testing::Values("models/sc0a.json", "models/sc0b.json",
                                           "models/sc1.json", "models/sc2.json", "models/ur5e.json",
                                           "models/examples/lift.json",
                                           "models/examples/two-phase.json"),
                         [](const auto& info) {
                           std::string n = fs::path(info.param).stem().string();
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

TEST(ParallelLoad, TheAuthorsAppsLoadTheSameOnTwoThreadsAsOnOne) {
  const fs::path models = fs::path(MOSPEC_SHARED_DIR) / "upstream" / "motion-spec-ral";
  if (!fs::exists(models / "models")) {
    GTEST_SKIP() << "../shared/upstream/motion-spec-ral is absent (" << models.string()
                 << "); the authors' apps are needed for this test";
  }
  app::LoadOptions options;
  options.root = models.string();
  for (const char* name : {"sc0a-right-arm.json", "sc0b-dual-arm.json", "sc1.json", "sc2.json"}) {
    SCOPED_TRACE(name);
    const std::string app = (models / "models" / name).string();
    Loaded one = load({app}, options, false);
    Loaded two = load({app}, options, true);
    ASSERT_TRUE(one.model) << one.error;
    ASSERT_TRUE(two.model) << two.error;
    expect_same(*one.model, *two.model);
  }
}

TEST(ParallelLoad, Sc1ReallyLoadsOnTwoThreads) {
  // Otherwise the comparisons above compare a load with itself.
  Loaded two = load({(kSource / "models/sc1.json").string()}, in_source_tree(), true);
  ASSERT_TRUE(two.model) << two.error;
  EXPECT_GT(two.model->forked_documents(), 5u);
  EXPECT_LT(two.model->forked_documents(), 25u);
}

// sc1's import list, so that the split falls as it does for sc1.
std::vector<std::string> sc1_imports() {
  app::LoadedModel sc1 = app::load({(kSource / "models/sc1.json").string()}, in_source_tree());
  return sc1.apps().front().imports;
}

// An app in a temporary directory (inside --root) that imports `imports`;
// https://mospec.example/ maps to the source tree and https://t.example/ to
// the directory itself.
class Fixture : public ::testing::Test {
 public:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mospec-parallel-load-" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    options_.maps = {{"https://mospec.example/", kSource.string()},
                     {"https://t.example/", dir_.string()}};
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  std::string app(const std::string& name, const std::vector<std::string>& imports) {
    std::string text =
        R"({"@context": {"app": "https://comp-rob2b.github.io/metamodels/application/",
      "import": {"@id": "app:import", "@type": "@id"}},
      "@id": "https://t.example/)" +
        name + R"(", "import": [)";
    for (size_t i = 0; i < imports.size(); ++i) text += (i ? ", \"" : "\"") + imports[i] + "\"";
    text += "]}\n";
    write(name, text);
    return (dir_ / name).string();
  }
  void expect_same_either_way(const std::string& app_file, bool expect_error) {
    Loaded one = load({app_file}, options_, false);
    Loaded two = load({app_file}, options_, true);
    EXPECT_EQ(one.error, two.error);
    EXPECT_EQ(!one.error.empty(), expect_error) << one.error;
    if (one.model && two.model) expect_same(*one.model, *two.model);
  }

  fs::path dir_;
  app::LoadOptions options_;
};

TEST_F(Fixture, AMissingImportOnTheWorkerIsReportedAsOnOneThread) {
  std::vector<std::string> imports = sc1_imports();
  imports.insert(imports.end() - 3, "https://t.example/absent.json");
  expect_same_either_way(app("top.json", imports), /*expect_error=*/true);
}

TEST_F(Fixture, MissingImportsOnBothThreadsAreReportedAsOnOneThread) {
  std::vector<std::string> imports = sc1_imports();
  imports.insert(imports.begin() + 1, "https://t.example/absent-1.json");
  imports.push_back("https://t.example/absent-2.json");
  expect_same_either_way(app("top.json", imports), /*expect_error=*/true);
}

TEST_F(Fixture, ABrokenDocumentOnTheWorkerFailsAsOnOneThread) {
  write("broken.json", "{\"@id\": \"https://t.example/x\",\n  \"a\": [1, 2\n}\n");
  std::vector<std::string> imports = sc1_imports();
  imports.insert(imports.end() - 2, "https://t.example/broken.json");
  expect_same_either_way(app("top.json", imports), /*expect_error=*/true);
}

TEST_F(Fixture, ABrokenDocumentOnEachThreadFailsWithTheFirst) {
  write("broken.json", "{\"@id\": \"https://t.example/x\",\n  \"a\": [1, 2\n}\n");
  write("broken-2.json", "[}\n");
  std::vector<std::string> imports = sc1_imports();
  imports.insert(imports.begin() + 2, "https://t.example/broken.json");
  imports.push_back("https://t.example/broken-2.json");
  expect_same_either_way(app("top.json", imports), /*expect_error=*/true);
}

// A nested app (its own import list) inserted `at` into sc1's imports.
void nested_app_at(Fixture& f, std::ptrdiff_t at);

TEST_F(Fixture, ANestedAppOnTheWorkerLoadsAsOnOneThread) {
  nested_app_at(*this, -4);
}

TEST_F(Fixture, ANestedAppOnTheMainThreadLoadsAsOnOneThread) {
  nested_app_at(*this, 0);
}

TEST_F(Fixture, WarningsOfBothThreadsComeInImportOrder) {
  // An undefined key in a document on each side of the split.
  write("warn-1.json", R"({"@id": "https://t.example/w1", "undefinedKey1": 1})");
  write("warn-2.json", R"({"@id": "https://t.example/w2", "undefinedKey2": 2})");
  std::vector<std::string> imports = sc1_imports();
  imports.insert(imports.begin() + 1, "https://t.example/warn-1.json");
  imports.push_back("https://t.example/warn-2.json");
  const std::string top = app("top.json", imports);
  expect_same_either_way(top, /*expect_error=*/false);
  Loaded two = load({top}, options_, true);
  ASSERT_TRUE(two.model) << two.error;
  EXPECT_GT(two.model->forked_documents(), 0u);
  std::string all;
  for (const Diagnostic& d : two.model->diagnostics().diagnostics()) all += format(d) + "\n";
  const size_t first = all.find("undefinedKey1");
  const size_t second = all.find("undefinedKey2");
  ASSERT_NE(first, std::string::npos) << all;
  ASSERT_NE(second, std::string::npos) << all;
  EXPECT_LT(first, second) << all;
}

void nested_app_at(Fixture& f, std::ptrdiff_t at) {
  f.write("extra.json",
          R"({"@id": "https://t.example/extra", "@type": "https://t.example/Thing"})");
  f.app("nested.json",
        {"https://t.example/extra.json", "https://mospec.example/models/sc1/07-scenario.json"});
  std::vector<std::string> imports = sc1_imports();
  imports.insert(at < 0 ? imports.end() + at : imports.begin() + at,
                 "https://t.example/nested.json");
  f.expect_same_either_way(f.app("top.json", imports), /*expect_error=*/false);
}

}  // namespace
