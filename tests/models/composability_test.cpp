// Composition never edits: a file shared by several scenarios contributes the
// same triples (up to blank-node renaming) whichever scenario imports it, and a
// scenario's own files only add. A missing import is a located error naming it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "app/app.hpp"
#include "rdf/isomorphism.hpp"
#include "rdf/nquads.hpp"

namespace fs = std::filesystem;
using namespace mospec;

namespace {

const fs::path kRoot = MOSPEC_SOURCE_DIR;

app::LoadedModel load_scenario(const std::string& name) {
  app::LoadOptions options;
  options.root = kRoot.string();
  return app::load({(kRoot / "models" / (name + ".json")).string()}, options);
}

// The quads a file contributed (by provenance), as a dataset of their own.
rdf::Dataset contribution(const app::LoadedModel& model, uint32_t file_id) {
  rdf::Dataset out;
  const rdf::Dataset& all = model.dataset();
  for (size_t i = 0; i < all.size(); ++i) {
    if (all.location(i).file != file_id) continue;
    const rdf::Quad& q = all.quads()[i];
    rdf::TermTable& t = out.terms();
    out.add({t.import(all.terms(), q.subject), t.import(all.terms(), q.predicate),
             t.import(all.terms(), q.object), t.import(all.terms(), q.graph)});
  }
  return out;
}

TEST(Composability, SharedFilesContributeTheSameTriplesInEveryScenario) {
  const std::vector<std::string> scenarios = {"sc0a", "sc0b", "sc1", "sc2"};
  std::map<std::string, app::LoadedModel> models;
  for (const std::string& s : scenarios) models.emplace(s, load_scenario(s));

  // file IRI -> (scenario, contribution) for every file outside the app files.
  std::map<std::string, std::vector<std::pair<std::string, uint32_t>>> uses;
  for (const auto& [name, model] : models) {
    for (const app::ModelFile& f : model.model_files()) {
      if (!f.is_app) uses[f.iri].emplace_back(name, f.file_id);
    }
  }
  size_t shared = 0;
  for (const auto& [iri, list] : uses) {
    if (list.size() < 2) continue;
    ++shared;
    const rdf::Dataset first = contribution(models.at(list[0].first), list[0].second);
    EXPECT_GT(first.size(), 0u) << iri;
    for (size_t k = 1; k < list.size(); ++k) {
      const rdf::Dataset other = contribution(models.at(list[k].first), list[k].second);
      EXPECT_TRUE(rdf::isomorphic(first, other))
          << iri << " contributes differently to " << list[0].first << " and " << list[k].first
          << ":\n"
          << rdf::describe_difference(first, other);
    }
  }
  // The scenarios really share files (the arms, the robot), or this proves nothing.
  EXPECT_GE(shared, 5u);
}

// The ground triples the model files (not the app file) contribute, as N-Triples.
std::set<std::string> model_triples(const app::LoadedModel& model) {
  std::set<uint32_t> app_files;
  for (const app::ModelFile& f : model.model_files())
    if (f.is_app) app_files.insert(f.file_id);
  std::set<std::string> out;
  const rdf::Dataset& all = model.dataset();
  for (size_t i = 0; i < all.size(); ++i) {
    if (app_files.count(all.location(i).file)) continue;
    const rdf::Quad& q = all.quads()[i];
    std::string line;
    for (rdf::TermId t : {q.subject, q.predicate, q.object}) {
      if (all.terms()[t].kind == rdf::TermKind::Blank) {
        line.clear();  // blank nodes: covered by the isomorphism test above
        break;
      }
      rdf::append_ntriples(line, all.terms(), t);
      line += ' ';
    }
    if (!line.empty()) out.insert(line);
  }
  return out;
}

TEST(Composability, AScenarioOnlyAddsToTheOneItExtends) {
  // Every model triple of sc0a (right arm) is in sc0b (both arms): the later
  // scenario adds, never edits. (SC1 and SC2 are not supersets of sc0b: they
  // replace its per-arm motions and handlers with the alignment task's.)
  for (auto [base, extended] : {std::pair{"sc0a", "sc0b"}}) {
    const std::set<std::string> before = model_triples(load_scenario(base));
    const std::set<std::string> after = model_triples(load_scenario(extended));
    EXPECT_GT(before.size(), 100u) << base;
    for (const std::string& triple : before) {
      EXPECT_TRUE(after.count(triple)) << extended << " drops or changes: " << triple;
    }
  }
}

// Loads a copy of sc0a whose import `from` is renamed to `to`; returns the error text.
std::string load_with_renamed_import(const std::string& from, const std::string& to) {
  // One folder per process: ctest runs this executable's cases in parallel.
  const fs::path dir =
      fs::temp_directory_path() / ("mospec-composability-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ifstream in(kRoot / "models" / "sc0a.json");
  std::string app((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = app.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return {};
  app.replace(at, from.size(), to);
  const fs::path copy = dir / "sc0a-renamed.json";
  std::ofstream(copy) << app;
  app::LoadOptions options;
  options.root = kRoot.string();
  std::string what = "no error";
  try {
    app::load({copy.string()}, options);
  } catch (const Error& e) {
    what = e.what();
    EXPECT_EQ(e.code(), "loading document failed");
    EXPECT_NE(what.find(copy.string() + ":"), std::string::npos) << what;  // located at the import
  }
  fs::remove_all(dir);
  return what;
}

TEST(Composability, AMissingImportIsALocatedErrorNamingIt) {
  const std::string what =
      load_with_renamed_import("https://mospec.example/models/sc0a/07-scenario.json",
                               "https://mospec.example/models/sc0a/07-renamed.json");
  EXPECT_NE(what.find("07-renamed.json"), std::string::npos) << what;
}

TEST(Composability, AMissingImportNamesTheReferencesThatNowDangle) {
  // The right arm's world model defines the poses, twists and wrenches that its
  // map file reads: without it those references dangle, each named with the
  // place that makes it.
  const std::string what =
      load_with_renamed_import("https://mospec.example/models/right-arm/01-world-model.json",
                               "https://mospec.example/models/right-arm/01-renamed.json");
  EXPECT_NE(what.find("01-renamed.json"), std::string::npos) << what;
  EXPECT_NE(what.find("reference(s) now dangle"), std::string::npos) << what;
  EXPECT_NE(what.find("<https://mospec.example/models/pose-rightarm-platform-elbow> (" +
                      (kRoot / "models/right-arm/02-map.json:").string()),
            std::string::npos)
      << what;
  // The app file's own import list is not a reference.
  EXPECT_EQ(what.find("<https://mospec.example/models/right-arm/00-misc.json>"), std::string::npos)
      << what;
}

}  // namespace
