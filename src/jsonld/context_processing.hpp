// Internal to src/jsonld: the Context Processing machinery shared by the
// files that implement the JSON-LD 1.1 Processing Algorithms on contexts:
//   context_processing.cpp      Context Processing (4.1), process_context()
//   create_term_definition.cpp  Create Term Definition (4.2)
//   iri_expansion.cpp           IRI Expansion (4.3), during context processing
//                               and expand_iri()
//   context.cpp                 ActiveContext and ContextCache
// Step numbers in comments refer to the JSON-LD 1.1 Processing Algorithms and API
// recommendation: "CP n" is Context Processing (4.1.2), "CTD n" Create Term
// Definition (4.2.2) and "IE n" IRI Expansion (4.3.2).
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "jsonld/context.hpp"
#include "jsonld/loader.hpp"
#include "rdf/id_hash_set.hpp"
#include "rdf/iri.hpp"
#include "support/spin_lock.hpp"

namespace mospec::jsonld {

namespace detail {

// A base IRI as active contexts, builders and cache entries hold it. Every
// context made from another keeps its base IRI (and original base URL), so
// they are copied far more often than written: a copy here shares the one
// string instead of allocating another. It is held prepared for resolving
// references (rdf::IriBase), which expansion does for every relative "@id".
// Immutable once made.
class SharedString {
 public:
  SharedString() = default;
  explicit SharedString(std::string_view s)
      : p_(s.empty() ? nullptr : std::make_shared<const rdf::IriBase>(std::string(s))) {}
  SharedString& operator=(std::string_view s) { return *this = SharedString(s); }
  const std::string& str() const { return iri_base().iri(); }
  operator const std::string&() const { return str(); }  // NOLINT: reads as the string
  const rdf::IriBase& iri_base() const { return p_ ? *p_ : empty_base(); }
  bool empty() const { return p_ == nullptr; }
  void clear() { p_.reset(); }
  friend bool operator==(const SharedString& a, const SharedString& b) {
    return a.p_ == b.p_ || a.str() == b.str();
  }

 private:
  static const rdf::IriBase& empty_base() {
    static const rdf::IriBase empty;
    return empty;
  }
  std::shared_ptr<const rdf::IriBase> p_;  // null: empty
};

// A term with its hash computed once, for looking it up in every layer of a
// chain (TermLayer::lookup) without hashing it again per layer.
struct HashedKey {
  std::string_view text;
  size_t hash;
};

struct StringHash {
  using is_transparent = void;
  size_t operator()(std::string_view s) const noexcept { return rdf::detail::hash_text(s); }
  size_t operator()(const HashedKey& k) const noexcept { return k.hash; }
};

using TermPtr = std::shared_ptr<const TermDefinition>;

// Terms to definitions, for a layer, a builder's overlay and a delta: the
// entries in one array in the order they were added, their hashes beside
// them, found by a scan of the hashes while there are few (most overlays hold
// a handful of terms) and through an open-addressing table of their indexes
// (linear probing) beyond that. A remote context's layer of a hundred terms is
// then a few allocations instead of a node per term, a small overlay one or
// two, a lookup touches one slot and one entry, and iteration is
// deterministic. Erasing is rare (a freeze dropping removals of nothing, a
// flatten): it rebuilds the table.
class TermMap {
 public:
  using value_type = std::pair<std::string, TermPtr>;
  using iterator = std::vector<value_type>::iterator;
  using const_iterator = std::vector<value_type>::const_iterator;

  iterator begin() { return entries_.begin(); }
  iterator end() { return entries_.end(); }
  const_iterator begin() const { return entries_.begin(); }
  const_iterator end() const { return entries_.end(); }
  bool empty() const { return entries_.empty(); }
  size_t size() const { return entries_.size(); }
  void clear() {
    entries_.clear();
    hashes_.clear();
    slots_.clear();
  }

  iterator find(std::string_view term) { return find(HashedKey{term, StringHash{}(term)}); }
  const_iterator find(std::string_view term) const {
    return find(HashedKey{term, StringHash{}(term)});
  }
  iterator find(const HashedKey& key) { return entries_.begin() + index_of(key); }
  const_iterator find(const HashedKey& key) const { return entries_.begin() + index_of(key); }

  // Adds `term` unless it is there (then nothing changes), like
  // std::unordered_map::emplace.
  std::pair<iterator, bool> emplace(std::string_view term, TermPtr def) {
    const HashedKey key{term, StringHash{}(term)};
    const size_t at = index_of(key);
    if (at != entries_.size()) return {entries_.begin() + static_cast<std::ptrdiff_t>(at), false};
    if (entries_.empty()) {
      entries_.reserve(4);
      hashes_.reserve(4);
    }
    entries_.emplace_back(std::string(term), std::move(def));
    hashes_.push_back(key.hash);
    if (!slots_.empty() && 2 * entries_.size() <= slots_.size()) {
      place(entries_.size() - 1);
    } else if (entries_.size() > kScanned) {
      rehash(std::max<size_t>(4 * kScanned, 2 * slots_.size()));
    }
    return {entries_.end() - 1, true};
  }

  // Removes the entry at `it`; the last entry takes its place, so a loop
  // erasing as it goes visits that one next (the returned iterator).
  iterator erase(iterator it) {
    const auto at = static_cast<size_t>(it - entries_.begin());
    if (at + 1 != entries_.size()) {
      entries_[at] = std::move(entries_.back());
      hashes_[at] = hashes_.back();
    }
    entries_.pop_back();
    hashes_.pop_back();
    reindex();
    return entries_.begin() + static_cast<std::ptrdiff_t>(at);
  }

  template <class Pred>
  friend size_t erase_if(TermMap& map, Pred pred) {
    size_t kept = 0;
    for (size_t i = 0; i < map.entries_.size(); ++i) {
      if (pred(std::as_const(map.entries_[i]))) continue;
      if (kept != i) {
        map.entries_[kept] = std::move(map.entries_[i]);
        map.hashes_[kept] = map.hashes_[i];
      }
      ++kept;
    }
    const size_t removed = map.entries_.size() - kept;
    map.entries_.resize(kept);
    map.hashes_.resize(kept);
    if (removed != 0) map.reindex();
    return removed;
  }

  // The hash of each entry's term (StringHash), in entry order.
  const std::vector<size_t>& hashes() const { return hashes_; }

 private:
  // Up to this many entries, lookups scan the hashes and there is no table.
  static constexpr size_t kScanned = 8;

  // The entry's index, or entries_.size() when absent.
  size_t index_of(const HashedKey& key) const {
    if (slots_.empty()) {
      for (size_t e = 0; e < hashes_.size(); ++e) {
        if (hashes_[e] == key.hash && entries_[e].first == key.text) return e;
      }
      return entries_.size();
    }
    const size_t mask = slots_.size() - 1;
    for (size_t i = key.hash & mask;; i = (i + 1) & mask) {
      const uint32_t slot = slots_[i];
      if (slot == 0) return entries_.size();
      if (hashes_[slot - 1] == key.hash && entries_[slot - 1].first == key.text) return slot - 1;
    }
  }
  void place(size_t entry) {
    const size_t mask = slots_.size() - 1;
    size_t i = hashes_[entry] & mask;
    while (slots_[i] != 0) i = (i + 1) & mask;
    slots_[i] = static_cast<uint32_t>(entry + 1);
  }
  // A table of `slot_count` slots (a power of two) holding every entry.
  void rehash(size_t slot_count) {
    slots_.assign(slot_count, 0);
    for (size_t e = 0; e < entries_.size(); ++e) place(e);
  }
  // The table for the entries left after erasing: none while they are few.
  void reindex() {
    if (entries_.size() <= kScanned) {
      slots_.clear();
    } else {
      rehash(slots_.size());
    }
  }

  std::vector<value_type> entries_;
  std::vector<size_t> hashes_;
  // Entry index + 1 (0: empty); a power of two, at most half full. Empty while
  // there are at most kScanned entries.
  std::vector<uint32_t> slots_;
};

// Term definitions are stored as a chain of immutable layers: processing a local
// context adds one layer with the terms it (re)defined over the layer of the
// context it started from, so deriving a context never copies the hundreds of
// definitions of the remote contexts below it, and layers are shared between
// all contexts derived from them. A null entry removes a term defined below.
// Chains are flattened into one layer once they grow deeper than
// kMaxLayerDepth, bounding the cost of a lookup.
struct TermLayer {
  std::shared_ptr<const TermLayer> parent;
  TermMap defs;
  uint32_t depth = 1;
  size_t protected_count = 0;  // protected terms visible through this layer
  // Terms visible through this layer whose IRI mapping is a keyword (aliases
  // such as "id": "@id"). Without any, only a keyword itself expands to a
  // keyword, which expansion's per-key keyword checks use to skip the lookup.
  size_t keyword_aliases = 0;
  // One bit per term of `defs` (bloom_bit of its hash): a lookup skips a
  // layer whose filter lacks the term's bit without probing its map, which
  // matters because most lookups pass the few terms of the scoped-context
  // layers on their way to the remote context's layer below.
  uint64_t bloom = 0;

  static uint64_t bloom_bit(size_t hash) { return uint64_t{1} << (hash >> 58); }
  // Sets `bloom` from `defs` (after defs is filled).
  void index_bloom() {
    bloom = 0;
    for (size_t hash : defs.hashes()) bloom |= bloom_bit(hash);
  }

  const TermPtr* lookup(std::string_view term) const {
    return lookup(HashedKey{term, StringHash{}(term)});
  }
  const TermPtr* lookup(const HashedKey& key) const {
    const uint64_t bit = bloom_bit(key.hash);
    for (const TermLayer* l = this; l != nullptr; l = l->parent.get()) {
      if ((l->bloom & bit) == 0) continue;
      auto it = l->defs.find(key);
      if (it != l->defs.end()) return &it->second;
    }
    return nullptr;
  }
};

// What processing a context read from the term definitions of the active
// context it started from (the "state"): the answer it got for a term. With
// `weak`, only whether that definition is protected mattered (Create Term
// Definition looking for a previous definition to protect). The term's text
// is kept in its DepList's `text`.
struct Dep {
  uint32_t pos = 0, len = 0;  // the term in DepList::text
  TermPtr def;                // null: not defined
  bool weak = false;
  size_t hash = 0;  // StringHash of the term
};

// Every term of one processing run, its spelling back to back in one string
// rather than one allocation per term.
struct DepList {
  std::vector<Dep> items;
  std::string text;
  std::string_view term(const Dep& d) const { return std::string_view(text).substr(d.pos, d.len); }
};

// Records the Deps of one processing run, one per term (a full answer wins
// over a weak one) in first-lookup order; `opaque` when processing depended on
// the state in a way Deps do not capture (nothing is then stored). A term is
// looked up many times while a context is processed (every compact IRI looks
// up its prefix), so repeats are merged as they are recorded, through a small
// open-addressing table of positions in `deps`, instead of being copied into
// the log and merged afterwards.
struct DepLog {
  DepList deps;
  bool opaque = false;

  // Room for about `terms` terms (each term a context defines is looked up
  // once for CTD 6), so that recording does not grow the log step by step.
  void reserve(size_t terms) {
    deps.items.reserve(terms);
    deps.text.reserve(terms * 16);
    size_t n = 32;
    while (n < 2 * terms) n *= 2;
    if (n > slots_.size()) rehash(n);
  }

  void record(const HashedKey& key, const TermPtr* found, bool weak) {
    TermPtr def = found != nullptr ? *found : nullptr;
    const bool only_protection = weak && !(def && def->protected_);
    if (2 * (deps.items.size() + 1) > slots_.size())
      rehash(std::max<size_t>(32, slots_.size() * 2));
    const size_t mask = slots_.size() - 1;
    size_t i = key.hash & mask;
    for (; slots_[i] != 0; i = (i + 1) & mask) {
      Dep& d = deps.items[slots_[i] - 1];
      if (d.hash != key.hash || deps.term(d) != key.text) continue;
      if (d.weak && !only_protection) {
        d.weak = false;
        d.def = std::move(def);
      }
      return;
    }
    Dep& d = deps.items.emplace_back();
    d.pos = static_cast<uint32_t>(deps.text.size());
    d.len = static_cast<uint32_t>(key.text.size());
    deps.text.append(key.text);
    if (!only_protection) d.def = std::move(def);
    d.weak = only_protection;
    d.hash = key.hash;
    slots_[i] = static_cast<uint32_t>(deps.items.size());
  }

 private:
  std::vector<uint32_t> slots_;  // position in deps.items + 1; 0: empty

  void rehash(size_t size) {
    slots_.assign(size, 0);
    const size_t mask = slots_.size() - 1;
    for (size_t n = 0; n < deps.items.size(); ++n) {
      size_t i = deps.items[n].hash & mask;
      while (slots_[i] != 0) i = (i + 1) & mask;
      slots_[i] = static_cast<uint32_t>(n + 1);
    }
  }
};

// The result of one processing run as a change to the term state, valid for
// any state on which `deps` hold.
struct Delta {
  unsigned flags = 0;
  std::optional<std::string> vocab, language, direction;  // of the state
  bool used_base = false;
  SharedString base;  // compared only when used_base
  DepList deps;
  TermMap changes;  // defined or (null) removed terms
  std::optional<std::string> out_vocab, out_language, out_direction;
};

}  // namespace detail

using detail::TermLayer;
using detail::TermMap;
using detail::TermPtr;
using LayerPtr = std::shared_ptr<const TermLayer>;

namespace internal {

constexpr uint32_t kMaxLayerDepth = 6;
// Processor-defined limit of CP 5.2.3: remote contexts nested deeper than this
// are reported as "context overflow".
constexpr size_t kMaxRemoteContexts = 32;
// Processor-defined limit on the remote contexts one context processing may
// process in all (repeats included), far above any real model's handful.
constexpr size_t kMaxRemoteProcessing = 4096;

constexpr std::array<std::string_view, 23> kKeywords = {
    "@base",   "@container", "@context", "@direction", "@graph",     "@id",
    "@import", "@included",  "@index",   "@json",      "@language",  "@list",
    "@nest",   "@none",      "@prefix",  "@propagate", "@protected", "@reverse",
    "@set",    "@type",      "@value",   "@version",   "@vocab"};

inline bool is_blank_node(std::string_view s) {
  return s.size() >= 2 && s[0] == '_' && s[1] == ':';
}

inline bool ends_with_gen_delim(std::string_view s) {
  if (s.empty()) return false;
  switch (s.back()) {
    case ':':
    case '/':
    case '?':
    case '#':
    case '[':
    case ']':
    case '@':
      return true;
    default:
      return false;
  }
}

// expand_iri(), also telling in *is_term (when given and the value is no
// keyword) whether `value` is a term of `active`, which the caller would
// otherwise look up a second time.
std::optional<std::string> expand_iri(const ActiveContext& active, std::string_view value,
                                      bool document_relative, bool vocab, bool* is_term);
// The same, written over `out` (false: the value expands to null). Expansion
// reuses one buffer for the IRIs it copies into its output.
bool expand_iri_into(std::string& out, const ActiveContext& active, std::string_view value,
                     bool document_relative, bool vocab, bool* is_term);

inline bool is_keyword_alias(const TermDefinition& def) {
  return def.iri && is_keyword(*def.iri);
}

inline std::string quoted(std::string_view s) {
  std::string out = "\"";
  out += s;
  out += '"';
  return out;
}

}  // namespace internal

struct ActiveContext::Impl {
  LayerPtr terms;  // nullptr: no term definitions
  detail::SharedString base;
  detail::SharedString original_base;
  std::optional<std::string> vocab;
  std::optional<std::string> language;
  std::optional<std::string> direction;
  ContextPtr previous;
};

namespace internal {

// A context with its state beside it: one allocation per context (and one
// free when the last user lets go) instead of one for each.
struct ContextBlock {
  explicit ContextBlock(ActiveContext::Impl state) : impl(std::move(state)), context(&impl) {}
  ContextBlock(const ContextBlock&) = delete;
  ContextBlock& operator=(const ContextBlock&) = delete;
  ActiveContext::Impl impl;
  ActiveContext context;
};

inline ContextPtr make_context(ActiveContext::Impl impl) {
  auto block = std::make_shared<const ContextBlock>(std::move(impl));
  return ContextPtr(block, &block->context);
}

inline size_t mix(size_t h, size_t v) {
  return h ^ (v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2));
}

// Structural hash consistent with json::Value's operator== (member order and
// locations ignored).
inline size_t hash_json(const json::Value& v) {
  switch (v.kind()) {
    case json::Kind::Null:
      return 0x51;
    case json::Kind::Boolean:
      return v.as_bool() ? 0x52 : 0x53;
    case json::Kind::Number: {
      const double d = v.as_number();
      return std::hash<double>{}(d == 0 ? 0.0 : d);
    }
    case json::Kind::String:
      return std::hash<std::string_view>{}(v.as_string());
    case json::Kind::Array: {
      size_t h = 0x54;
      for (const auto& e : v.as_array()) h = mix(h, hash_json(e));
      return h;
    }
    case json::Kind::Object: {
      size_t h = 0x55;
      const json::Object& o = v.as_object();
      for (size_t i = 0; i < o.size(); ++i) {
        h += mix(std::hash<std::string_view>{}(o.key(i)), hash_json(o.value(i)));
      }
      return h;
    }
  }
  return 0;
}

struct RemoteDoc {
  std::shared_ptr<const json::Value> document;
  std::string url;
};

}  // namespace internal

using internal::hash_json;
using internal::RemoteDoc;

struct ContextCache::Impl {
  // The documents of one load are expanded on more than one thread, sharing
  // this cache. The lock is held only to look entries up (copying out what is
  // used or applying it) and to store them, never while a context is being
  // processed: two threads that miss the same entry both process it, and both
  // results (equal) are stored.
  SpinLock mutex;
  Stats stats;  // under the lock

  // Exact level: the result ContextPtr for one (active context, local context).
  struct ExactEntry {
    std::weak_ptr<const ActiveContext> active;
    const ActiveContext* active_raw = nullptr;
    TermPtr owner;        // the scoped context's definition, when known
    json::Value content;  // otherwise a copy of the local context
    std::string base_url;
    unsigned flags = 0;
    ContextPtr result;
  };
  std::unordered_map<size_t, std::vector<ExactEntry>> exact;

  // Which term definition holds a scoped context, so expansion passing
  // `*def->local_context` is recognised by address instead of by content.
  struct Owner {
    std::weak_ptr<const TermDefinition> def;
    // hash_json of its local context, computed when first needed (most
    // scoped contexts of a remote context are never used by a document).
    std::optional<size_t> hash;
  };
  std::unordered_map<const json::Value*, Owner> owners;
  size_t owners_purge_at = 1024;

  // Remote level: what applying a remote context to a term state produced.
  struct RemoteEntry {
    std::weak_ptr<const TermLayer> terms;
    const TermLayer* terms_raw = nullptr;
    std::optional<std::string> vocab, language, direction;
    unsigned flags = 0;
    bool used_base = false;
    detail::SharedString base;  // compared only when used_base
    LayerPtr out_terms;
    std::optional<std::string> out_vocab, out_language, out_direction;
  };
  std::unordered_map<std::string, std::vector<RemoteEntry>, detail::StringHash, std::equal_to<>>
      remote;

  // Term-state level for local contexts given to process_context (typically
  // scoped contexts): like RemoteEntry, keyed by content.
  struct StateEntry {
    RemoteEntry state;
    TermPtr owner;
    json::Value content;
    std::string base_url;
    bool sets_previous = false;  // CP 3 applied
  };
  std::unordered_map<size_t, std::vector<StateEntry>> states;

  std::unordered_map<std::string, RemoteDoc, detail::StringHash, std::equal_to<>> documents;

  // Delta level, by remote context IRI and by local context content.
  std::unordered_map<std::string, std::vector<detail::Delta>, detail::StringHash, std::equal_to<>>
      remote_deltas;
  struct LocalDelta {
    detail::Delta delta;
    TermPtr owner;
    json::Value content;
    std::string base_url;
  };
  std::unordered_map<size_t, std::vector<LocalDelta>> local_deltas;

  void register_owner(const TermPtr& def) {
    if (owners.size() >= owners_purge_at) {
      std::erase_if(owners, [](const auto& kv) { return kv.second.def.expired(); });
      owners_purge_at = std::max<size_t>(1024, owners.size() * 2);
    }
    owners[&*def->local_context] = Owner{def, std::nullopt};
  }
};

namespace internal {

// A context under construction: the frozen layers it started from plus the
// definitions changed so far. A builder with a `parent` is the throw-away
// context of a scoped-context validation (CTD 21.3), stacked on the builder
// whose term is being defined.
struct Builder {
  const Builder* parent = nullptr;
  LayerPtr layer;
  TermMap overlay;
  detail::SharedString base;
  detail::SharedString original_base;
  std::optional<std::string> vocab, language, direction;
  ContextPtr previous;
  // Whether processing read the base IRI (the cache key must then include it)
  // or replaced it (the result is not a pure function of the term state).
  mutable bool used_base = false;
  bool touched_base = false;

  Builder() = default;
  explicit Builder(const ActiveContext& a) {
    const ActiveContext::Impl& i = a.impl();
    layer = i.terms;
    base = i.base;
    original_base = i.original_base;
    vocab = i.vocab;
    language = i.language;
    direction = i.direction;
    previous = i.previous;
  }

  // While set, lookups that reach `layer` (the state processing started from)
  // are recorded, so the result can be cached as a Delta.
  detail::DepLog* deps = nullptr;

  const TermPtr* lookup(std::string_view term, bool weak = false) const {
    // Hashed once for the overlays, the layers and the dependency log.
    return lookup(detail::HashedKey{term, detail::StringHash{}(term)}, weak);
  }
  const TermPtr* lookup(const detail::HashedKey& key, bool weak) const {
    auto it = overlay.find(key);
    if (it != overlay.end()) return &it->second;
    if (parent != nullptr) return parent->lookup(key, weak);
    const TermPtr* p = layer ? layer->lookup(key) : nullptr;
    if (deps != nullptr) deps->record(key, p, weak);
    return p;
  }
  // CTD 6: the previous definition of a term being defined, which matters
  // only if it is protected.
  const TermPtr* lookup_previous(std::string_view term) const { return lookup(term, true); }
  const TermDefinition* find(std::string_view term) const {
    const TermPtr* p = lookup(term);
    return p != nullptr ? p->get() : nullptr;
  }
  const std::string& base_iri() const {
    used_base = true;
    return base.str();
  }

  void set(std::string_view term, TermPtr def) {
    auto it = overlay.find(term);
    if (it != overlay.end()) {
      it->second = std::move(def);
    } else {
      overlay.emplace(term, std::move(def));
    }
  }

  void reset_terms() {
    parent = nullptr;
    layer = nullptr;
    overlay.clear();
  }

  bool has_protected() const {
    if (deps != nullptr) deps->opaque = true;
    size_t n = 0;
    if (parent != nullptr) {
      n = parent->has_protected() ? 1 : 0;
    } else if (layer) {
      n = layer->protected_count;
    }
    for (const auto& [k, v] : overlay) {
      const TermPtr* below = parent != nullptr ? parent->lookup(k)
                             : layer           ? layer->lookup(k)
                                               : nullptr;
      if (below != nullptr && *below && (*below)->protected_ && n > 0) --n;
      if (v && v->protected_) ++n;
    }
    return n != 0;
  }

  // Moves the overlay into a new immutable layer (requires parent == nullptr).
  void freeze() {
    if (deps != nullptr) deps->opaque = true;
    size_t protected_count = layer ? layer->protected_count : 0;
    size_t keyword_aliases = layer ? layer->keyword_aliases : 0;
    for (auto it = overlay.begin(); it != overlay.end();) {
      const TermPtr* below = layer ? layer->lookup(it->first) : nullptr;
      const bool below_defined = below != nullptr && *below;
      if (below_defined && (*below)->protected_) --protected_count;
      if (it->second && it->second->protected_) ++protected_count;
      if (below_defined && is_keyword_alias(**below)) --keyword_aliases;
      if (it->second && is_keyword_alias(*it->second)) ++keyword_aliases;
      if (!it->second && !below_defined) {
        it = overlay.erase(it);  // removing nothing
      } else {
        ++it;
      }
    }
    if (overlay.empty()) return;
    auto l = std::make_shared<TermLayer>();
    l->defs = std::move(overlay);  // the nodes move; nothing is reallocated
    overlay = TermMap();
    l->protected_count = protected_count;
    l->keyword_aliases = keyword_aliases;
    if (layer && layer->depth + 1 > kMaxLayerDepth) {
      // Flatten: upper layers first, so emplace keeps the visible definition.
      for (const TermLayer* p = layer.get(); p != nullptr; p = p->parent.get()) {
        for (const auto& [k, v] : p->defs) l->defs.emplace(k, v);
      }
      erase_if(l->defs, [](const auto& kv) { return !kv.second; });
    } else {
      l->parent = layer;
      l->depth = layer ? layer->depth + 1 : 1;
    }
    l->index_bloom();
    layer = std::move(l);
  }

  ContextPtr to_context() {
    freeze();
    ActiveContext::Impl impl;
    impl.terms = layer;
    impl.base = base;
    impl.original_base = original_base;
    impl.vocab = vocab;
    impl.language = language;
    impl.direction = direction;
    impl.previous = previous;
    return make_context(std::move(impl));
  }
};

// The local context whose terms are being defined, with the `defined` map of
// CP 5.12 kept per member index (inline for the usual few dozen members).
struct LocalCtx {
  enum State : uint8_t { Undefined, InProgress, Defined };
  const json::Object* obj = nullptr;
  State* state;

  explicit LocalCtx(const json::Object& o) : obj(&o) {
    if (o.size() <= small_.size()) {
      state = small_.data();
    } else {
      large_.resize(o.size());
      state = large_.data();
    }
    std::fill(state, state + o.size(), Undefined);
  }
  LocalCtx(const LocalCtx&) = delete;
  LocalCtx& operator=(const LocalCtx&) = delete;
  // Index of `key`, or npos (through the object's own key index when it has
  // one).
  size_t find(std::string_view key) const { return obj->index_of(key); }

 private:
  std::array<State, 64> small_;
  std::vector<State> large_;
};

// Whether `state` answers every lookup in `deps` as the state they were
// recorded on did: the same definition, or an equal unprotected one.
inline bool deps_hold(const detail::DepList& deps, const TermLayer* state) {
  for (const detail::Dep& d : deps.items) {
    const TermPtr* p =
        state != nullptr ? state->lookup(detail::HashedKey{deps.term(d), d.hash}) : nullptr;
    const TermDefinition* now = p != nullptr ? p->get() : nullptr;
    if (d.weak) {
      if (now != nullptr && now->protected_) return false;
      continue;
    }
    const TermDefinition* then = d.def.get();
    if (now == then) continue;
    if (now == nullptr || then == nullptr || now->protected_ || then->protected_ ||
        now->base_url != then->base_url || !(*now == *then)) {
      return false;
    }
  }
  return true;
}

// The number of members of a local context (summed over an array of them):
// about how many terms processing it looks up.
inline size_t member_count(const json::Value& local_context) {
  if (local_context.is_object()) return local_context.as_object().size();
  size_t n = 0;
  if (local_context.is_array()) {
    for (const json::Value& item : local_context.as_array()) {
      if (item.is_object()) n += item.as_object().size();
    }
  }
  return n;
}

// Applies a cached Delta to `b` (whose state the Delta's deps hold on) and
// freezes the result.
inline void apply_delta(Builder& b, const detail::Delta& d) {
  b.overlay = d.changes;
  b.vocab = d.out_vocab;
  b.language = d.out_language;
  b.direction = d.out_direction;
  if (d.used_base) b.used_base = true;
  b.freeze();
}

// Context Processing passes "a copy of remote contexts" to the processing of
// a remote or scoped context (CP 5.2.6, CTD 21.3): processing only appends to
// the list, so taking its additions off when that processing ends, even by an
// exception, is the same as giving it a copy.
struct RemoteContextsMark {
  std::vector<std::string>& list;
  size_t size;
  explicit RemoteContextsMark(std::vector<std::string>& l) : list(l), size(l.size()) {}
  ~RemoteContextsMark() {
    if (list.size() > size)
      list.erase(list.begin() + static_cast<std::ptrdiff_t>(size), list.end());
  }
  RemoteContextsMark(const RemoteContextsMark&) = delete;
  RemoteContextsMark& operator=(const RemoteContextsMark&) = delete;
};

// Turns off dependency recording when processing ends (even by an exception).
struct DepRecording {
  Builder& b;
  DepRecording(Builder& builder, detail::DepLog* log) : b(builder) { b.deps = log; }
  ~DepRecording() { b.deps = nullptr; }
  DepRecording(const DepRecording&) = delete;
  DepRecording& operator=(const DepRecording&) = delete;
};

// Flags that change a processing result, part of every cache key.
inline unsigned flags_of(const Options& o, bool override_protected, bool propagate, bool validate) {
  return (o.processing_mode == ProcessingMode::JsonLd10 ? 1u : 0u) |
         (override_protected ? 2u : 0u) | (propagate ? 4u : 0u) | (validate ? 8u : 0u);
}

class Processor {
 public:
  explicit Processor(const Options& options)
      : opts_(options),
        cache_(options.context_cache ? &options.context_cache->impl() : nullptr),
        json10_(options.processing_mode == ProcessingMode::JsonLd10) {}
  // Adds what this run counted to the cache's statistics: once per run, not
  // once per term, so that threads sharing the cache do not take turns on it.
  ~Processor() {
    if (cache_ == nullptr || (terms_defined_ == 0 && scoped_validations_ == 0)) return;
    std::lock_guard lock(cache_->mutex);
    cache_->stats.terms_defined += terms_defined_;
    cache_->stats.scoped_validations += scoped_validations_;
  }
  Processor(const Processor&) = delete;
  Processor& operator=(const Processor&) = delete;

  ContextCache::Impl* cache() const { return cache_; }
  // The shared cache's lock (none without a cache).
  std::unique_lock<SpinLock> lock_cache() const {
    return cache_ != nullptr ? std::unique_lock(cache_->mutex) : std::unique_lock<SpinLock>();
  }

  // The Context Processing algorithm on `result` (which starts as a clone of the
  // active context). `active` is the active context as a ContextPtr when known
  // (CP 3 stores it as the previous context). `in_remote`: the local context
  // came from a remote document, so @base is ignored (CP 5.7).
  void process(Builder& result, const ContextPtr* active, const json::Value& local_context,
               const std::string& base_url, std::vector<std::string>& remote_contexts,
               bool override_protected, bool propagate, bool validate, bool in_remote);

  [[noreturn]] void fail(DiagnosticCode code, const std::string& message, SourceLoc loc) const {
    std::string file;
    if (opts_.loader != nullptr && loc.file != 0) file = opts_.loader->files().path(loc.file);
    throw Error(code, message, std::move(file), loc.line, loc.column);
  }

 private:
  const Options& opts_;
  ContextCache::Impl* cache_;
  size_t terms_defined_ = 0, scoped_validations_ = 0;  // see ~Processor
  bool json10_;
  // Remote contexts processed (not answered from the cache) by this call.
  size_t remote_processed_ = 0;
  // The remote contexts being processed, outermost first: the ancestors of the
  // one at hand, for cycle detection.
  std::vector<std::string> chain_;
  // Keeps `chain_` balanced when processing ends, even by an exception.
  struct ChainEntry {
    std::vector<std::string>& chain;
    ChainEntry(std::vector<std::string>& c, const std::string& iri) : chain(c) {
      chain.push_back(iri);
    }
    ~ChainEntry() { chain.pop_back(); }
    ChainEntry(const ChainEntry&) = delete;
    ChainEntry& operator=(const ChainEntry&) = delete;
  };
  // The document the local context being processed was read from, when it
  // is a remote context: a scoped context written in it is kept by pointing
  // into it rather than copied. Null while processing anything else.
  std::shared_ptr<const json::Value> owner_;
  struct OwnerScope {
    std::shared_ptr<const json::Value>& owner;
    std::shared_ptr<const json::Value> saved;
    OwnerScope(std::shared_ptr<const json::Value>& o, std::shared_ptr<const json::Value> now)
        : owner(o), saved(std::exchange(o, std::move(now))) {}
    ~OwnerScope() { owner = std::move(saved); }
    OwnerScope(const OwnerScope&) = delete;
    OwnerScope& operator=(const OwnerScope&) = delete;
  };
  // Documents dereferenced during this call when there is no shared cache (CP
  // 5.2.4: a context is dereferenced at most once).
  std::unordered_map<std::string, RemoteDoc, detail::StringHash, std::equal_to<>> local_docs_;

  void warn(const std::string& message, SourceLoc loc) const {
    if (opts_.diagnostics == nullptr) return;
    std::string file;
    if (opts_.loader != nullptr && loc.file != 0) file = opts_.loader->files().path(loc.file);
    opts_.diagnostics->report(Diagnostic{Severity::Warning, std::move(file), loc.line, loc.column,
                                         "keyword-like-term", message});
  }

  static ContextPtr snapshot(Builder& b) {
    if (b.parent != nullptr) return nullptr;
    return b.to_context();
  }

  void process_item(Builder& result, const json::Value& context, const std::string& base_url,
                    std::vector<std::string>& remote_contexts, bool override_protected,
                    bool propagate, bool validate, bool in_remote);

  std::string resolve_context_iri(const std::string& base_url, std::string_view ref,
                                  SourceLoc loc) const;

  // CP 5.2.4, 5.2.5: the remote document (dereferenced at most once).
  const RemoteDoc& dereference(const std::string& iri, SourceLoc loc);

  void process_remote(Builder& result, const json::Value& context, const std::string& base_url,
                      std::vector<std::string>& remote_contexts, bool override_protected,
                      bool validate);

  // Records the remote level's entry: `iri` applied to (in_terms, vocab,
  // language, direction[, base]) gave `result` (frozen).
  void store_remote(const std::string& iri, unsigned flags, const LayerPtr& in_terms,
                    const std::optional<std::string>& vocab,
                    const std::optional<std::string>& language,
                    const std::optional<std::string>& direction, bool used_base,
                    const detail::SharedString& base, const Builder& result);

  struct TermArgs {
    const std::string& base_url;
    bool protected_default;
    bool override_protected;
    std::vector<std::string>* remote_contexts;
    bool validate;
  };

  // IRI Expansion (4.3.2) during context processing; `lc` (may be null) is the
  // local context whose undefined terms are created on demand (IE 3, IE 6.3).
  std::optional<std::string> expand(Builder& active, std::string_view value, bool document_relative,
                                    bool vocab, LocalCtx* lc, const std::optional<TermArgs>& args);

  // A term definition's value as the map of CTD 7 - 9 without building it: a
  // string or null value stands for {"@id": value}. Its entries are picked out
  // by one scan of the object rather than one search per keyword.
  struct TermValue {
    const json::Object* obj = nullptr;
    const json::Value* id = nullptr;
    const json::Value* reverse = nullptr;
    const json::Value* container = nullptr;
    const json::Value* context = nullptr;
    const json::Value* direction = nullptr;
    const json::Value* index = nullptr;
    const json::Value* language = nullptr;
    const json::Value* nest = nullptr;
    const json::Value* prefix = nullptr;
    const json::Value* protected_ = nullptr;
    const json::Value* type = nullptr;
    // The first member that is none of the above (CTD 26), or npos.
    size_t unexpected = std::string::npos;

    void scan(const json::Object& o);
  };
  // Create Term Definition (4.2.2) for member `idx` of the local context.
  void create_term(Builder& active, LocalCtx& lc, size_t idx, const TermArgs& args);

  void validate_container(std::string_view term, const json::Value& c, TermDefinition& def);
};

}  // namespace internal

}  // namespace mospec::jsonld
