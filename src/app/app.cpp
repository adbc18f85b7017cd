#include "app/app.hpp"

#include <algorithm>
#include <cassert>
#include <cstdlib>
#include <filesystem>
#include <memory_resource>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "jsonld/context.hpp"
#include "jsonld/expand.hpp"
#include "jsonld/to_rdf.hpp"
#include "rdf/iri.hpp"
#include "support/arena.hpp"
#include "support/paths.hpp"
#include "vocab/w3c.hpp"

namespace mospec::app {
namespace fs = std::filesystem;

namespace {

// The first block of a document's expansion arena, one buffer reused by every
// document of a load; a larger document's arena grows from it, and the buffer
// is then enlarged (up to kMaxExpandedBufferBytes) for the documents after it.
constexpr size_t kExpandedArenaBytes = 32 * 1024;
constexpr size_t kMaxExpandedBufferBytes = 1024 * 1024;

std::string app_term(std::string_view local) {
  return std::string(kAppNs) + std::string(local);
}

// The IRI a local file is known by: the inverse of an IRI mapping when one
// covers it (so relative references inside it resolve as they would on the
// web), otherwise its file: URL.
std::string iri_for_path(const jsonld::MappedDocumentLoader& docs,
                         const std::vector<std::pair<std::string, std::string>>& maps,
                         const std::string& path) {
  const std::string abs = docs.canonical(path);
  for (const auto& [prefix, dir] : maps) {
    std::string d = docs.canonical(dir);
    if (!d.empty() && d.back() != '/') d += '/';
    if (abs.starts_with(d)) return prefix + abs.substr(d.size());
  }
  return "file://" + abs;
}

std::string join_root(const LoadOptions& options, const std::string& path) {
  if (!options.root || fs::path(path).is_absolute()) return path;
  return (fs::path(*options.root) / path).generic_string();
}

class Loader {
 public:
  Loader(const LoadOptions& options, jsonld::MappedDocumentLoader& docs, rdf::Dataset& dataset,
         std::vector<ModelFile>& files, std::vector<AppInfo>& apps, DiagnosticSink& diagnostics)
      : options_(options),
        docs_(docs),
        dataset_(dataset),
        files_(files),
        apps_(apps),
        diagnostics_(diagnostics) {
    for (const auto& [prefix, dir] : options.maps) {
      docs_.map(prefix, dir);
      maps_.emplace_back(prefix, dir);
    }
    if (options.builtin_metamodels) {
      docs_.map_fallback(std::string(kMetamodelsIri), builtin_metamodels_dir());
    }
    // The model tree is a sandbox: references load only from the directories
    // above, --root, the app's iri-map and the inputs' own directories.
    docs_.confine();
    if (options.root) docs_.allow(*options.root);
  }

  void load_input(const std::string& path) {
    docs_.allow(fs::path(path).has_parent_path() ? fs::path(path).parent_path().string() : ".");
    std::string iri = iri_for_path(docs_, maps_, path);
    if (!loaded_.insert(iri).second) return;
    jsonld::RemoteDocument doc = docs_.load_file(path, iri);
    load_document(doc, path, SourceLoc{});
  }

 private:
  void load_import(const std::string& iri, SourceLoc imported_at) {
    if (!loaded_.insert(iri).second) return;  // duplicates load once
    jsonld::RemoteDocument doc = docs_.load(iri, imported_at, /*for_context=*/false);
    load_document(doc, docs_.resolve(iri), imported_at);
  }

  void load_document(const jsonld::RemoteDocument& doc, const std::string& path,
                     SourceLoc imported_at) {
    jsonld::Options opts;
    opts.base = doc.document_url;
    opts.loader = &docs_;
    opts.diagnostics = &diagnostics_;
    opts.context_cache = context_cache_;  // remote contexts are processed once per load
    // Only a document with a property in the application namespace can hold
    // the app:import quads that make it an app.
    bool mentions_app_property = false;
    opts.property_prefix = kAppNs;
    opts.property_prefix_seen = &mentions_app_property;
    ModelFile file{doc.document_url, path, doc.file_id, false, imported_at};
    std::optional<rdf::Dataset> local;  // an app's own quads
    size_t grown = 0;                   // what the expansion needed beyond the buffer
    {
      // The expanded tree is walked once by toRdf and dropped: it lives in an
      // arena for this document, on the load's reused buffer. (Nothing below
      // loads another document while it lives.)
      if (!expand_buffer_) reserve_expand_buffer(kExpandedArenaBytes);
      Arena arena(expand_buffer_.get(), expand_buffer_bytes_);
      // Built in the arena and dropped with it, never destroyed value by
      // value: all of it is in the arena (json::lives_in; the expand
      // conformance runner checks that for every test it passes).
      const json::Value& expanded = *new (arena.allocate(sizeof(json::Value), alignof(json::Value)))
                                        json::Value(jsonld::expand(*doc.document, opts, &arena));
      assert(json::lives_in(expanded, &arena));
      if (!mentions_app_property) {
        // No app:* property, so not an app: its quads go straight into the
        // model's dataset, default graph renamed to the file's graph (what
        // copy_into_file_graph does, without a dataset per file).
        opts.default_graph = doc.document_url;
        jsonld::to_rdf(expanded, dataset_, opts, &arena);
      } else {
        jsonld::to_rdf(expanded, local.emplace(), opts, &arena);
      }
      grown = arena.allocated_bytes();
    }
    // (Only once the tree in it is gone.)
    if (grown != 0) {
      reserve_expand_buffer(std::min(kMaxExpandedBufferBytes, expand_buffer_bytes_ + grown));
    }
    if (!mentions_app_property) {
      files_.push_back(file);
      return;
    }

    const rdf::TermTable& lt = local->terms();
    rdf::TermId import_p = lt.find_iri(app_term("import"));
    file.is_app = !import_p.is_any() &&
                  !local->match(rdf::TermId::any(), import_p, rdf::TermId::any()).empty();
    copy_into_file_graph(*local, doc.document_url);
    files_.push_back(file);
    if (file.is_app) load_app(*local, path);
  }

  // Copies quads into the model's dataset: blank nodes renamed fresh (files
  // never share one), default-graph quads moved to the file's own graph.
  void copy_into_file_graph(const rdf::Dataset& local, const std::string& file_iri) {
    rdf::TermTable& t = dataset_.terms();
    const rdf::TermTable& lt = local.terms();
    std::unordered_map<uint32_t, rdf::TermId> blanks;
    rdf::TermId file_graph = t.iri(file_iri);
    auto copy = [&](rdf::TermId id) -> rdf::TermId {
      const rdf::Term& term = lt[id];
      switch (term.kind) {
        case rdf::TermKind::DefaultGraph:
          return file_graph;
        case rdf::TermKind::Iri:
          return t.iri(term.value);
        case rdf::TermKind::Blank: {
          auto [it, fresh] = blanks.try_emplace(id.index);
          if (fresh) it->second = t.fresh_blank();
          return it->second;
        }
        case rdf::TermKind::Literal:
          return t.literal(term.value, t.iri(lt[term.datatype].value), term.language,
                           term.direction);
      }
      return file_graph;
    };
    auto quads = local.quads();
    for (size_t i = 0; i < quads.size(); ++i) {
      const rdf::Quad& q = quads[i];
      dataset_.add({copy(q.subject), copy(q.predicate), copy(q.object), copy(q.graph)},
                   local.location(i));
    }
  }

  void load_app(const rdf::Dataset& local, const std::string& path) {
    const rdf::TermTable& lt = local.terms();
    auto any = rdf::TermId::any();
    AppInfo app;
    app.file = path;

    // iri-map first: the imports resolve through it.
    rdf::TermId map_p = lt.find_iri(app_term("iri-map"));
    rdf::TermId path_p = lt.find_iri(app_term("path"));
    if (!map_p.is_any()) {
      for (uint32_t qi : local.match(any, map_p, any)) {
        const rdf::Quad& q = local.quads()[qi];
        const rdf::Term& prefix = lt[q.object];
        if (prefix.kind != rdf::TermKind::Iri || path_p.is_any()) continue;
        for (uint32_t pi : local.match(q.object, path_p, any)) {
          std::string dir = join_root(options_, std::string(lt[local.quads()[pi].object].value));
          check_iri_map_dir(dir, local.location(pi), std::string(prefix.value));
          docs_.map(std::string(prefix.value), dir);
          maps_.emplace_back(std::string(prefix.value), dir);
          app.iri_map.emplace_back(std::string(prefix.value), dir);
        }
      }
    }
    auto objects = [&](std::string_view local_name, std::vector<std::string>& into,
                       std::vector<SourceLoc>* locs) {
      rdf::TermId p = lt.find_iri(app_term(local_name));
      if (p.is_any()) return;
      for (uint32_t qi : local.match(any, p, any)) {
        const rdf::Term& o = lt[local.quads()[qi].object];
        into.emplace_back(o.value);
        if (locs) locs->push_back(local.location(qi));
      }
    };
    std::vector<SourceLoc> import_locs;
    objects("import", app.imports, &import_locs);
    objects("constraints", app.constraints, nullptr);

    // Duplicates load once; keep the first mention.
    std::vector<std::string> unique;
    std::vector<SourceLoc> unique_locs;
    std::unordered_set<std::string> seen;
    for (size_t i = 0; i < app.imports.size(); ++i) {
      if (seen.insert(app.imports[i]).second) {
        unique.push_back(app.imports[i]);
        unique_locs.push_back(import_locs[i]);
      }
    }
    app.imports = unique;
    apps_.push_back(app);
    // A missing import does not stop the others from loading, so the error can
    // name what the rest of the model points at in it.
    std::vector<Error> missing;
    for (size_t i = 0; i < unique.size(); ++i) {
      try {
        load_import(unique[i], unique_locs[i]);
      } catch (const Error& e) {
        if (e.code() != "loading document failed") throw;
        missing.push_back(e);
      }
    }
    if (!missing.empty()) throw with_dangling_references(missing);
  }

  // An app's iri-map may only name directories inside the tree its relative
  // paths resolve against (--root, else the current directory): an untrusted
  // app must not map an IRI onto /etc or the user's home.
  void check_iri_map_dir(const std::string& dir, SourceLoc at, const std::string& prefix) const {
    const fs::path base = docs_.canonical(options_.root.value_or("."));
    const fs::path target = docs_.canonical(dir);
    bool inside = is_within(target, base);
    for (char c : dir) inside = inside && static_cast<unsigned char>(c) >= 0x20 && c != 0x7f;
    if (inside) return;
    std::string message =
        "iri-map entry <" + prefix + "> names the directory '" + escaped_bytes(target.string());
    message += "', outside the model tree '" + base.string() + "' (" +
               (options_.root ? "--root" : "the current directory; pass --root DIR to change it") +
               "); an app may only map IRIs into its own tree (pass --root DIR naming a tree "
               "that holds it, if you trust it)";
    throw Error("invalid iri-map", message, docs_.files().path(at.file), at.line, at.column);
  }

  // The first missing import's error, extended with the references the loaded
  // files make to model entities (IRIs under the app's iri-map, outside the
  // metamodels) that no loaded file describes: what the missing files held.
  Error with_dangling_references(const std::vector<Error>& missing) const {
    const rdf::TermTable& t = dataset_.terms();
    std::unordered_set<uint32_t> described;
    for (const rdf::Quad& q : dataset_.quads()) described.insert(q.subject.index);
    const rdf::TermId type = t.find_iri(vocab::rdf::type);
    std::unordered_set<uint32_t> app_files;  // their import lists are not references
    for (const ModelFile& f : files_)
      if (f.is_app) app_files.insert(f.file_id);
    std::vector<std::string> dangling;
    std::unordered_set<uint32_t> seen;
    for (size_t i = 0; i < dataset_.size(); ++i) {
      if (app_files.count(dataset_.location(i).file)) continue;
      const rdf::Quad& q = dataset_.quads()[i];
      const rdf::Term& o = t[q.object];
      if (o.kind != rdf::TermKind::Iri || q.predicate == type || described.count(q.object.index) ||
          o.value.starts_with(kMetamodelsIri) || !seen.insert(q.object.index).second) {
        continue;
      }
      bool in_model_namespace = false;
      for (const auto& [prefix, dir] : maps_) in_model_namespace |= o.value.starts_with(prefix);
      if (!in_model_namespace) continue;
      const SourceLoc at = dataset_.location(i);
      std::string entry = "<";
      entry.append(o.value).append(">");
      if (at.known()) {
        entry.append(" (").append(docs_.files().path(at.file)).append(":");
        entry.append(std::to_string(at.line)).append(")");
      }
      dangling.push_back(std::move(entry));
    }
    const Diagnostic& first = missing.front().diagnostic();
    std::string message = first.message;
    if (missing.size() > 1) {
      message.append(" (and ").append(std::to_string(missing.size() - 1));
      message.append(" more missing import(s))");
    }
    if (dangling.empty()) {
      message += "; no loaded file refers to what it would define";
    } else {
      message.append("; ").append(std::to_string(dangling.size()));
      message += " reference(s) now dangle: ";
      const size_t shown = std::min<size_t>(dangling.size(), 10);
      for (size_t k = 0; k < shown; ++k) message.append(k ? ", " : "").append(dangling[k]);
      if (shown < dangling.size()) message += ", ...";
    }
    return Error(missing.front().code(), message, first.file, first.line, first.column);
  }

  const LoadOptions& options_;
  jsonld::MappedDocumentLoader& docs_;
  rdf::Dataset& dataset_;
  std::vector<ModelFile>& files_;
  std::vector<AppInfo>& apps_;
  DiagnosticSink& diagnostics_;
  std::vector<std::pair<std::string, std::string>> maps_;
  std::unordered_set<std::string> loaded_;
  std::shared_ptr<jsonld::ContextCache> context_cache_ = std::make_shared<jsonld::ContextCache>();
  // See kExpandedArenaBytes. Not initialised: an arena only hands it out.
  std::unique_ptr<std::byte[]> expand_buffer_;
  size_t expand_buffer_bytes_ = 0;
  void reserve_expand_buffer(size_t bytes) {
    expand_buffer_.reset(new std::byte[bytes]);
    expand_buffer_bytes_ = bytes;
  }
};

}  // namespace

std::string builtin_metamodels_dir() {
  if (const char* env = std::getenv("MOSPEC_METAMODELS_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return MOSPEC_METAMODELS_DIR;
}

LoadedModel load(const std::vector<std::string>& inputs, const LoadOptions& options) {
  LoadedModel model;
  Loader loader(options, model.loader_, model.dataset_, model.files_, model.apps_,
                model.diagnostics_);
  // The indexes are folded once, when every file is in.
  model.dataset_.set_auto_compact(false);
  for (const std::string& input : inputs) loader.load_input(input);
  model.dataset_.compact();
  model.dataset_.set_auto_compact(true);
  return model;
}

std::optional<SourceLoc> LoadedModel::where(rdf::TermId subject) const {
  auto hits = dataset_.match(subject, rdf::TermId::any(), rdf::TermId::any());
  for (uint32_t i : hits) {
    SourceLoc loc = dataset_.location(i);
    if (loc.known()) return loc;
  }
  return std::nullopt;
}

std::string LoadedModel::describe(SourceLoc loc) const {
  std::string out = files().path(loc.file);
  if (loc.line != 0) {
    out.append(":").append(std::to_string(loc.line));
    out.append(":").append(std::to_string(loc.column));
  }
  return out;
}

}  // namespace mospec::app
