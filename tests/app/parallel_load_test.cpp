// A load reads, parses and expands an app's imports on two threads and turns
// them into quads on the calling thread, in order (LoadOptions::threads). The
// model must not depend on it: quads, blank node labels, file:line of every
// quad, the files, the apps, the warnings and the first error are the same as
// when every document is loaded one after another.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app/app.hpp"
#include "rdf/nquads.hpp"

namespace fs = std::filesystem;
using namespace mospec;

namespace {

const fs::path kSource = MOSPEC_SOURCE_DIR;
const fs::path kNested = kSource / "tests/app/data/nested";

std::string where(const app::LoadedModel& m, SourceLoc loc) {
  return m.files().path(loc.file) + ":" + std::to_string(loc.line) + ":" +
         std::to_string(loc.column);
}

// Everything a later stage can read of a loaded model, as text.
std::string describe(const app::LoadedModel& m) {
  std::ostringstream out;
  out << rdf::to_nquads(m.dataset());
  for (size_t i = 0; i < m.dataset().size(); ++i) out << where(m, m.dataset().location(i)) << '\n';
  for (const app::ModelFile& f : m.model_files()) {
    out << "file " << f.iri << ' ' << f.path << ' ' << m.files().path(f.file_id) << ' ' << f.is_app
        << ' ' << where(m, f.imported_at) << '\n';
  }
  // Reports sort by file id: the files' order by id is part of the model.
  std::vector<const app::ModelFile*> by_id;
  for (const app::ModelFile& f : m.model_files()) by_id.push_back(&f);
  std::sort(by_id.begin(), by_id.end(), [](auto* a, auto* b) { return a->file_id < b->file_id; });
  for (const app::ModelFile* f : by_id) out << "by id " << f->iri << '\n';
  for (const app::AppInfo& a : m.apps()) {
    out << "app " << a.file;
    for (const std::string& i : a.imports) out << ' ' << i;
    for (const std::string& c : a.constraints) out << ' ' << c;
    for (const auto& [prefix, dir] : a.iri_map) out << ' ' << prefix << '=' << dir;
    out << '\n';
  }
  for (const Diagnostic& d : m.diagnostics().diagnostics()) {
    out << "diagnostic " << d.file << ':' << d.line << ':' << d.column << ' ' << d.code << ' '
        << d.message << '\n';
  }
  return out.str();
}

// The model, or the error, loading `input` (relative to --root `root`).
// `impatient`: the calling thread prepares again every document it finds the
// other thread preparing instead of waiting for it.
std::string load_text(const fs::path& root, const std::string& input, unsigned threads,
                      bool impatient = false) {
  app::LoadOptions options;
  options.root = root.string();
  options.threads = threads;
  if (impatient) options.helper_patience = std::chrono::microseconds(0);
  try {
    return describe(app::load({(root / input).string()}, options));
  } catch (const Error& e) {
    const Diagnostic& d = e.diagnostic();
    return "error " + e.code() + " " + d.file + ":" + std::to_string(d.line) + ":" +
           std::to_string(d.column) + " " + d.message;
  }
}

void expect_same_on_two_threads(const fs::path& root, const std::string& input) {
  const std::string one = load_text(root, input, 1);
  ASSERT_FALSE(one.empty());
  // Several times: which thread takes which document varies from run to run.
  for (int run = 0; run < 6; ++run) {
    const bool impatient = run % 2 == 1;
    const std::string two = load_text(root, input, 2, impatient);
    ASSERT_EQ(one, two) << input << ", run " << run << (impatient ? " (impatient)" : "");
  }
}

// The shipped apps (the scenarios and the examples).
std::vector<std::string> shipped_apps() {
  std::vector<std::string> apps;
  for (const fs::path& dir : {kSource / "models", kSource / "models/examples"}) {
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (e.is_regular_file() && name.ends_with(".json") && !name.ends_with(".world.json")) {
        apps.push_back(fs::relative(e.path(), kSource).string());
      }
    }
  }
  std::sort(apps.begin(), apps.end());
  return apps;
}

TEST(ParallelLoad, ShippedAppsLoadTheSameOnOneThreadAndTwo) {
  const std::vector<std::string> apps = shipped_apps();
  ASSERT_GE(apps.size(), 10u);
  for (const std::string& app : apps) {
    SCOPED_TRACE(app);
    expect_same_on_two_threads(kSource, app);
  }
}

TEST(ParallelLoad, TheAuthorsAppsLoadTheSameOnOneThreadAndTwo) {
  const fs::path models = fs::path(MOSPEC_SHARED_DIR) / "upstream/motion-spec-ral";
  if (!fs::exists(models / "models")) {
    GTEST_SKIP() << "../shared/upstream/motion-spec-ral is absent (" << models.string()
                 << "); the authors' apps are needed for this test";
  }
  for (const char* app : {"sc0a-right-arm.json", "sc0b-dual-arm.json", "sc1.json", "sc2.json"}) {
    SCOPED_TRACE(app);
    expect_same_on_two_threads(models, std::string("models/") + app);
  }
}

TEST(ParallelLoad, WarningsComeInTheOrderOfTheImports) {
  const std::string text = load_text(kSource, "tests/app/data/nested/outer.json", 2);
  const size_t b = text.find("/tests/app/data/nested/b.json:12:7 ");
  const size_t d = text.find("/tests/app/data/nested/d.json:13:9 ");
  ASSERT_NE(b, std::string::npos) << text;
  ASSERT_NE(d, std::string::npos) << text;
  EXPECT_LT(b, d);
  expect_same_on_two_threads(kSource, "tests/app/data/nested/outer.json");
}

// An import that is itself an app maps IRIs of its own and loads its imports
// first (depth first): documents read ahead of it are not used.
TEST(ParallelLoad, AnImportThatIsAnAppLoadsAsItWouldOneAfterAnother) {
  const std::string text = load_text(kSource, "tests/app/data/nested/outer-nested.json", 2);
  EXPECT_NE(text.find("file https://mospec.example/tests/deep/e.json"), std::string::npos) << text;
  EXPECT_LT(text.find("file https://mospec.example/tests/deep/e.json"),
            text.find("file https://mospec.example/tests/nested/b.json"));
  expect_same_on_two_threads(kSource, "tests/app/data/nested/outer-nested.json");
}

TEST(ParallelLoad, MissingImportsAreReportedAsOneAfterAnother) {
  const std::string text = load_text(kSource, "tests/app/data/nested/outer-missing.json", 2);
  EXPECT_TRUE(text.starts_with("error loading document failed")) << text;
  EXPECT_NE(text.find("missing.json"), std::string::npos) << text;
  EXPECT_NE(text.find("(and 1 more missing import(s))"), std::string::npos) << text;
  expect_same_on_two_threads(kSource, "tests/app/data/nested/outer-missing.json");
}

// Both bad imports fail to expand; the first in the app's order is reported,
// whichever thread expanded which.
TEST(ParallelLoad, TheFirstBadImportInOrderIsTheError) {
  const std::string text = load_text(kSource, "tests/app/data/nested/outer-errors.json", 2);
  EXPECT_TRUE(text.starts_with("error ")) << text;
  EXPECT_NE(text.find("bad-version.json:3:"), std::string::npos) << text;
  expect_same_on_two_threads(kSource, "tests/app/data/nested/outer-errors.json");
}

}  // namespace
