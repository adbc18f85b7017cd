#include "jsonld/context.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <unordered_map>
#include <utility>

#include "jsonld/loader.hpp"
#include "rdf/iri.hpp"

// Step numbers in comments refer to the JSON-LD 1.1 Processing Algorithms and API
// recommendation: "CP n" is Context Processing (4.1.2), "CTD n" Create Term
// Definition (4.2.2) and "IE n" IRI Expansion (4.3.2).

namespace mospec::jsonld {

namespace detail {

struct StringHash {
  using is_transparent = void;
  size_t operator()(std::string_view s) const noexcept { return std::hash<std::string_view>{}(s); }
};

using TermPtr = std::shared_ptr<const TermDefinition>;
using TermMap = std::unordered_map<std::string, TermPtr, StringHash, std::equal_to<>>;

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

  const TermPtr* lookup(std::string_view term) const {
    for (const TermLayer* l = this; l != nullptr; l = l->parent.get()) {
      auto it = l->defs.find(term);
      if (it != l->defs.end()) return &it->second;
    }
    return nullptr;
  }
};

// What processing a context read from the term definitions of the active
// context it started from (the "state"): the answer it got for `term`. With
// `weak`, only whether that definition is protected mattered (Create Term
// Definition looking for a previous definition to protect).
struct Dep {
  std::string term;
  TermPtr def;  // null: not defined
  bool weak = false;
};

// Records the Deps of one processing run; `opaque` when processing depended on
// the state in a way Deps do not capture (nothing is then stored).
struct DepLog {
  std::vector<Dep> deps;
  bool opaque = false;
};

// The result of one processing run as a change to the term state, valid for
// any state on which `deps` hold.
struct Delta {
  unsigned flags = 0;
  std::optional<std::string> vocab, language, direction;  // of the state
  bool used_base = false;
  std::string base;  // compared only when used_base
  std::vector<Dep> deps;
  TermMap changes;  // defined or (null) removed terms
  std::optional<std::string> out_vocab, out_language, out_direction;
};

}  // namespace detail

using detail::TermLayer;
using detail::TermMap;
using detail::TermPtr;
using LayerPtr = std::shared_ptr<const TermLayer>;

namespace {

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

bool is_blank_node(std::string_view s) {
  return s.size() >= 2 && s[0] == '_' && s[1] == ':';
}

bool ends_with_gen_delim(std::string_view s) {
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

std::string quoted(std::string_view s) {
  std::string out = "\"";
  out += s;
  out += '"';
  return out;
}

}  // namespace

bool is_keyword(std::string_view s) {
  if (s.size() < 3 || s[0] != '@') return false;
  return std::find(kKeywords.begin(), kKeywords.end(), s) != kKeywords.end();
}

bool has_keyword_form(std::string_view s) {
  if (s.size() < 2 || s[0] != '@') return false;
  for (size_t i = 1; i < s.size(); ++i) {
    const char c = s[i];
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'))) return false;
  }
  return true;
}

bool TermDefinition::operator==(const TermDefinition& o) const {
  // CTD 27 compares definitions "other than the value of protected"; `where` and
  // base_url only say where the definition came from.
  return iri == o.iri && prefix == o.prefix && reverse == o.reverse &&
         local_context == o.local_context && container == o.container && direction == o.direction &&
         language == o.language && index == o.index && nest == o.nest && type == o.type;
}

// ---------------------------------------------------------------------------
// ActiveContext

struct ActiveContext::Impl {
  LayerPtr terms;  // nullptr: no term definitions
  std::string base;
  std::string original_base;
  std::optional<std::string> vocab;
  std::optional<std::string> language;
  std::optional<std::string> direction;
  ContextPtr previous;
};

ActiveContext::ActiveContext(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}

ContextPtr ActiveContext::initial(std::string base, const Options&) {
  auto impl = std::make_shared<Impl>();
  impl->original_base = base;
  impl->base = std::move(base);
  return std::make_shared<const ActiveContext>(std::move(impl));
}

const std::string& ActiveContext::base() const {
  return impl_->base;
}
const std::string& ActiveContext::original_base() const {
  return impl_->original_base;
}
const std::optional<std::string>& ActiveContext::vocab() const {
  return impl_->vocab;
}
const std::optional<std::string>& ActiveContext::default_language() const {
  return impl_->language;
}
const std::optional<std::string>& ActiveContext::default_direction() const {
  return impl_->direction;
}
const ContextPtr& ActiveContext::previous() const {
  return impl_->previous;
}

const TermDefinition* ActiveContext::find(std::string_view term) const {
  if (!impl_->terms) return nullptr;
  const TermPtr* p = impl_->terms->lookup(term);
  return p != nullptr ? p->get() : nullptr;
}

std::vector<std::string> ActiveContext::terms() const {
  std::vector<std::string> out;
  TermMap seen;
  for (const TermLayer* l = impl_->terms.get(); l != nullptr; l = l->parent.get()) {
    for (const auto& [k, v] : l->defs) {
      if (seen.emplace(k, v).second && v) out.push_back(k);
    }
  }
  return out;
}

bool ActiveContext::has_protected_terms() const {
  return impl_->terms && impl_->terms->protected_count != 0;
}

// ---------------------------------------------------------------------------
// ContextCache

namespace {

size_t mix(size_t h, size_t v) {
  return h ^ (v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2));
}

// Structural hash consistent with json::Value's operator== (member order and
// locations ignored).
size_t hash_json(const json::Value& v) {
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

}  // namespace

struct ContextCache::Impl {
  Stats stats;

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
    size_t hash = 0;  // hash_json of its local context, computed once
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
    std::string base;  // compared only when used_base
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
    owners[&*def->local_context] = Owner{def, hash_json(*def->local_context)};
  }
};

ContextCache::ContextCache() : impl_(std::make_unique<Impl>()) {}
ContextCache::~ContextCache() = default;
const ContextCache::Stats& ContextCache::stats() const {
  return impl_->stats;
}
void ContextCache::clear() {
  impl_ = std::make_unique<Impl>();
}

// ---------------------------------------------------------------------------
// Processing

namespace {

// A context under construction: the frozen layers it started from plus the
// definitions changed so far. A builder with a `parent` is the throw-away
// context of a scoped-context validation (CTD 21.3), stacked on the builder
// whose term is being defined.
struct Builder {
  const Builder* parent = nullptr;
  LayerPtr layer;
  TermMap overlay;
  std::string base;
  std::string original_base;
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
    auto it = overlay.find(term);
    if (it != overlay.end()) return &it->second;
    if (parent != nullptr) return parent->lookup(term, weak);
    const TermPtr* p = layer ? layer->lookup(term) : nullptr;
    if (deps != nullptr) {
      TermPtr def = p != nullptr ? *p : nullptr;
      const bool only_protection = weak && !(def && def->protected_);
      deps->deps.push_back(
          {std::string(term), only_protection ? nullptr : std::move(def), only_protection});
    }
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
    return base;
  }

  void set(std::string_view term, TermPtr def) {
    auto it = overlay.find(term);
    if (it != overlay.end()) {
      it->second = std::move(def);
    } else {
      overlay.emplace(std::string(term), std::move(def));
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
    for (auto it = overlay.begin(); it != overlay.end();) {
      const TermPtr* below = layer ? layer->lookup(it->first) : nullptr;
      const bool below_defined = below != nullptr && *below;
      if (below_defined && (*below)->protected_) --protected_count;
      if (it->second && it->second->protected_) ++protected_count;
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
    if (layer && layer->depth + 1 > kMaxLayerDepth) {
      // Flatten: upper layers first, so emplace keeps the visible definition.
      for (const TermLayer* p = layer.get(); p != nullptr; p = p->parent.get()) {
        for (const auto& [k, v] : p->defs) l->defs.emplace(k, v);
      }
      std::erase_if(l->defs, [](const auto& kv) { return !kv.second; });
    } else {
      l->parent = layer;
      l->depth = layer ? layer->depth + 1 : 1;
    }
    layer = std::move(l);
  }

  ContextPtr to_context() {
    freeze();
    auto impl = std::make_shared<ActiveContext::Impl>();
    impl->terms = layer;
    impl->base = base;
    impl->original_base = original_base;
    impl->vocab = vocab;
    impl->language = language;
    impl->direction = direction;
    impl->previous = previous;
    return std::make_shared<const ActiveContext>(std::move(impl));
  }
};

// The local context whose terms are being defined, with the `defined` map of
// CP 5.12 kept per member index.
struct LocalCtx {
  enum State : uint8_t { Undefined, InProgress, Defined };
  const json::Object* obj = nullptr;
  std::vector<State> state;
  std::unordered_map<std::string_view, size_t> index;  // built for large contexts

  explicit LocalCtx(const json::Object& o) : obj(&o), state(o.size(), Undefined) {
    if (o.size() > 16) {
      index.reserve(o.size());
      for (size_t i = 0; i < o.size(); ++i) index.emplace(o.key(i), i);
    }
  }
  // Index of `key`, or npos.
  size_t find(std::string_view key) const {
    if (!index.empty()) {
      auto it = index.find(key);
      return it == index.end() ? std::string::npos : it->second;
    }
    for (size_t i = 0; i < obj->size(); ++i) {
      if (obj->key(i) == key) return i;
    }
    return std::string::npos;
  }
};

// Whether `state` answers every lookup in `deps` as the state they were
// recorded on did: the same definition, or an equal unprotected one.
bool deps_hold(const std::vector<detail::Dep>& deps, const TermLayer* state) {
  for (const detail::Dep& d : deps) {
    const TermPtr* p = state != nullptr ? state->lookup(d.term) : nullptr;
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

// One Dep per term (a full answer wins over a weak one), in first-lookup order.
std::vector<detail::Dep> unique_deps(std::vector<detail::Dep> deps) {
  std::unordered_map<std::string_view, size_t> at;  // views of out's terms
  at.reserve(deps.size());
  std::vector<detail::Dep> out;
  out.reserve(deps.size());  // never reallocates, so the views stay valid
  for (detail::Dep& d : deps) {
    auto it = at.find(d.term);
    if (it == at.end()) {
      out.push_back(std::move(d));
      at.emplace(out.back().term, out.size() - 1);
    } else if (out[it->second].weak && !d.weak) {
      out[it->second].weak = false;
      out[it->second].def = std::move(d.def);
    }
  }
  return out;
}

// Applies a cached Delta to `b` (whose state the Delta's deps hold on) and
// freezes the result.
void apply_delta(Builder& b, const detail::Delta& d) {
  b.overlay = d.changes;
  b.vocab = d.out_vocab;
  b.language = d.out_language;
  b.direction = d.out_direction;
  if (d.used_base) b.used_base = true;
  b.freeze();
}

// Turns off dependency recording when processing ends (even by an exception).
struct DepRecording {
  Builder& b;
  DepRecording(Builder& builder, detail::DepLog* log) : b(builder) { b.deps = log; }
  ~DepRecording() { b.deps = nullptr; }
  DepRecording(const DepRecording&) = delete;
  DepRecording& operator=(const DepRecording&) = delete;
};

// Flags that change a processing result, part of every cache key.
unsigned flags_of(const Options& o, bool override_protected, bool propagate, bool validate) {
  return (o.processing_mode == ProcessingMode::JsonLd10 ? 1u : 0u) |
         (override_protected ? 2u : 0u) | (propagate ? 4u : 0u) | (validate ? 8u : 0u);
}

class Processor {
 public:
  explicit Processor(const Options& options)
      : opts_(options),
        cache_(options.context_cache ? &options.context_cache->impl() : nullptr),
        json10_(options.processing_mode == ProcessingMode::JsonLd10) {}

  ContextCache::Impl* cache() const { return cache_; }

  // The Context Processing algorithm on `result` (which starts as a clone of the
  // active context). `active` is the active context as a ContextPtr when known
  // (CP 3 stores it as the previous context). `in_remote`: the local context
  // came from a remote document, so @base is ignored (CP 5.7).
  void process(Builder& result, const ContextPtr* active, const json::Value& local_context,
               const std::string& base_url, std::vector<std::string>& remote_contexts,
               bool override_protected, bool propagate, bool validate, bool in_remote) {
    // CP 2: @propagate is read first; its value is checked in CP 5.11.
    if (const json::Value* p = local_context.get("@propagate"); p != nullptr && p->is_bool()) {
      propagate = p->as_bool();
    }
    // CP 3
    if (!propagate && !result.previous && result.parent == nullptr) {
      result.previous = active != nullptr ? *active : snapshot(result);
    }
    // CP 4
    if (local_context.is_array()) {
      for (const json::Value& item : local_context.as_array()) {
        process_item(result, item, base_url, remote_contexts, override_protected, propagate,
                     validate, in_remote);
      }
    } else {
      process_item(result, local_context, base_url, remote_contexts, override_protected, propagate,
                   validate, in_remote);
    }
  }

  [[noreturn]] void fail(const std::string& code, const std::string& message, SourceLoc loc) const {
    std::string file;
    if (opts_.loader != nullptr && loc.file != 0) file = opts_.loader->files().path(loc.file);
    throw Error(code, message, std::move(file), loc.line, loc.column);
  }

 private:
  const Options& opts_;
  ContextCache::Impl* cache_;
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
                    bool propagate, bool validate, bool in_remote) {
    const SourceLoc loc = context.location();
    // CP 5.1
    if (context.is_null()) {
      // CP 5.1.1
      if (!override_protected && result.has_protected()) {
        fail("invalid context nullification",
             "a null context cannot clear protected term definitions", loc);
      }
      // CP 5.1.2 (a non-propagated result keeps the previous context of CP 3)
      result.reset_terms();
      result.base = result.original_base;
      result.vocab.reset();
      result.language.reset();
      result.direction.reset();
      if (propagate) result.previous = nullptr;
      result.touched_base = true;
      return;
    }
    // CP 5.2
    if (context.is_string()) {
      process_remote(result, context, base_url, remote_contexts, override_protected, validate);
      return;
    }
    // CP 5.3
    if (!context.is_object()) {
      fail("invalid local context",
           "a context must be an object, a string IRI, null or an array of those", loc);
    }
    const json::Object* ctx = &context.as_object();

    // CP 5.5
    if (const json::Value* v = ctx->find("@version")) {
      if (!v->is_number() || (v->as_number() != 1.1 && v->as_number() != 1.2)) {
        fail("invalid @version value", "@version must be the number 1.1", v->location());
      }
      if (json10_) {
        fail("processing mode conflict", "@version 1.1 while processing in json-ld-1.0 mode",
             v->location());
      }
    }
    // CP 5.6
    json::Object merged;
    if (const json::Value* v = ctx->find("@import")) {
      if (json10_) fail("invalid context entry", "@import is not allowed in json-ld-1.0", loc);
      if (!v->is_string()) fail("invalid @import value", "@import must be a string", v->location());
      const std::string import = resolve_context_iri(base_url, v->as_string(), v->location());
      const RemoteDoc& doc = dereference(import, v->location());
      const json::Value* ic = doc.document->get("@context");
      if (ic == nullptr || !ic->is_object()) {
        fail("invalid remote context",
             "imported context " + import + " has no top-level @context object", v->location());
      }
      if (ic->as_object().contains("@import")) {
        fail("invalid context entry", "imported context " + import + " itself contains @import",
             v->location());
      }
      // CP 5.6.7: members of the importing context replace imported ones.
      merged = ic->as_object();
      for (size_t i = 0; i < ctx->size(); ++i) {
        if (ctx->key(i) == "@import") continue;
        size_t at = 0;
        while (at < merged.size() && merged.key(at) != ctx->key(i)) ++at;
        if (at < merged.size()) {
          merged.value(at) = ctx->value(i);
        } else {
          merged.append_new(ctx->key(i), ctx->value(i));
        }
        merged.set_key_location(at, ctx->key_location(i));
      }
      ctx = &merged;
    }
    // CP 5.7
    if (const json::Value* v = ctx->find("@base"); v != nullptr && !in_remote) {
      result.touched_base = true;
      if (v->is_null()) {
        result.base.clear();
      } else if (v->is_string() && rdf::is_absolute_iri(v->as_string())) {
        result.base = v->as_string();
      } else if (v->is_string() && !result.base.empty()) {
        result.base = rdf::resolve_iri(result.base_iri(), v->as_string());
      } else {
        fail("invalid base IRI",
             v->is_string() ? "relative @base " + quoted(v->as_string()) + " without a base IRI"
                            : std::string("@base must be a string or null"),
             v->location());
      }
    }
    // CP 5.8
    if (const json::Value* v = ctx->find("@vocab")) {
      if (v->is_null()) {
        result.vocab.reset();
      } else if (v->is_string() && (!json10_ || rdf::is_absolute_iri(v->as_string()) ||
                                    is_blank_node(v->as_string()))) {
        std::optional<std::string> iri = expand(result, v->as_string(), true, true, nullptr, {});
        if (!iri || is_keyword(*iri)) {
          fail("invalid vocab mapping", "@vocab " + quoted(v->as_string()) + " is not an IRI",
               v->location());
        }
        result.vocab = std::move(iri);
      } else {
        fail("invalid vocab mapping",
             v->is_string() ? "@vocab " + quoted(v->as_string()) +
                                  " must be an absolute IRI or blank node in json-ld-1.0"
                            : std::string("@vocab must be a string or null"),
             v->location());
      }
    }
    // CP 5.9
    if (const json::Value* v = ctx->find("@language")) {
      if (v->is_null()) {
        result.language.reset();
      } else if (v->is_string()) {
        result.language = v->as_string();
      } else {
        fail("invalid default language", "@language must be a string or null", v->location());
      }
    }
    // CP 5.10
    if (const json::Value* v = ctx->find("@direction")) {
      if (json10_) fail("invalid context entry", "@direction is not allowed in json-ld-1.0", loc);
      if (v->is_null()) {
        result.direction.reset();
      } else if (v->is_string() && (v->as_string() == "ltr" || v->as_string() == "rtl")) {
        result.direction = v->as_string();
      } else {
        fail("invalid base direction", "@direction must be \"ltr\", \"rtl\" or null",
             v->location());
      }
    }
    // CP 5.11
    if (const json::Value* v = ctx->find("@propagate")) {
      if (json10_) fail("invalid context entry", "@propagate is not allowed in json-ld-1.0", loc);
      if (!v->is_bool()) {
        fail("invalid @propagate value", "@propagate must be true or false", v->location());
      }
    }
    bool protected_default = false;
    if (const json::Value* v = ctx->find("@protected")) {
      if (!v->is_bool()) {
        fail("invalid @protected value", "@protected must be true or false", v->location());
      }
      protected_default = v->as_bool();
    }
    // CP 5.12, 5.13
    LocalCtx lc(*ctx);
    for (size_t i = 0; i < ctx->size(); ++i) {
      const std::string& key = ctx->key(i);
      if (key == "@base" || key == "@direction" || key == "@import" || key == "@language" ||
          key == "@propagate" || key == "@protected" || key == "@version" || key == "@vocab") {
        continue;
      }
      TermArgs args{base_url, protected_default, override_protected, &remote_contexts, validate};
      create_term(result, lc, i, args);
    }
  }

  std::string resolve_context_iri(const std::string& base_url, const std::string& ref,
                                  SourceLoc loc) const {
    if (rdf::is_absolute_iri(ref)) return ref;
    if (!rdf::is_absolute_iri(base_url)) {
      fail("loading document failed",
           "relative context reference " + quoted(ref) + " without a base IRI", loc);
    }
    return rdf::resolve_iri(base_url, ref);
  }

  // CP 5.2.4, 5.2.5: the remote document (dereferenced at most once).
  const RemoteDoc& dereference(const std::string& iri, SourceLoc loc) {
    auto& docs = cache_ != nullptr ? cache_->documents : local_docs_;
    auto it = docs.find(iri);
    if (it != docs.end()) return it->second;
    if (opts_.loader == nullptr) {
      fail("loading remote context failed",
           "cannot load remote context " + iri + ": no document loader configured", loc);
    }
    RemoteDocument rd;
    try {
      rd = opts_.loader->load(iri, loc, /*for_context=*/true);
    } catch (const Error& e) {
      if (e.code() == "loading remote context failed") throw;
      fail("loading remote context failed",
           "cannot load remote context " + iri + ": " + e.diagnostic().message, loc);
    }
    if (!rd.document || !rd.document->is_object()) {
      fail("invalid remote context", "remote context " + iri + " is not a JSON object", loc);
    }
    if (cache_ != nullptr) ++cache_->stats.documents_loaded;
    RemoteDoc doc{rd.document, rd.document_url.empty() ? iri : rd.document_url};
    return docs.emplace(iri, std::move(doc)).first->second;
  }

  void process_remote(Builder& result, const json::Value& context, const std::string& base_url,
                      std::vector<std::string>& remote_contexts, bool override_protected,
                      bool validate) {
    const SourceLoc loc = context.location();
    // CP 5.2.1
    const std::string iri = resolve_context_iri(base_url, context.as_string(), loc);
    const bool seen =
        std::find(remote_contexts.begin(), remote_contexts.end(), iri) != remote_contexts.end();
    // CP 5.2.2
    if (!validate && seen) return;
    // CP 5.2.3: a context that (transitively) includes itself would recurse
    // forever, so that is reported at once rather than after kMaxRemoteContexts
    // loads. Only the chain of contexts being processed around this one counts:
    // `remote_contexts` also holds earlier siblings, and a context listed twice
    // in one @context array is processed twice, not a cycle.
    if (std::find(chain_.begin(), chain_.end(), iri) != chain_.end()) {
      std::string path;
      for (auto it = std::find(chain_.begin(), chain_.end(), iri); it != chain_.end(); ++it) {
        path.append(*it).append(" -> ");
      }
      path += iri;
      const std::string message = "remote context " + iri + " includes itself (" + path + ")";
      fail(json10_ ? "recursive context inclusion" : "context overflow", message, loc);
    }
    if (chain_.size() >= kMaxRemoteContexts) {
      fail("context overflow",
           "more than " + std::to_string(kMaxRemoteContexts) + " nested remote contexts at " + iri,
           loc);
    }
    remote_contexts.push_back(iri);

    // Not while an enclosing run records dependencies: freezing would move
    // that run's own definitions into the state it is recorded against.
    const bool cacheable =
        cache_ != nullptr && result.parent == nullptr && validate && result.deps == nullptr;
    const unsigned flags = flags_of(opts_, override_protected, true, validate);
    LayerPtr in_terms;
    if (cacheable) {
      result.freeze();
      in_terms = result.layer;
      auto it = cache_->remote.find(iri);
      if (it != cache_->remote.end()) {
        for (const auto& e : it->second) {
          if (e.terms_raw != result.layer.get() || e.flags != flags) continue;
          if (e.terms_raw != nullptr && e.terms.lock().get() != e.terms_raw) continue;
          if (e.vocab != result.vocab || e.language != result.language ||
              e.direction != result.direction)
            continue;
          if (e.used_base && e.base != result.base) continue;
          ++cache_->stats.remote_hits;
          result.layer = e.out_terms;
          result.vocab = e.out_vocab;
          result.language = e.out_language;
          result.direction = e.out_direction;
          if (e.used_base) result.used_base = true;
          return;
        }
      }
      ++cache_->stats.remote_misses;
      auto dit = cache_->remote_deltas.find(iri);
      if (dit != cache_->remote_deltas.end()) {
        for (const detail::Delta& d : dit->second) {
          if (d.flags != flags || d.vocab != result.vocab || d.language != result.language ||
              d.direction != result.direction) {
            continue;
          }
          if (d.used_base && d.base != result.base) continue;
          if (!deps_hold(d.deps, result.layer.get())) continue;
          ++cache_->stats.delta_hits;
          const std::string in_base = result.base;
          apply_delta(result, d);
          store_remote(iri, flags, in_terms, d.vocab, d.language, d.direction, d.used_base, in_base,
                       result);
          return;
        }
      }
    }

    // A context listed twice is processed twice, so contexts that each list
    // the next one twice would take 2^depth steps: the total is bounded too.
    if (++remote_processed_ > kMaxRemoteProcessing) {
      fail("context overflow",
           "more than " + std::to_string(kMaxRemoteProcessing) +
               " remote contexts processed for one @context (the last one " + iri +
               "); is a context listed many times?",
           loc);
    }

    // CP 5.2.4 - 5.2.5
    const RemoteDoc& doc = dereference(iri, loc);
    const json::Value* loaded = doc.document->get("@context");
    if (loaded == nullptr) {
      fail("invalid remote context", "remote context " + iri + " has no top-level @context entry",
           loc);
    }
    // Keep the document alive even if the cache is cleared while processing it.
    const std::shared_ptr<const json::Value> keep = doc.document;
    const std::string doc_url = doc.url;

    // CP 5.2.6
    detail::Delta delta;
    delta.flags = flags;
    delta.vocab = result.vocab;
    delta.language = result.language;
    delta.direction = result.direction;
    const std::string in_base = result.base;
    const ContextPtr in_previous = result.previous;
    const bool saved_used = result.used_base, saved_touched = result.touched_base;
    result.used_base = false;
    result.touched_base = false;
    std::vector<std::string> copy = remote_contexts;
    detail::DepLog log;
    {
      DepRecording recording(result, cacheable ? &log : nullptr);
      ChainEntry in_chain(chain_, iri);
      process(result, nullptr, *loaded, doc_url, copy, override_protected, true, validate,
              /*in_remote=*/true);
    }
    if (cacheable && !result.touched_base && result.previous == in_previous) {
      delta.used_base = result.used_base;
      if (delta.used_base) delta.base = in_base;
      if (!log.opaque) {
        delta.deps = unique_deps(std::move(log.deps));
        delta.changes = result.overlay;
        delta.out_vocab = result.vocab;
        delta.out_language = result.language;
        delta.out_direction = result.direction;
      }
      result.freeze();
      store_remote(iri, flags, in_terms, delta.vocab, delta.language, delta.direction,
                   delta.used_base, in_base, result);
      if (!log.opaque) cache_->remote_deltas[iri].push_back(std::move(delta));
    }
    result.used_base = result.used_base || saved_used;
    result.touched_base = result.touched_base || saved_touched;
  }

  // Records the remote level's entry: `iri` applied to (in_terms, vocab,
  // language, direction[, base]) gave `result` (frozen).
  void store_remote(const std::string& iri, unsigned flags, const LayerPtr& in_terms,
                    const std::optional<std::string>& vocab,
                    const std::optional<std::string>& language,
                    const std::optional<std::string>& direction, bool used_base,
                    const std::string& base, const Builder& result) {
    ContextCache::Impl::RemoteEntry e;
    e.terms = in_terms;
    e.terms_raw = in_terms.get();
    e.vocab = vocab;
    e.language = language;
    e.direction = direction;
    e.flags = flags;
    e.used_base = used_base;
    if (used_base) e.base = base;
    e.out_terms = result.layer;
    e.out_vocab = result.vocab;
    e.out_language = result.language;
    e.out_direction = result.direction;
    cache_->remote[iri].push_back(std::move(e));
  }

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
                                    bool vocab, LocalCtx* lc, const std::optional<TermArgs>& args) {
    // IE 1
    if (is_keyword(value)) return std::string(value);
    // IE 2
    if (has_keyword_form(value)) return std::nullopt;
    // IE 3
    if (lc != nullptr) {
      const size_t i = lc->find(value);
      if (i != std::string::npos && lc->state[i] != LocalCtx::Defined) {
        create_term(active, *lc, i, *args);
      }
    }
    const TermDefinition* def = active.find(value);
    // IE 4
    if (def != nullptr && def->iri && is_keyword(*def->iri)) return def->iri;
    // IE 5
    if (vocab && def != nullptr) return def->iri;
    // IE 6
    const size_t colon = value.find(':', 1);
    if (colon != std::string_view::npos) {
      // IE 6.1
      const std::string_view prefix = value.substr(0, colon);
      const std::string_view suffix = value.substr(colon + 1);
      // IE 6.2
      if (prefix == "_" || suffix.starts_with("//")) return std::string(value);
      // IE 6.3
      if (lc != nullptr) {
        const size_t i = lc->find(prefix);
        if (i != std::string::npos && lc->state[i] != LocalCtx::Defined) {
          create_term(active, *lc, i, *args);
        }
      }
      // IE 6.4
      const TermDefinition* pdef = active.find(prefix);
      if (pdef != nullptr && pdef->iri && pdef->prefix) {
        std::string out = *pdef->iri;
        out += suffix;
        return out;
      }
      // IE 6.5
      if (rdf::is_absolute_iri(value)) return std::string(value);
    }
    // IE 7
    if (vocab && active.vocab) return *active.vocab + std::string(value);
    // IE 8
    if (document_relative) return rdf::resolve_iri(active.base_iri(), value);
    // IE 9
    return std::string(value);
  }

  // A term definition's value as the map of CTD 7 - 9 without building it: a
  // string or null value stands for {"@id": value}.
  struct TermValue {
    const json::Object* obj = nullptr;
    const json::Value* id_only = nullptr;
    const json::Value* find(std::string_view key) const {
      if (obj != nullptr) return obj->find(key);
      return key == "@id" ? id_only : nullptr;
    }
    bool contains(std::string_view key) const { return find(key) != nullptr; }
    size_t size() const { return obj != nullptr ? obj->size() : 0; }
    const std::string& key(size_t i) const { return obj->key(i); }
    SourceLoc key_location(size_t i) const { return obj->key_location(i); }
  };

  // Create Term Definition (4.2.2) for member `idx` of the local context.
  void create_term(Builder& active, LocalCtx& lc, size_t idx, const TermArgs& args) {
    const std::string& term = lc.obj->key(idx);
    const SourceLoc where = lc.obj->key_location(idx);
    const json::Value& value = lc.obj->value(idx);
    // Only error paths need the display name.
    auto name = [&term] { return "term " + quoted(term); };
    // CTD 1
    if (lc.state[idx] == LocalCtx::Defined) return;
    if (lc.state[idx] == LocalCtx::InProgress) {
      fail("cyclic IRI mapping", name() + " depends on itself", where);
    }
    // CTD 2
    if (term.empty()) fail("invalid term definition", "the empty string cannot be a term", where);
    lc.state[idx] = LocalCtx::InProgress;
    if (cache_ != nullptr) ++cache_->stats.terms_defined;
    // CTD 4
    if (term == "@type") {
      bool ok = !json10_ && value.is_object() && !value.as_object().empty();
      if (ok) {
        const json::Object& o = value.as_object();
        for (size_t i = 0; i < o.size(); ++i) {
          if (o.key(i) == "@container") {
            ok = ok && o.value(i).is_string() && o.value(i).as_string() == "@set";
          } else if (o.key(i) != "@protected") {
            ok = false;
          }
        }
      }
      if (!ok) {
        fail("keyword redefinition",
             json10_ ? std::string("@type cannot be redefined in json-ld-1.0")
                     : std::string("@type may only be given \"@container\": \"@set\" and "
                                   "\"@protected\""),
             where);
      }
    } else if (is_keyword(term)) {
      // CTD 5
      fail("keyword redefinition", "keyword " + term + " cannot be redefined", where);
    } else if (has_keyword_form(term)) {
      warn(name() + " has the form of a keyword and is ignored", where);
      lc.state[idx] = LocalCtx::Defined;
      return;
    }
    // CTD 6
    TermPtr previous;
    if (const TermPtr* p = active.lookup_previous(term)) previous = *p;
    if (previous) active.set(term, nullptr);
    // CTD 7 - 9
    TermValue tv;
    const TermValue* v = &tv;
    bool simple_term = false;
    if (value.is_null() || value.is_string()) {
      tv.id_only = &value;
      simple_term = value.is_string();
    } else if (value.is_object()) {
      tv.obj = &value.as_object();
    } else {
      fail("invalid term definition", name() + " must be defined by a string, null or an object",
           value.location());
    }
    // CTD 10
    auto def = std::make_shared<TermDefinition>();
    def->protected_ = args.protected_default;
    def->where = where;
    // CTD 11
    if (const json::Value* p = v->find("@protected")) {
      if (json10_) {
        fail("invalid term definition", name() + ": @protected is not allowed in json-ld-1.0",
             p->location());
      }
      if (!p->is_bool()) {
        fail("invalid @protected value", name() + ": @protected must be true or false",
             p->location());
      }
      def->protected_ = p->as_bool();
    }
    // CTD 12
    if (const json::Value* t = v->find("@type")) {
      if (!t->is_string()) {
        fail("invalid type mapping", name() + ": @type must be a string", t->location());
      }
      std::optional<std::string> type = expand(active, t->as_string(), false, true, &lc, args);
      if (type && (*type == "@json" || *type == "@none") && json10_) {
        fail("invalid type mapping", name() + ": @type " + *type + " requires json-ld-1.1",
             t->location());
      }
      if (!type || !(*type == "@id" || *type == "@json" || *type == "@none" || *type == "@vocab" ||
                     rdf::is_absolute_iri(*type))) {
        fail("invalid type mapping",
             name() + ": @type " + quoted(t->as_string()) +
                 " must be @id, @vocab, @json, @none or an absolute IRI",
             t->location());
      }
      def->type = std::move(type);
    }
    // CTD 13
    if (const json::Value* r = v->find("@reverse")) {
      if (v->contains("@id") || v->contains("@nest")) {
        fail("invalid reverse property", name() + ": @reverse cannot be combined with @id or @nest",
             r->location());
      }
      if (!r->is_string()) {
        fail("invalid IRI mapping", name() + ": @reverse must be a string", r->location());
      }
      if (has_keyword_form(r->as_string())) {
        warn(name() + ": @reverse value " + r->as_string() +
                 " has the form of a keyword; the definition is ignored",
             r->location());
        lc.state[idx] = LocalCtx::Defined;
        return;
      }
      std::optional<std::string> iri = expand(active, r->as_string(), false, true, &lc, args);
      if (!iri || !(rdf::is_absolute_iri(*iri) || is_blank_node(*iri)) || is_keyword(*iri)) {
        fail("invalid IRI mapping",
             name() + ": @reverse " + quoted(r->as_string()) +
                 " does not expand to an IRI or blank node identifier",
             r->location());
      }
      def->iri = std::move(iri);
      if (const json::Value* c = v->find("@container")) {
        if (!(c->is_null() ||
              (c->is_string() && (c->as_string() == "@set" || c->as_string() == "@index")))) {
          fail("invalid reverse property",
               name() + ": a reverse property's @container must be @set, @index or null",
               c->location());
        }
        if (c->is_string()) def->container.insert(c->as_string());
      }
      def->reverse = true;
    } else if (const json::Value* id = v->find("@id");
               id != nullptr && !(id->is_string() && id->as_string() == term)) {
      // CTD 14
      if (id->is_null()) {
        // CTD 14.1: kept (with no IRI mapping) to detect later redefinitions.
      } else {
        if (!id->is_string()) {
          fail("invalid IRI mapping", name() + ": @id must be a string or null", id->location());
        }
        const std::string& idv = id->as_string();
        // CTD 14.2.2
        if (!is_keyword(idv) && has_keyword_form(idv)) {
          warn(name() + ": @id " + idv + " has the form of a keyword; the definition is ignored",
               id->location());
          lc.state[idx] = LocalCtx::Defined;
          return;
        }
        // CTD 14.2.3
        std::optional<std::string> iri = expand(active, idv, false, true, &lc, args);
        if (!iri || !(is_keyword(*iri) || rdf::is_absolute_iri(*iri) || is_blank_node(*iri))) {
          fail("invalid IRI mapping",
               name() + ": @id " + quoted(idv) +
                   " does not expand to a keyword, an IRI or a blank node identifier",
               id->location());
        }
        if (*iri == "@context") {
          fail("invalid keyword alias", name() + ": @context cannot be aliased", id->location());
        }
        def->iri = std::move(iri);
        // CTD 14.2.4
        const size_t colon = term.find(':', 1);
        if ((colon != std::string::npos && colon + 1 < term.size()) ||
            term.find('/') != std::string::npos) {
          lc.state[idx] = LocalCtx::Defined;
          std::optional<std::string> self = expand(active, term, false, true, &lc, args);
          if (self != def->iri) {
            fail("invalid IRI mapping",
                 name() + " looks like an IRI but @id maps it to " + quoted(*def->iri) +
                     " instead of " + quoted(self.value_or("null")),
                 id->location());
          }
        }
        // CTD 14.2.5
        if (term.find(':') == std::string::npos && term.find('/') == std::string::npos &&
            simple_term && (ends_with_gen_delim(*def->iri) || is_blank_node(*def->iri))) {
          def->prefix = true;
        }
      }
    } else if (term.find(':', 1) != std::string::npos) {
      // CTD 15
      const size_t colon = term.find(':', 1);
      const std::string_view prefix = std::string_view(term).substr(0, colon);
      const std::string_view suffix = std::string_view(term).substr(colon + 1);
      // CTD 15.1
      const size_t pi = lc.find(prefix);
      if (pi != std::string::npos && !(prefix == "_" || suffix.starts_with("//"))) {
        create_term(active, lc, pi, args);
      }
      // CTD 15.2, 15.3
      const TermDefinition* pdef = active.find(prefix);
      if (pdef != nullptr && pdef->iri) {
        def->iri = *pdef->iri + std::string(suffix);
      } else {
        def->iri = term;
      }
    } else if (term.find('/') != std::string::npos) {
      // CTD 16
      std::optional<std::string> iri = expand(active, term, true, true, nullptr, {});
      if (!iri || !rdf::is_absolute_iri(*iri)) {
        fail("invalid IRI mapping", name() + " is a relative IRI that does not expand to an IRI",
             where);
      }
      def->iri = std::move(iri);
    } else if (term == "@type") {
      // CTD 17
      def->iri = "@type";
    } else if (active.vocab) {
      // CTD 18
      def->iri = *active.vocab + term;
    } else {
      fail("invalid IRI mapping",
           name() + " has no @id and there is no @vocab to derive its IRI from", where);
    }
    // CTD 19
    if (const json::Value* c = v->find("@container"); c != nullptr && !def->reverse) {
      validate_container(term, *c, *def);
    }
    // CTD 20
    if (const json::Value* ix = v->find("@index")) {
      if (json10_ || !def->container.contains("@index")) {
        fail("invalid term definition",
             name() + ": @index requires json-ld-1.1 and an @index container", ix->location());
      }
      std::optional<std::string> e;
      if (ix->is_string()) e = expand(active, ix->as_string(), false, true, nullptr, {});
      if (!ix->is_string() || !e || !rdf::is_absolute_iri(*e) || is_keyword(ix->as_string())) {
        fail("invalid term definition", name() + ": @index must be a property (not a keyword)",
             ix->location());
      }
      def->index = ix->as_string();
    }
    // CTD 21
    if (const json::Value* sc = v->find("@context")) {
      if (json10_) {
        fail("invalid term definition", name() + ": scoped contexts require json-ld-1.1",
             sc->location());
      }
      // CTD 21.3: processed now to report errors where the definition is
      // written; the result is discarded.
      if (cache_ != nullptr) ++cache_->stats.scoped_validations;
      try {
        Builder scratch;
        scratch.parent = &active;
        scratch.base = active.base;
        scratch.original_base = active.original_base;
        scratch.vocab = active.vocab;
        scratch.language = active.language;
        scratch.direction = active.direction;
        std::vector<std::string> remote = *args.remote_contexts;
        process(scratch, nullptr, *sc, args.base_url, remote, true, true, false, false);
        if (scratch.used_base) active.used_base = true;
      } catch (const Error& e) {
        fail("invalid scoped context",
             name() + ": invalid scoped context: " + e.diagnostic().message +
                 (e.code() == "invalid scoped context" ? "" : " (" + e.code() + ")"),
             sc->location());
      }
      // CTD 21.4
      def->local_context = *sc;
      def->base_url = args.base_url;
    }
    // CTD 22
    if (const json::Value* l = v->find("@language"); l != nullptr && !v->contains("@type")) {
      if (!l->is_null() && !l->is_string()) {
        fail("invalid language mapping", name() + ": @language must be a string or null",
             l->location());
      }
      def->language = *l;
    }
    // CTD 23
    if (const json::Value* d = v->find("@direction"); d != nullptr && !v->contains("@type")) {
      if (!(d->is_null() ||
            (d->is_string() && (d->as_string() == "ltr" || d->as_string() == "rtl")))) {
        fail("invalid base direction", name() + ": @direction must be \"ltr\", \"rtl\" or null",
             d->location());
      }
      def->direction = *d;
    }
    // CTD 24
    if (const json::Value* n = v->find("@nest")) {
      if (json10_) {
        fail("invalid term definition", name() + ": @nest requires json-ld-1.1", n->location());
      }
      if (!n->is_string() || (is_keyword(n->as_string()) && n->as_string() != "@nest")) {
        fail("invalid @nest value", name() + ": @nest must be a term or @nest", n->location());
      }
      def->nest = n->as_string();
    }
    // CTD 25
    if (const json::Value* p = v->find("@prefix")) {
      if (json10_ || term.find(':') != std::string::npos || term.find('/') != std::string::npos) {
        fail("invalid term definition",
             name() + ": @prefix requires json-ld-1.1 and a term without ':' or '/'",
             p->location());
      }
      if (!p->is_bool()) {
        fail("invalid @prefix value", name() + ": @prefix must be true or false", p->location());
      }
      def->prefix = p->as_bool();
      if (def->prefix && def->iri && is_keyword(*def->iri)) {
        fail("invalid term definition", name() + ": a keyword alias cannot be a prefix",
             p->location());
      }
    }
    // CTD 26
    for (size_t i = 0; i < v->size(); ++i) {
      const std::string& k = v->key(i);
      if (k != "@id" && k != "@reverse" && k != "@container" && k != "@context" &&
          k != "@direction" && k != "@index" && k != "@language" && k != "@nest" &&
          k != "@prefix" && k != "@protected" && k != "@type") {
        fail("invalid term definition", name() + ": unexpected entry " + quoted(k),
             v->key_location(i));
      }
    }
    // CTD 27
    TermPtr final_def = def;
    if (!args.override_protected && previous && previous->protected_) {
      if (!(*def == *previous)) {
        std::string first;
        if (previous->where.known()) {
          first = " (protected definition at ";
          if (opts_.loader != nullptr && previous->where.file != 0) {
            first += opts_.loader->files().path(previous->where.file) + ":";
          }
          first += std::to_string(previous->where.line) + ":" +
                   std::to_string(previous->where.column) + ")";
        }
        fail("protected term redefinition",
             name() + " is protected and cannot be redefined" + first, where);
      }
      final_def = previous;
    }
    if (cache_ != nullptr && final_def->local_context && final_def == def) {
      cache_->register_owner(final_def);
    }
    // CTD 28
    active.set(term, std::move(final_def));
    lc.state[idx] = LocalCtx::Defined;
  }

  void validate_container(std::string_view term, const json::Value& c, TermDefinition& def) {
    auto bad = [&](const std::string& why) {
      fail("invalid container mapping", "term " + quoted(term) + ": " + why, c.location());
    };
    // CTD 19.2
    if (json10_) {
      if (!c.is_string()) bad("@container must be a string in json-ld-1.0");
      const std::string& s = c.as_string();
      if (s == "@graph" || s == "@id" || s == "@type")
        bad("@container " + s + " requires json-ld-1.1");
    }
    std::set<std::string> values;
    auto add = [&](const json::Value& e) {
      static constexpr std::array<std::string_view, 7> kContainers = {
          "@graph", "@id", "@index", "@language", "@list", "@set", "@type"};
      if (!e.is_string() ||
          std::find(kContainers.begin(), kContainers.end(), e.as_string()) == kContainers.end()) {
        bad("@container values must be @graph, @id, @index, @language, @list, @set or @type");
      }
      values.insert(e.as_string());
    };
    if (c.is_array()) {
      for (const auto& e : c.as_array()) add(e);
    } else {
      add(c);
    }
    // CTD 19.1: the allowed combinations.
    const bool has_set = values.contains("@set");
    if (values.contains("@list")) {
      if (values.size() != 1) bad("@list cannot be combined with other containers");
    } else if (values.contains("@graph")) {
      for (const auto& s : values) {
        if (s != "@graph" && s != "@id" && s != "@index" && s != "@set") {
          bad("@graph can only be combined with @id or @index and @set");
        }
      }
      if (values.contains("@id") && values.contains("@index")) {
        bad("@graph cannot be combined with both @id and @index");
      }
    } else if (values.size() > (has_set ? 2u : 1u)) {
      bad("@set can be combined with only one of @index, @id, @type or @language");
    }
    def.container = std::move(values);
    // CTD 19.4
    if (def.container.contains("@type")) {
      if (!def.type) def.type = "@id";
      if (*def.type != "@id" && *def.type != "@vocab") {
        fail("invalid type mapping",
             "term " + quoted(term) + ": a @type container requires @type @id or @vocab",
             c.location());
      }
    }
  }
};

}  // namespace

namespace {

// Whether a local context names a remote context (a string, or a string in
// an array).
bool has_remote_reference(const json::Value& local_context) {
  if (local_context.is_string()) return true;
  if (!local_context.is_array()) return false;
  const json::Array& items = local_context.as_array();
  return std::any_of(items.begin(), items.end(),
                     [](const json::Value& v) { return v.is_string(); });
}

void store_exact(ContextCache::Impl& cache, const ContextPtr& active, const TermPtr& owner,
                 const json::Value& local_context, const std::string& base_url, unsigned flags,
                 size_t key, const ContextPtr& result) {
  ContextCache::Impl::ExactEntry e;
  e.active = active;
  e.active_raw = active.get();
  if (owner) {
    e.owner = owner;
  } else {
    e.content = local_context;
  }
  e.base_url = base_url;
  e.flags = flags;
  e.result = result;
  cache.exact[key].push_back(std::move(e));
}

}  // namespace

ContextPtr process_context(const ContextPtr& active, const json::Value& local_context,
                           const std::string& base_url, const Options& options,
                           std::vector<std::string>* remote_contexts, bool override_protected,
                           bool propagate, bool validate_scoped_context) {
  Processor proc(options);
  ContextCache::Impl* cache = proc.cache();
  const bool exact_cacheable = cache != nullptr && validate_scoped_context &&
                               (remote_contexts == nullptr || remote_contexts->empty());
  const unsigned flags = flags_of(options, override_protected, propagate, validate_scoped_context);
  TermPtr owner;
  size_t key = 0;
  size_t content_hash = 0;
  if (exact_cacheable) {
    // A scoped context passed by reference from its term definition is known by
    // address (the entry pins the definition), which saves hashing and
    // comparing its content; anything else is looked up by content.
    if (auto it = cache->owners.find(&local_context); it != cache->owners.end()) {
      owner = it->second.def.lock();
      if (owner && owner->local_context && &*owner->local_context == &local_context) {
        content_hash = it->second.hash;
      } else {
        owner.reset();
      }
    }
    if (!owner) content_hash = hash_json(local_context);
    key = mix(std::hash<const void*>{}(active.get()), content_hash);
    key = mix(key, std::hash<std::string_view>{}(base_url));
    auto it = cache->exact.find(key);
    if (it != cache->exact.end()) {
      for (const auto& e : it->second) {
        if (e.active_raw != active.get() || e.flags != flags || e.base_url != base_url) continue;
        if (e.active.lock().get() != active.get()) continue;
        if (!(owner && e.owner == owner)) {
          const json::Value& stored = e.owner ? *e.owner->local_context : e.content;
          if (!(stored == local_context)) continue;
        }
        ++cache->stats.exact_hits;
        return e.result;
      }
    }
    ++cache->stats.exact_misses;
  }
  // CP 2, 3: whether the result keeps `active` as its previous context.
  bool effective_propagate = propagate;
  if (const json::Value* p = local_context.get("@propagate"); p != nullptr && p->is_bool()) {
    effective_propagate = p->as_bool();
  }
  const ActiveContext::Impl& in = active->impl();
  const ContextPtr expected_previous = !effective_propagate && !in.previous ? active : in.previous;
  size_t state_key = 0;
  if (exact_cacheable) {
    state_key = mix(mix(std::hash<const void*>{}(in.terms.get()), content_hash),
                    std::hash<std::string_view>{}(base_url));
    auto it = cache->states.find(state_key);
    if (it != cache->states.end()) {
      for (const auto& se : it->second) {
        const auto& e = se.state;
        if (e.terms_raw != in.terms.get() || e.flags != flags || se.base_url != base_url) continue;
        if (e.terms_raw != nullptr && e.terms.lock().get() != e.terms_raw) continue;
        if (e.vocab != in.vocab || e.language != in.language || e.direction != in.direction) {
          continue;
        }
        if (e.used_base && e.base != in.base) continue;
        if (!(owner && se.owner == owner)) {
          const json::Value& stored = se.owner ? *se.owner->local_context : se.content;
          if (!(stored == local_context)) continue;
        }
        ++cache->stats.state_hits;
        auto impl = std::make_shared<ActiveContext::Impl>();
        impl->terms = e.out_terms;
        impl->base = in.base;
        impl->original_base = in.original_base;
        impl->vocab = e.out_vocab;
        impl->language = e.out_language;
        impl->direction = e.out_direction;
        impl->previous = expected_previous;
        ContextPtr out = std::make_shared<const ActiveContext>(std::move(impl));
        store_exact(*cache, active, owner, local_context, base_url, flags, key, out);
        return out;
      }
    }
  }

  // Stores the term-state entry for a result computed from `active`.
  auto store_state = [&](const Builder& result) {
    ContextCache::Impl::StateEntry se;
    se.state.terms = in.terms;
    se.state.terms_raw = in.terms.get();
    se.state.vocab = in.vocab;
    se.state.language = in.language;
    se.state.direction = in.direction;
    se.state.flags = flags;
    se.state.used_base = result.used_base;
    if (result.used_base) se.state.base = in.base;
    se.state.out_terms = result.layer;
    se.state.out_vocab = result.vocab;
    se.state.out_language = result.language;
    se.state.out_direction = result.direction;
    if (owner) {
      se.owner = owner;
    } else {
      se.content = local_context;
    }
    se.base_url = base_url;
    cache->states[state_key].push_back(std::move(se));
  };

  // The delta level, for contexts that reference no remote context (those are
  // cached per remote context instead).
  const bool delta_cacheable = exact_cacheable && !has_remote_reference(local_context);
  size_t delta_key = 0;
  if (delta_cacheable) {
    delta_key = mix(content_hash, std::hash<std::string_view>{}(base_url));
    auto it = cache->local_deltas.find(delta_key);
    if (it != cache->local_deltas.end()) {
      for (const auto& ld : it->second) {
        const detail::Delta& d = ld.delta;
        if (d.flags != flags || ld.base_url != base_url) continue;
        if (d.vocab != in.vocab || d.language != in.language || d.direction != in.direction) {
          continue;
        }
        if (d.used_base && d.base != in.base) continue;
        if (!(owner && ld.owner == owner)) {
          const json::Value& stored = ld.owner ? *ld.owner->local_context : ld.content;
          if (!(stored == local_context)) continue;
        }
        if (!deps_hold(d.deps, in.terms.get())) continue;
        ++cache->stats.delta_hits;
        Builder result(*active);
        apply_delta(result, d);
        result.previous = expected_previous;
        ContextPtr out = result.to_context();
        store_exact(*cache, active, owner, local_context, base_url, flags, key, out);
        store_state(result);
        return out;
      }
    }
  }

  // CP 1
  Builder result(*active);
  std::vector<std::string> local_remote;
  std::vector<std::string>& remote = remote_contexts != nullptr ? *remote_contexts : local_remote;
  detail::DepLog log;
  {
    DepRecording recording(result, delta_cacheable ? &log : nullptr);
    proc.process(result, &active, local_context, base_url, remote, override_protected, propagate,
                 validate_scoped_context, /*in_remote=*/false);
  }
  const bool state_cacheable =
      exact_cacheable && !result.touched_base && result.previous == expected_previous;
  if (state_cacheable && delta_cacheable && !log.opaque) {
    ContextCache::Impl::LocalDelta ld;
    detail::Delta& d = ld.delta;
    d.flags = flags;
    d.vocab = in.vocab;
    d.language = in.language;
    d.direction = in.direction;
    d.used_base = result.used_base;
    if (d.used_base) d.base = in.base;
    d.deps = unique_deps(std::move(log.deps));
    d.changes = result.overlay;
    d.out_vocab = result.vocab;
    d.out_language = result.language;
    d.out_direction = result.direction;
    if (owner) {
      ld.owner = owner;
    } else {
      ld.content = local_context;
    }
    ld.base_url = base_url;
    cache->local_deltas[delta_key].push_back(std::move(ld));
  }
  ContextPtr out = result.to_context();

  if (exact_cacheable) {
    store_exact(*cache, active, owner, local_context, base_url, flags, key, out);
    if (state_cacheable) store_state(result);
  }
  return out;
}

std::optional<std::string> expand_iri(const ActiveContext& active, std::string_view value,
                                      bool document_relative, bool vocab) {
  // IE 1
  if (!value.empty() && value[0] == '@') {
    if (is_keyword(value)) return std::string(value);
    // IE 2
    if (has_keyword_form(value)) return std::nullopt;
  }
  const TermDefinition* def = active.find(value);
  if (def != nullptr) {
    // IE 4
    if (def->iri && is_keyword(*def->iri)) return def->iri;
    // IE 5
    if (vocab) return def->iri;
  }
  // IE 6
  const size_t colon = value.find(':', 1);
  if (colon != std::string_view::npos) {
    const std::string_view prefix = value.substr(0, colon);
    const std::string_view suffix = value.substr(colon + 1);
    if (prefix == "_" || suffix.starts_with("//")) return std::string(value);
    const TermDefinition* pdef = active.find(prefix);
    if (pdef != nullptr && pdef->iri && pdef->prefix) {
      std::string out = *pdef->iri;
      out += suffix;
      return out;
    }
    if (rdf::is_absolute_iri(value)) return std::string(value);
  }
  // IE 7
  if (vocab && active.vocab()) return *active.vocab() + std::string(value);
  // IE 8
  if (document_relative) return rdf::resolve_iri(active.base(), value);
  return std::string(value);
}

}  // namespace mospec::jsonld
