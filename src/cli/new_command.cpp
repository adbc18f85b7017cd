// `mospec new NAME --from SCENARIO`: a new task that starts as a copy of a
// shipped one, with its own scenario files and world file, so that a user
// changes the scenario's numbers (the contact force, the elbow's height, a
// timeout) in files of their own instead of forking the shared ones.
//
// Which files are the scenario's: an imported model file whose folder F has a
// sibling app file F.json (models/sc0a/ beside models/sc0a.json) belongs to a
// scenario and is copied; everything else (right-arm/, platform/, common/, the
// robot descriptions) is shared and stays imported as it is. sc0b imports
// sc0a's folder too, so a task from sc0b gets copies of both.
//
// The new app sits beside SCENARIO as NAME.json, its files in NAME/ (a copied
// file from another scenario's folder is prefixed with that folder's name when
// its name is taken), and SCENARIO's world file is copied as NAME.world.json.
// The IRIs follow the files: each copied folder's IRI prefix is renamed to
// NAME's in every copied file and in the app. Nothing existing is overwritten,
// and the result is loaded before it is kept: on any error nothing is left.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <regex>
#include <set>

#include "cli/commands.hpp"
#include "support/io.hpp"
#include "support/paths.hpp"

namespace mospec::cli {
namespace {

namespace fs = std::filesystem;

struct NewFlags {
  std::string name, from;
  LoadFlags load;
};

// Every occurrence of `from` in `text` replaced by `to`.
std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// The IRI of the folder a file IRI is in: everything up to its last '/'.
std::string folder_iri(const std::string& iri) {
  const size_t slash = iri.rfind('/');
  return slash == std::string::npos ? std::string() : iri.substr(0, slash + 1);
}

// The app file a scenario's name or path means: an existing path as given,
// else models/NAME.json.
std::string scenario_app(const std::string& from) {
  if (fs::exists(from)) return from;
  const std::string shipped = "models/" + from + ".json";
  if (fs::exists(shipped)) return shipped;
  throw Error("new", "mospec new: no scenario '" + from + "': give an app file (e.g. " +
                         "models/sc0a.json) or the name of one in models/ (sc0a, sc0b, sc1, sc2)");
}

// The model tree a task's files may be read from, as the loader confines
// imports (docs/security.md): the scenario app's own directory, the tree its
// iri-map resolves against (--root, else the current directory) and the
// directories of --map. The files a scenario imports went through the
// loader's sandbox; the world file beside the app did not, so a planted
// symbolic link out of a shared bundle would copy a file of the user's into
// the new task.
struct Tree {
  std::vector<fs::path> roots;
  // The file's content when it lies inside a root once links are resolved.
  std::string read(const fs::path& file, std::string_view what) const {
    const fs::path canonical = canonical_path(file.string());
    for (const fs::path& root : roots) {
      if (is_within(canonical, root)) return read_file(canonical.string());
    }
    std::string where;
    for (const fs::path& root : roots) where += (where.empty() ? "" : ", ") + root.string();
    throw Error("new", "mospec new: the scenario's " + std::string(what) + " " +
                           escaped_bytes(file.string()) + " resolves to '" +
                           escaped_bytes(canonical.string()) + "', outside the model tree (" +
                           escaped_bytes(where) +
                           "); nothing was created (copy the file into the scenario's directory "
                           "if you trust it)");
  }
};

// The removal of whatever a failed `new` created.
class Undo {
 public:
  void add(fs::path p) { made_.push_back(std::move(p)); }
  void keep() { made_.clear(); }
  ~Undo() {
    std::error_code ec;
    for (auto it = made_.rbegin(); it != made_.rend(); ++it) fs::remove_all(*it, ec);
  }

 private:
  std::vector<fs::path> made_;
};

int run_new(const NewFlags& flags) {
  static const std::regex kName("[a-z][a-z0-9-]{0,62}");
  if (!std::regex_match(flags.name, kName)) {
    throw Error("new", "mospec new: '" + flags.name +
                           "' is not a task name: use lower-case letters, digits and '-', "
                           "starting with a letter (at most 63), e.g. push-harder");
  }
  const std::string source = scenario_app(flags.from);
  const app::LoadedModel model = app::load({source}, flags.load.to_options());
  if (model.apps().empty())
    throw Error("new", "mospec new: '" + source + "' is not an app file (it imports nothing)");
  const fs::path app_path(source);
  const fs::path dir = app_path.parent_path();
  Tree tree{{canonical_path(dir.empty() ? "." : dir.string()),
             canonical_path(flags.load.root.empty() ? "." : flags.load.root)}};
  for (const std::string& map : flags.load.maps) {
    const size_t eq = map.find('=');
    if (eq != std::string::npos) tree.roots.push_back(canonical_path(map.substr(eq + 1)));
  }
  const std::string own_folder = app_path.stem().string();
  const fs::path target_app = dir / (flags.name + ".json");
  const fs::path target_world = dir / (flags.name + ".world.json");
  const fs::path target_dir = dir / flags.name;
  for (const fs::path& p : {target_app, target_world, target_dir}) {
    std::error_code ec;
    if (fs::exists(fs::symlink_status(p, ec)))
      throw Error("new", "mospec new: " + p.string() +
                             " exists; choose another name (nothing is overwritten)");
  }

  // The scenario files, in import order, and their new names: the app's own
  // folder's keep theirs, another scenario's are prefixed with its folder.
  struct Copy {
    std::string iri, path, new_name;
    bool own = false;
  };
  std::vector<Copy> copies;
  std::set<std::string> names;
  for (const std::string& iri : model.apps().front().imports) {
    const auto f = std::find_if(model.model_files().begin(), model.model_files().end(),
                                [&](const app::ModelFile& m) { return m.iri == iri; });
    if (f == model.model_files().end()) continue;
    const fs::path path(f->path);
    const fs::path folder = path.parent_path();
    if (!fs::exists(folder.parent_path() / (folder.filename().string() + ".json"))) continue;
    Copy c{iri, f->path, path.filename().string(),
           fs::equivalent(folder, (dir.empty() ? fs::path(".") : dir) / own_folder)};
    if (!c.own) c.new_name = folder.filename().string() + "-" + c.new_name;
    if (!names.insert(c.new_name).second) {
      throw Error("new", "mospec new: two scenario files of '" + source + "' would both be " +
                             flags.name + "/" + c.new_name + "; copy them by hand");
    }
    copies.push_back(std::move(c));
  }
  if (copies.empty()) {
    throw Error("new", "mospec new: '" + source +
                           "' imports no scenario files (files in a folder beside an app file of "
                           "the same name, like models/sc0a/ beside models/sc0a.json); nothing "
                           "to copy");
  }
  // The IRIs: the app's own folder (models/sc0a/) becomes NAME's
  // (models/push-harder/), and the app's IRI by convention that folder's
  // without the slash.
  std::string own_iri;  // the own folder's IRI
  for (const Copy& c : copies) {
    if (c.own) own_iri = folder_iri(c.iri);
  }
  if (own_iri.empty()) {
    throw Error("new", "mospec new: '" + source + "' imports no files from its own folder " +
                           (dir / own_folder).string() +
                           "/, so there is no folder IRI to name the new task's after");
  }
  const std::string new_folder =
      folder_iri(own_iri.substr(0, own_iri.size() - 1)) + flags.name + "/";
  const std::string app_iri = own_iri.substr(0, own_iri.size() - 1);
  const std::string new_app_iri = new_folder.substr(0, new_folder.size() - 1);
  // IRIs under a copied folder move to NAME's folder (its own folder's files
  // keep their names; another scenario's files are prefixed when renamed).
  auto new_iri = [&](const Copy& c) { return new_folder + c.new_name; };
  auto rename_iris = [&](std::string text) {
    for (const Copy& c : copies)
      text = replace_all(text, '"' + c.iri + '"', '"' + new_iri(c) + '"');
    text = replace_all(text, own_iri, new_folder);
    return replace_all(text, '"' + app_iri + '"', '"' + new_app_iri + '"');
  };

  Undo undo;
  fs::create_directory(target_dir);
  undo.add(target_dir);
  for (const Copy& c : copies)
    write_output((target_dir / c.new_name).string(),
                 rename_iris(tree.read(c.path, "imported file")));
  const std::string app_text = rename_iris(read_file(source));
  fs::path world = app_path;
  world.replace_extension(".world.json");
  std::error_code ec;
  const bool has_world = fs::exists(fs::symlink_status(world, ec));
  if (has_world) {
    write_output(target_world.string(), tree.read(world, "world file"));
    undo.add(target_world);
  }
  write_output(target_app.string(), app_text);
  undo.add(target_app);

  // The new task must load as it is, or nothing of it is kept.
  try {
    const app::LoadedModel check = app::load({target_app.string()}, flags.load.to_options());
    for (const Copy& c : copies) {
      const auto f = std::find_if(check.model_files().begin(), check.model_files().end(),
                                  [&](const app::ModelFile& m) { return m.iri == new_iri(c); });
      if (f == check.model_files().end() ||
          !fs::equivalent(fs::path(f->path), target_dir / c.new_name)) {
        throw Error("new", "the app's iri-map does not resolve '" + new_iri(c) + "' to " +
                               (target_dir / c.new_name).string());
      }
    }
  } catch (const Error& e) {
    throw Error("new", "mospec new: the copy of '" + source +
                           "' does not load, so nothing was "
                           "created: " +
                           e.what());
  }
  undo.keep();

  std::cout << "mospec: created " << target_app.string() << " from " << source << ":\n";
  for (const Copy& c : copies) {
    std::cout << "  " << (target_dir / c.new_name).string() << "  (from " << c.path << ")\n";
  }
  if (has_world)
    std::cout << "  " << target_world.string() << "  (from " << world.string() << ")\n";
  std::cout << "Its numbers (references, thresholds, timeouts) are in those files; the shared "
               "files it imports (arms, platform, clock) stay shared.\nNext:\n  mospec validate "
            << target_app.string() << "\n  mospec run " << target_app.string() << " --sim\n";
  return kExitOk;
}

}  // namespace

Action add_new_command(CLI::App& app) {
  auto flags = std::make_shared<NewFlags>();
  CLI::App* cmd = app.add_subcommand(
      "new",
      "Start a task of your own from a shipped scenario: copy its scenario files (not the "
      "shared arm and platform files) and its world file beside it as NAME.json, NAME/ and "
      "NAME.world.json, with the IRIs renamed, ready to edit");
  cmd->add_option("NAME", flags->name, "The new task's name (e.g. push-harder)")->required();
  cmd->add_option("--from", flags->from,
                  "The scenario to start from: an app file, or a name in models/ (sc0a, sc0b, "
                  "sc1, sc2)")
      ->required()
      ->type_name("SCENARIO");
  flags->load.add_to(*cmd, /*strict=*/false, /*validates=*/false);
  return [flags]() { return run_new(*flags); };
}

}  // namespace mospec::cli
