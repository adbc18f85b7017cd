// JSON-LD 1.1 active contexts: Context Processing (API spec 4.1), Create Term
// Definition (4.2) and IRI Expansion (4.3).
//
// Active contexts are immutable once built and shared by pointer: expansion
// switches between them (type-scoped, property-scoped, previous context) at
// every node, so a switch must be cheap. How term definitions are stored
// (e.g. a layered map over a parent context) is an implementation detail
// behind find()/terms().
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "json/json.hpp"
#include "jsonld/options.hpp"

namespace mospec::jsonld {

struct TermDefinition {
  // IRI mapping; nullopt when the term is explicitly mapped to null (decoupled).
  std::optional<std::string> iri;
  bool prefix = false;
  bool protected_ = false;
  bool reverse = false;
  // Base URL to use when applying local_context (for property-scoped contexts).
  std::string base_url;
  // The scoped context, unprocessed (null: none). It points into the context
  // document it was written in, which it keeps alive, when that is known
  // (remote contexts); otherwise it is a copy.
  std::shared_ptr<const json::Value> local_context;
  std::set<std::string> container;  // "@list", "@set", "@index", ...
  // Each optional: absent = not set; present null/"ltr"/"rtl" etc.
  std::optional<json::Value> direction;  // null or "ltr"/"rtl"
  std::optional<json::Value> language;   // null or a string
  std::optional<std::string> index;      // index mapping (@index property)
  std::optional<std::string> nest;       // nest value
  std::optional<std::string> type;       // type mapping ("@id", "@vocab", "@json", "@none", IRI)
  SourceLoc where;                       // where the definition was written

  bool operator==(const TermDefinition& other) const;  // per 4.2 step 27 (ignores `where`)
};

class ActiveContext;
using ContextPtr = std::shared_ptr<const ActiveContext>;

class ActiveContext {
 public:
  // A fresh context with the given base IRI.
  static ContextPtr initial(std::string base, const Options& options);

  const std::string& base() const;           // base IRI (may be empty = none)
  const std::string& original_base() const;  // original base URL
  const std::optional<std::string>& vocab() const;
  const std::optional<std::string>& default_language() const;
  const std::optional<std::string>& default_direction() const;  // "ltr"/"rtl"
  const ContextPtr& previous() const;  // previous context (non-propagated), may be null

  // Term lookup; nullptr when the term is not defined. A term defined as null
  // yields a definition whose iri is nullopt.
  const TermDefinition* find(std::string_view term) const;
  // All defined terms (for IRI compaction checks / debugging); order unspecified.
  std::vector<std::string> terms() const;
  // Calls `visit` with each defined term's name, without copying any (a term
  // redefined in a nested context may come twice); order unspecified.
  void for_each_term(const std::function<void(std::string_view)>& visit) const;
  bool has_protected_terms() const;

  struct Impl;
  // A context and its state are made together, in one allocation
  // (internal::make_context); the context only points at the state.
  explicit ActiveContext(const Impl* impl) : impl_(impl) {}
  ActiveContext(const ActiveContext&) = delete;
  ActiveContext& operator=(const ActiveContext&) = delete;
  const Impl& impl() const { return *impl_; }

 private:
  const Impl* impl_;
};

// Memo of context processing shared by the documents of one run (one per
// DocumentLoader; not thread-safe). Two levels:
//  * exact: (active context pointer, local context, base URL, flags) -> the very
//    ContextPtr produced before, so expansion switching into the same type-scoped
//    context at every node allocates nothing;
//  * term state: (term definitions, @vocab, @language and @direction of the
//    active context, local context or remote context IRI, flags) -> the term
//    definitions it produced, so a context used by many documents (each with
//    its own base IRI, hence its own active contexts) is processed once;
//  * delta: (local context or remote context IRI, flags, @vocab, @language,
//    @direction) -> the term definitions processing added or removed, with
//    the definitions of the active context that processing looked at. It
//    applies to any active context that gives the same answers there, so a
//    context that is applied on top of different term states (a remote context
//    listed after different ones, a type-scoped context in documents with
//    different contexts) is still processed once.
// Results depend only on the inputs in the key (the base IRI is added to the
// key when processing read it), and only successful results are stored.
class ContextCache {
 public:
  ContextCache();
  ~ContextCache();
  ContextCache(const ContextCache&) = delete;
  ContextCache& operator=(const ContextCache&) = delete;

  struct Stats {
    size_t exact_hits = 0;
    size_t exact_misses = 0;
    size_t state_hits = 0;  // exact misses answered by the term-state level
    size_t remote_hits = 0;
    size_t remote_misses = 0;
    size_t delta_hits = 0;          // state or remote misses answered by the delta level
    size_t documents_loaded = 0;    // remote context documents fetched from the loader
    size_t terms_defined = 0;       // Create Term Definition runs (work not saved)
    size_t scoped_validations = 0;  // scoped contexts processed to validate them
  };
  Stats stats() const;  // a snapshot
  void clear();

  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// Context Processing algorithm (4.1.2). `local_context` is the value of an
// @context entry (object, string IRI, null or array of those). `remote_contexts`
// tracks IRIs already loaded on this path (cycle detection: "context overflow"
// / "recursive context inclusion"). Throws mospec::Error with spec error codes.
ContextPtr process_context(const ContextPtr& active, const json::Value& local_context,
                           const std::string& base_url, const Options& options,
                           std::vector<std::string>* remote_contexts = nullptr,
                           bool override_protected = false, bool propagate = true,
                           bool validate_scoped_context = true);

// IRI Expansion (4.3) for values outside context processing. Returns nullopt when
// the value expands to null (e.g. a term mapped to null).
std::optional<std::string> expand_iri(const ActiveContext& active, std::string_view value,
                                      bool document_relative = false, bool vocab = true);

bool is_keyword(std::string_view s);
// "@" followed by ALPHA only: reserved for future keywords, ignored with a warning.
bool has_keyword_form(std::string_view s);

}  // namespace mospec::jsonld
