#include "app/app.hpp"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory_resource>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include "jsonld/context.hpp"
#include "jsonld/expand.hpp"
#include "jsonld/to_rdf.hpp"
#include "rdf/iri.hpp"
#include "support/arena.hpp"
#include "support/paths.hpp"
#include "vocab/metamodels.hpp"
#include "vocab/w3c.hpp"

namespace mospec::app {
namespace fs = std::filesystem;

namespace {

// The first block of a document's expansion arena, a buffer from a pool that
// the documents of a load reuse (one per document being expanded or waiting
// for its turn); a larger document's arena grows from it, and the buffer is
// then enlarged (up to kMaxExpandedBufferBytes) for the documents after it.
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

// A first-block buffer for a document's expansion arena (see
// kExpandedArenaBytes).
struct ExpandBuffer {
  std::unique_ptr<std::byte[]> data;  // not initialised: an arena only hands it out
  size_t bytes = 0;
};

// One document read, parsed and expanded, waiting for its turn to become
// quads. The imports of an app are prepared on two threads, ahead of their
// turn; turning them into quads (and everything that depends on the order of
// the files) stays on the loading thread, in the order the app lists them.
struct Prepared {
  // Each of the two steps, reading (and parsing) and expanding, is claimed by
  // one thread, which marks it done.
  enum Step : int { kWaiting, kBusy, kDone };
  std::string iri;  // the IRI imported
  SourceLoc imported_at;
  std::atomic<int> read{kWaiting};
  std::atomic<int> expanded{kWaiting};
  jsonld::RemoteDocument doc;
  std::string path;
  std::exception_ptr load_error;    // reading or parsing it failed
  std::exception_ptr expand_error;  // expanding it failed
  ExpandBuffer buffer;
  std::optional<Arena> arena;  // holds `tree`, on `buffer` first
  const json::Value* tree = nullptr;
  bool mentions_app_property = false;
  DiagnosticSink diagnostics;  // what expanding it reported
  // Prepared again by the loading thread while the helper, holding this one,
  // was too slow (Helper::wait_for); used instead of it.
  std::unique_ptr<Prepared> stand_in;
};

// A document prepared ahead of its turn no longer means what it would at its
// turn: an import that is itself an app can map IRIs (and load files) that
// change what later imports resolve to. The load is then redone one document
// after another.
struct PreparedAheadInvalid {};

class Loader {
  const unsigned threads_;

 public:
  Loader(const LoadOptions& options, unsigned threads, jsonld::MappedDocumentLoader& docs,
         rdf::Dataset& dataset, std::vector<ModelFile>& files, std::vector<AppInfo>& apps,
         DiagnosticSink& diagnostics)
      : threads_(threads),
        options_(options),
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
      // The secorolab extensions: mospec's own contexts of the ones it reads;
      // any other of their URLs names a file that is not there, refused at
      // the reference like an unknown comp-rob2b context.
      docs_.map_fallback(std::string(kSecorolabIri), builtin_metamodels_dir() + "/secorolab");
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
    Prepared p;
    p.doc = docs_.load_file(path, iri);
    p.path = path;
    expand(p);
    load_document(p);
  }

 private:
  // Reads and parses p.iri (any thread).
  void read(Prepared& p) {
    try {
      p.doc = docs_.load(p.iri, p.imported_at, /*for_context=*/false);
      p.path = docs_.resolve(p.iri);
    } catch (...) {
      p.load_error = std::current_exception();
    }
  }

  // Expands p.doc into p's arena (any thread).
  void expand(Prepared& p) {
    if (p.load_error) return;
    try {
      jsonld::Options opts = document_options(p.doc);
      opts.diagnostics = &p.diagnostics;
      opts.property_prefix_seen = &p.mentions_app_property;
      p.buffer = take_buffer();
      Arena& arena = p.arena.emplace(p.buffer.data.get(), p.buffer.bytes);
      // Built in the arena and dropped with it, never destroyed value by
      // value: all of it is in the arena (json::lives_in; the expand
      // conformance runner checks that for every test it passes).
      p.tree = new (arena.allocate(sizeof(json::Value), alignof(json::Value)))
          json::Value(jsonld::expand(*p.doc.document, opts, &arena));
      assert(json::lives_in(*p.tree, &arena));
    } catch (...) {
      p.expand_error = std::current_exception();
    }
  }

  jsonld::Options document_options(const jsonld::RemoteDocument& doc) {
    jsonld::Options opts;
    opts.base = doc.document_url;
    opts.loader = &docs_;
    opts.diagnostics = &diagnostics_;
    opts.context_cache = context_cache_;  // remote contexts are processed once per load
    // Only a document with a property in the application namespace can hold
    // the app:import quads that make it an app.
    opts.property_prefix = kAppNs;
    return opts;
  }

  // Turns a prepared document into quads (the loading thread, in order).
  void load_document(Prepared& p) {
    for (const Diagnostic& d : p.diagnostics.diagnostics()) diagnostics_.report(d);
    if (p.expand_error) {
      give_back(p);
      std::rethrow_exception(p.expand_error);
    }
    const jsonld::RemoteDocument& doc = p.doc;
    jsonld::Options opts = document_options(doc);
    ModelFile file{doc.document_url, p.path, doc.file_id, false, p.imported_at};
    std::optional<rdf::Dataset> local;  // an app's own quads
    if (!p.mentions_app_property) {
      // No app:* property, so not an app: its quads go straight into the
      // model's dataset, default graph renamed to the file's graph (what
      // copy_into_file_graph does, without a dataset per file).
      opts.default_graph = doc.document_url;
      jsonld::to_rdf(*p.tree, dataset_, opts, &*p.arena);
    } else {
      jsonld::to_rdf(*p.tree, local.emplace(), opts, &*p.arena);
    }
    give_back(p);
    if (!p.mentions_app_property) {
      files_.push_back(file);
      return;
    }

    const rdf::TermTable& lt = local->terms();
    rdf::TermId import_p = lt.find_iri(app_term("import"));
    file.is_app = !import_p.is_any() &&
                  !local->match(rdf::TermId::any(), import_p, rdf::TermId::any()).empty();
    copy_into_file_graph(*local, doc.document_url);
    files_.push_back(file);
    if (file.is_app) {
      // Read ahead of it, later imports of an outer app may now resolve
      // differently (see PreparedAheadInvalid).
      if (preparing_ahead_ > 0) throw PreparedAheadInvalid{};
      load_app(*local, p.path);
    }
  }

  // The expansion's buffer back to the pool, once the tree in it is gone;
  // enlarged (up to kMaxExpandedBufferBytes) when the document needed more.
  void give_back(Prepared& p) {
    const size_t grown = p.arena ? p.arena->allocated_bytes() : 0;
    p.tree = nullptr;
    p.arena.reset();
    if (!p.buffer.data) return;
    if (grown != 0) {
      const size_t bytes = std::min(kMaxExpandedBufferBytes, p.buffer.bytes + grown);
      p.buffer.data.reset(new std::byte[bytes]);
      p.buffer.bytes = bytes;
    }
    std::lock_guard lock(pool_mutex_);
    buffers_.push_back(std::move(p.buffer));
  }

  ExpandBuffer take_buffer() {
    {
      std::lock_guard lock(pool_mutex_);
      if (!buffers_.empty()) {
        ExpandBuffer b = std::move(buffers_.back());
        buffers_.pop_back();
        return b;
      }
    }
    return ExpandBuffer{std::unique_ptr<std::byte[]>(new std::byte[kExpandedArenaBytes]),
                        kExpandedArenaBytes};
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
    if (rdf::TermId drop_p = lt.find_iri(vocab::term(vocab::mospec_app::ns, "drop"));
        !drop_p.is_any()) {
      for (uint32_t qi : local.match(any, drop_p, any))
        app.drops.push_back({std::string(lt[local.quads()[qi].object].value), local.location(qi)});
    }

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
    load_imports(unique, unique_locs, missing);
    if (!missing.empty()) throw with_dangling_references(missing);
  }

  // Loads each import once, in order. With threads_ > 1 a helper thread
  // prepares (reads, parses, expands) the imports ahead of their turn while
  // this thread prepares too and turns them into quads in order; the result is
  // the same as one document after another.
  void load_imports(const std::vector<std::string>& iris, const std::vector<SourceLoc>& at,
                    std::vector<Error>& missing) {
    std::vector<std::unique_ptr<Prepared>> jobs;
    for (size_t i = 0; i < iris.size(); ++i) {
      if (loaded_.contains(iris[i])) continue;  // duplicates load once
      auto& p = *jobs.emplace_back(std::make_unique<Prepared>());
      p.iri = iris[i];
      p.imported_at = at[i];
    }
    const bool ahead = threads_ > 1 && jobs.size() > 1;
    if (ahead) {
      // Files are numbered in the order the app lists them, as one after
      // another would (reports sort by file), whichever thread reads them.
      for (const auto& p : jobs) {
        if (std::string mapped = docs_.resolve(p->iri); !mapped.empty()) {
          docs_.files().add(std::move(mapped));
        }
      }
    }
    Helper helper(*this, jobs, ahead);
    for (size_t i = 0; i < jobs.size(); ++i) {
      // (Loaded meanwhile by an import that is an app, one after another.)
      if (!loaded_.insert(jobs[i]->iri).second) continue;
      Prepared& p = helper.wait_for(i);
      try {
        if (p.load_error) std::rethrow_exception(p.load_error);
        load_document(p);
      } catch (const Error& e) {
        if (e.code() != "loading document failed") throw;
        missing.push_back(e);
      }
    }
  }

  // Prepares jobs on one more thread, which reads and parses every one first
  // (so that it has work while the first expansion processes the remote
  // contexts every document shares) and then expands them in order, at most
  // kExpandAhead past the one its owner is at (each expanded tree is held
  // until its turn). The owner waits for each job in turn, meanwhile taking
  // unclaimed steps itself.
  class Helper {
   public:
    static constexpr size_t kExpandAhead = 8;

    Helper(Loader& loader, std::vector<std::unique_ptr<Prepared>>& jobs, bool start)
        : loader_(loader), jobs_(jobs) {
      if (!start) return;
      try {
        thread_ = std::thread([this] {
          while (help()) {
          }
        });
      } catch (const std::system_error&) {
        return;  // no thread to be had: the owner prepares every job
      }
      ++loader_.preparing_ahead_;
    }
    ~Helper() {
      if (!thread_.joinable()) return;
      {
        std::lock_guard lock(mutex_);
        stop_.store(true, std::memory_order_relaxed);
      }
      changed_.notify_all();
      thread_.join();
      --loader_.preparing_ahead_;
    }
    Helper(const Helper&) = delete;
    Helper& operator=(const Helper&) = delete;

    // Returns jobs[i] read and expanded (or a stand-in for it), the jobs
    // before it having been taken. While the helper prepares it, the owner
    // expands a job of its own from the end of the window (the helper works
    // from the front, in the order the owner needs them); with nothing else
    // to do it waits, but at most LoadOptions::helper_patience: a helper
    // whose core was taken away must not hold the load up, so the owner then
    // prepares the job itself as well and the helper's copy is dropped.
    Prepared& wait_for(size_t i) {
      {
        std::lock_guard lock(mutex_);
        current_ = i;
      }
      changed_.notify_all();
      Prepared& p = *jobs_[i];
      if (claim(p.read)) run_read(p);
      while (!done(p.expanded)) {
        if (done(p.read) && claim(p.expanded)) {
          run_expand(p);
          break;
        }
        if (Prepared* other = claim_other(i)) {
          run_expand(*other);
          continue;
        }
        std::unique_lock lock(mutex_);
        if (!changed_.wait_for(lock, loader_.options_.helper_patience, [&p] {
              return done(p.expanded) || (done(p.read) && p.expanded.load() == Prepared::kWaiting);
            })) {
          lock.unlock();
          p.stand_in = std::make_unique<Prepared>();
          Prepared& s = *p.stand_in;
          s.iri = p.iri;
          s.imported_at = p.imported_at;
          loader_.read(s);
          loader_.expand(s);
          return s;
        }
      }
      return p;
    }

   private:
    static bool claim(std::atomic<int>& step) {
      int waiting = Prepared::kWaiting;
      return step.compare_exchange_strong(waiting, Prepared::kBusy);
    }
    static bool done(const std::atomic<int>& step) {
      return step.load(std::memory_order_acquire) == Prepared::kDone;
    }
    // An unclaimed expansion in the window after jobs[i], from its end, read
    // here if need be (not one the helper is reading: that would be waited for).
    Prepared* claim_other(size_t i) {
      for (size_t k = std::min(jobs_.size(), i + 1 + kExpandAhead); k-- > i + 1;) {
        Prepared& q = *jobs_[k];
        if (q.expanded.load() != Prepared::kWaiting) continue;
        if (!done(q.read)) {
          if (!claim(q.read)) continue;
          run_read(q);
        }
        if (claim(q.expanded)) return &q;
      }
      return nullptr;
    }
    void mark_done(std::atomic<int>& step) {
      {
        std::lock_guard lock(mutex_);
        step.store(Prepared::kDone, std::memory_order_release);
      }
      changed_.notify_all();
    }
    void run_read(Prepared& p) {
      loader_.read(p);
      mark_done(p.read);
    }
    void run_expand(Prepared& p) {
      loader_.expand(p);
      mark_done(p.expanded);
    }
    // The helper thread's step: reads every job, then expands within the
    // window. False once there is nothing left (or it is told to stop).
    bool help() {
      for (; next_read_ < jobs_.size(); ++next_read_) {
        if (stop_.load(std::memory_order_relaxed)) return false;
        if (claim(jobs_[next_read_]->read)) {
          run_read(*jobs_[next_read_++]);
          return true;
        }
      }
      for (; next_expand_ < jobs_.size(); ++next_expand_) {
        {
          std::unique_lock lock(mutex_);
          changed_.wait(lock, [this] { return stop_ || next_expand_ <= current_ + kExpandAhead; });
          if (stop_) return false;
        }
        if (claim(jobs_[next_expand_]->expanded)) {
          Prepared& p = *jobs_[next_expand_++];
          wait_until_done(p.read);
          run_expand(p);
          return true;
        }
      }
      return false;
    }
    void wait_until_done(const std::atomic<int>& step) {
      if (done(step)) return;
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&step] { return done(step); });
    }

    Loader& loader_;
    std::vector<std::unique_ptr<Prepared>>& jobs_;
    size_t next_read_ = 0, next_expand_ = 0;  // the helper thread's own
    std::mutex mutex_;  // guards current_ (and stop_'s changes), pairs with changed_
    std::condition_variable changed_;
    size_t current_ = 0;  // the job the owner waits for or turns into quads
    std::atomic<bool> stop_{false};
    std::thread thread_;
  };

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
  int preparing_ahead_ = 0;  // Helpers running (an import that is an app ends them)
  std::mutex pool_mutex_;
  std::vector<ExpandBuffer> buffers_;  // see kExpandedArenaBytes
};

// "file:line:col" of each location, at most `max`, then "and N more".
std::string places(const LoadedModel& model, const std::vector<SourceLoc>& statements,
                   size_t max = 4) {
  std::vector<std::string> locs;  // a node's statements share its line: once each
  for (SourceLoc loc : statements) {
    std::string place = model.describe(loc);
    if (std::find(locs.begin(), locs.end(), place) == locs.end()) locs.push_back(std::move(place));
  }
  std::string out;
  for (size_t i = 0; i < locs.size() && i < max; ++i)
    out.append(i == 0 ? "" : ", ").append(locs[i]);
  if (locs.size() > max)
    out.append(" and ").append(std::to_string(locs.size() - max)).append(" more");
  return out;
}

// Leaves out what the apps drop: statements about the entity (and the blank
// nodes only they hold), and references to it. A drop that would cut an item
// out of an ordered list, or a class out of its instances, is refused: what
// remains would not be what any file says.
void apply_drops(LoadedModel& model) {
  rdf::Dataset& ds = model.dataset();
  rdf::TermTable& terms = ds.terms();
  const rdf::TermId any = rdf::TermId::any();
  const rdf::TermId drop_p = terms.find_iri(vocab::term(vocab::mospec_app::ns, "drop"));
  const rdf::TermId first_p = terms.find_iri(vocab::rdf::first);
  const rdf::TermId type_p = terms.find_iri(vocab::rdf::type);
  std::vector<uint32_t> gone;
  for (const AppInfo& app : model.apps()) {
    for (const Drop& d : app.drops) {
      const auto refuse = [&](const std::string& why) {
        throw Error("invalid-drop", "the app drops '" + d.iri + "', " + why,
                    model.files().path(d.at.file), d.at.line, d.at.column);
      };
      const rdf::TermId e = terms.find_iri(d.iri);
      std::vector<uint32_t> about = e.is_any() ? std::vector<uint32_t>{} : ds.match(e, any, any);
      std::vector<uint32_t> refs;
      if (!e.is_any()) {
        for (uint32_t i : ds.match(any, any, e))
          if (ds.quads()[i].predicate != drop_p) refs.push_back(i);
      }
      if (about.empty() && refs.empty()) {
        const std::string nearest = rdf::nearest_subject_iri(ds, d.iri);
        refuse("which no loaded file mentions" +
               (nearest.empty() ? std::string() : "; did you mean '" + nearest + "'?"));
      }
      for (uint32_t i : refs) {
        const rdf::Quad& q = ds.quads()[i];
        if (q.predicate == first_p || q.predicate == type_p)
          refuse(std::string("but ") + model.describe(ds.location(i)) +
                 (q.predicate == first_p ? " lists it in an ordered list, which cannot lose one "
                                           "item; drop the entity that holds the list"
                                         : " gives it as a class; only entities can be dropped"));
      }
      // The blank nodes (nested objects, lists) only its statements hold.
      std::vector<uint32_t> held = about;
      for (size_t k = 0; k < held.size(); ++k) {
        const rdf::TermId o = ds.quads()[held[k]].object;
        if (terms[o].kind != rdf::TermKind::Blank || ds.count(any, any, o) != 1) continue;
        for (uint32_t i : ds.match(o, any, any)) held.push_back(i);
      }
      std::vector<SourceLoc> stated, referenced;
      for (uint32_t i : about)
        if (ds.location(i).known()) stated.push_back(ds.location(i));
      for (uint32_t i : refs)
        if (ds.location(i).known()) referenced.push_back(ds.location(i));
      std::string what = "dropped '" + d.iri + "'";
      what.append(": ").append(std::to_string(about.size())).append(" statement(s) about it");
      if (!stated.empty()) what.append(" (").append(places(model, stated)).append(")");
      what.append(", ").append(std::to_string(refs.size())).append(" reference(s) to it");
      if (!referenced.empty()) what.append(" (").append(places(model, referenced)).append(")");
      model.diagnostics().report(
          located(Severity::Note, d.at, model.files(), "dropped", std::move(what)));
      gone.insert(gone.end(), held.begin(), held.end());
      gone.insert(gone.end(), refs.begin(), refs.end());
    }
  }
  if (!gone.empty()) ds.erase(gone);
}

}  // namespace

std::string builtin_metamodels_dir() {
  if (const char* env = std::getenv("MOSPEC_METAMODELS_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return MOSPEC_METAMODELS_DIR;
}

LoadedModel load(const std::vector<std::string>& inputs, const LoadOptions& options) {
  auto load_with = [&](unsigned threads) {
    LoadedModel model;
    Loader loader(options, threads, model.loader_, model.dataset_, model.files_, model.apps_,
                  model.diagnostics_);
    // The indexes are folded once, when every file is in.
    model.dataset_.set_auto_compact(false);
    for (const std::string& input : inputs) loader.load_input(input);
    model.dataset_.compact();
    model.dataset_.set_auto_compact(true);
    apply_drops(model);
    return model;
  };
  unsigned threads = options.threads;
  if (threads == 0) threads = std::clamp(std::thread::hardware_concurrency(), 1u, 2u);
  if (threads == 1) return load_with(1);
  try {
    return load_with(threads);
  } catch (const PreparedAheadInvalid&) {
    return load_with(1);
  }
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
