// Offline document loading for JSON-LD: IRIs map to local directories, the
// network is never used, and every document is read and parsed once per run.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "json/json.hpp"
#include "support/canonical_paths.hpp"
#include "support/diagnostics.hpp"

namespace mospec::jsonld {

struct RemoteDocument {
  std::string document_url;  // the IRI it was loaded as (after any redirect)
  std::string content_type;  // "application/ld+json" unless known otherwise
  std::string context_url;   // from an HTTP Link header, if the loader models one
  std::shared_ptr<const json::Value> document;
  uint32_t file_id = 0;  // id in the loader's SourceFiles
};

class DocumentLoader {
 public:
  DocumentLoader() = default;
  virtual ~DocumentLoader() = default;
  // Loads `iri` (absolute). `referenced_from` is where the reference was written,
  // for error messages. Errors throw mospec::Error with code
  // "loading document failed" (or "loading remote context failed" when
  // `for_context` is set), naming the IRI and the referencing file:line.
  virtual RemoteDocument load(std::string_view iri, SourceLoc referenced_from,
                              bool for_context) = 0;
  SourceFiles& files() { return files_; }
  const SourceFiles& files() const { return files_; }

 protected:
  DocumentLoader(DocumentLoader&&) noexcept = default;
  DocumentLoader& operator=(DocumentLoader&&) noexcept = default;
  SourceFiles files_;
};

// Maps IRI prefixes to local directories (longest prefix wins) and plain file
// paths to themselves. Parsed documents are cached by absolute path.
//
// Thread-safe: the documents of a load are read, parsed and expanded on more
// than one thread. Two threads that miss the cache for the same file both
// parse it and the first to finish is kept (documents_read() counts it once).
//
// Confined (confine()), it is a sandbox for untrusted models: a document loaded
// by reference (load(), resolve_for_loading()) must lie inside one of the
// directories given to map(), map_fallback() or allow(), checked after
// percent-decoding, `..` and symbolic links are resolved (by whole path
// components, so /tree2 is not inside /tree). IRIs with control characters
// (U+0000-U+001F, U+007F, written raw or percent-encoded) are refused whether
// confined or not. load_file() is for paths the user named and is not confined.
class MappedDocumentLoader : public DocumentLoader {
 public:
  MappedDocumentLoader();
  ~MappedDocumentLoader() override;
  MappedDocumentLoader(MappedDocumentLoader&&) noexcept;
  MappedDocumentLoader& operator=(MappedDocumentLoader&&) noexcept;

  // `prefix` is an IRI prefix such as "https://comp-rob2b.github.io/"; `dir` a
  // local directory (a trailing '/' is optional).
  void map(std::string prefix, std::string dir);
  // A mapping consulted only when no map() entry covers the IRI: where mospec's
  // own metamodels live, so users need no iri-map entry for them while an app
  // that maps the same IRIs elsewhere (e.g. to the authors' files) keeps its own.
  void map_fallback(std::string prefix, std::string dir);
  // One more directory a confined loader may read from (an input's directory,
  // --root).
  void allow(std::string dir);
  // Turns the sandbox on (or off).
  void confine(bool on = true);
  bool confined() const;
  // Local path for an IRI, or empty when no prefix maps it.
  std::string resolve(std::string_view iri) const;
  // The local path to read for `iri`, written at `referenced_from`: resolve()
  // plus the checks above. Throws mospec::Error with `code`, located at the
  // reference, when the IRI is unmapped, holds a control character or (when
  // confined) leaves the sandbox; the message calls the document `what`
  // ("document", "remote context", "shape file") and never quotes its content.
  std::string resolve_for_loading(std::string_view iri, SourceLoc referenced_from,
                                  std::string_view code, std::string_view what) const;
  RemoteDocument load(std::string_view iri, SourceLoc referenced_from, bool for_context) override;
  // Reads and parses a local file (cached), registering it in files().
  RemoteDocument load_file(const std::string& path, std::string document_url = {});
  size_t documents_read() const;
  // canonical_path(path), answered from what this loader (one load) has
  // already resolved of the same directories.
  std::string canonical(std::string_view path) const;

 private:
  // `read_path_is_canonical`: read_path is already canonical_path()'s answer
  // (the sandbox check computed it), so it keys the cache as it is.
  RemoteDocument load_path(const std::string& path, const std::string& read_path,
                           std::string document_url, bool read_path_is_canonical = false);
  // resolve_for_loading(), also storing resolve()'s answer in *mapped. The
  // *_locked functions expect sync_->mutex held.
  std::string resolve_for_loading_locked(std::string_view iri, SourceLoc referenced_from,
                                         std::string_view code, std::string_view what,
                                         std::string* mapped) const;
  std::string resolve_locked(std::string_view iri) const;
  bool inside_sandbox(const std::string& canonical) const;
  std::string sandbox_roots() const;
  // Records the canonical form of a sandbox root when it is added, so each
  // check costs one canonicalisation (of the document) rather than one per root.
  void add_root(const std::string& dir);
  // The lock and what it guards beyond the members below, apart so that the
  // loader (and the model that holds it) stays movable.
  struct Sync;
  std::unique_ptr<Sync> sync_;
  std::map<std::string, std::string, std::greater<>> prefixes_;  // longest first
  std::vector<std::string> allowed_;                             // allow()'s directories
  bool confined_ = false;
  std::map<std::string, std::string, std::greater<>> fallbacks_;
  // Every directory of prefixes_, fallbacks_ and allowed_, by its spelling
  // there, and its canonical_path() at the time it was added.
  std::unordered_map<std::string, std::string> root_paths_;
  std::unordered_map<std::string, RemoteDocument> cache_;  // by path
  mutable CanonicalPaths canonical_;
  size_t reads_ = 0;
};

}  // namespace mospec::jsonld
