// The authors' scenario apps, loaded through mospec, must mean exactly what a
// conformant JSON-LD processor says they mean (../shared/upstream/expected), and
// the terms they silently lose must be reported.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "app/app.hpp"
#include "rdf/isomorphism.hpp"
#include "rdf/nquads.hpp"
#include "support/io.hpp"

namespace fs = std::filesystem;
using namespace mospec;

namespace {

const fs::path kUpstream = fs::path(MOSPEC_SHARED_DIR) / "upstream";
const fs::path kModels = kUpstream / "motion-spec-ral";

#define SKIP_WITHOUT_SHARED()                                                            \
  if (!fs::exists(kModels / "models")) {                                                 \
    GTEST_SKIP() << "../shared/upstream/motion-spec-ral is absent (" << kModels.string() \
                 << "); the upstream compatibility corpus is needed for this test";      \
  }

app::LoadedModel load_app(const std::string& app_file) {
  app::LoadOptions options;
  options.root = kModels.string();  // the app's iri-map paths are relative to this folder
  return app::load({(kModels / "models" / app_file).string()}, options);
}

class UpstreamApp : public ::testing::TestWithParam<std::string> {};

TEST_P(UpstreamApp, FlattenedUnionIsIsomorphicToReference) {
  SKIP_WITHOUT_SHARED();
  const std::string name = GetParam();
  app::LoadedModel model = load_app(name + ".json");
  rdf::Dataset got = model.flattened();

  rdf::Dataset expected;
  read_nquads(read_file((kUpstream / "expected" / (name + ".nt")).string()), expected);
  EXPECT_EQ(got.size(), expected.size());
  EXPECT_TRUE(rdf::isomorphic(got, expected)) << rdf::describe_difference(got, expected);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, UpstreamApp,
                         ::testing::Values("sc0a-right-arm", "sc0b-dual-arm", "sc1", "sc2"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

TEST(UpstreamApp, Sc1HasThePublishedTripleCountAndFiles) {
  SKIP_WITHOUT_SHARED();
  app::LoadedModel model = load_app("sc1.json");
  EXPECT_EQ(model.flattened().size(), 1334u);
  // The app file plus its 27 distinct imports (two are listed twice).
  EXPECT_EQ(model.model_files().size(), 28u);
  ASSERT_EQ(model.apps().size(), 1u);
  EXPECT_EQ(model.apps()[0].imports.size(), 27u);
  EXPECT_EQ(model.apps()[0].constraints.size(), 9u);
}

bool has_diagnostic(const app::LoadedModel& model, std::string_view file_suffix,
                    std::string_view code, std::string_view text, uint32_t line) {
  for (const Diagnostic& d : model.diagnostics().diagnostics()) {
    if (d.code == code && d.file.ends_with(file_suffix) &&
        d.message.find(text) != std::string::npos && (line == 0 || d.line == line)) {
      return true;
    }
  }
  return false;
}

std::string all_diagnostics(const app::LoadedModel& model) {
  std::string out;
  for (const Diagnostic& d : model.diagnostics().diagnostics()) out += format(d) + "\n";
  return out;
}

TEST(UpstreamApp, SilentDropsAreReportedWithTheirLocation) {
  SKIP_WITHOUT_SHARED();
  app::LoadedModel model = load_app("sc1.json");
  EXPECT_TRUE(has_diagnostic(model, "01-right-arm/00-misc.json", "undefined-type",
                             "RotateWrenchToProximalWithPose", 78))
      << all_diagnostics(model);
  EXPECT_TRUE(
      has_diagnostic(model, "04-sc1/07-scenario.json", "dropped-key", "kinematic-chain", 66))
      << all_diagnostics(model);
  EXPECT_TRUE(
      has_diagnostic(model, "04-sc1/07-scenario.json", "dropped-key", "kinematic-chain", 120))
      << all_diagnostics(model);
  for (const Diagnostic& d : model.diagnostics().diagnostics()) {
    EXPECT_EQ(d.severity, Severity::Warning) << format(d);
    EXPECT_FALSE(d.file.empty()) << format(d);
    EXPECT_GT(d.line, 0u) << format(d);
  }
}

TEST(UpstreamApp, EntitiesKnowWhereTheirIdIsWritten) {
  SKIP_WITHOUT_SHARED();
  app::LoadedModel model = load_app("sc1.json");
  rdf::TermId chain =
      model.dataset().terms().find_iri("https://secorolab.github.io/models/demo/chain-rightarm");
  ASSERT_FALSE(chain.is_any());
  auto loc = model.where(chain);
  ASSERT_TRUE(loc.has_value());
  EXPECT_TRUE(model.files().path(loc->file).ends_with("models/01-right-arm/00-misc.json"))
      << model.describe(*loc);
  EXPECT_EQ(loc->line, 53u) << model.describe(*loc);
}

}  // namespace
