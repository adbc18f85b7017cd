// Context Processing (JSON-LD 1.1 Processing Algorithms 4.1) and process_context().
#include "jsonld/context_processing.hpp"

namespace mospec::jsonld::internal {

void Processor::process(Builder& result, const ContextPtr* active, const json::Value& local_context,
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
      process_item(result, item, base_url, remote_contexts, override_protected, propagate, validate,
                   in_remote);
    }
  } else {
    process_item(result, local_context, base_url, remote_contexts, override_protected, propagate,
                 validate, in_remote);
  }
}

void Processor::process_item(Builder& result, const json::Value& context,
                             const std::string& base_url, std::vector<std::string>& remote_contexts,
                             bool override_protected, bool propagate, bool validate,
                             bool in_remote) {
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
  std::optional<OwnerScope> merged_values;  // copies: owned by no document
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
    merged_values.emplace(owner_, nullptr);
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
      fail("invalid base direction", "@direction must be \"ltr\", \"rtl\" or null", v->location());
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
    const std::string_view key = ctx->key(i);
    if (!key.empty() && key[0] == '@' &&
        (key == "@base" || key == "@direction" || key == "@import" || key == "@language" ||
         key == "@propagate" || key == "@protected" || key == "@version" || key == "@vocab")) {
      continue;
    }
    TermArgs args{base_url, protected_default, override_protected, &remote_contexts, validate};
    create_term(result, lc, i, args);
  }
}

std::string Processor::resolve_context_iri(const std::string& base_url, std::string_view ref,
                                           SourceLoc loc) const {
  if (rdf::is_absolute_iri(ref)) return std::string(ref);
  if (!rdf::is_absolute_iri(base_url)) {
    fail("loading document failed",
         "relative context reference " + quoted(ref) + " without a base IRI", loc);
  }
  return rdf::resolve_iri(base_url, ref);
}

const RemoteDoc& Processor::dereference(const std::string& iri, SourceLoc loc) {
  auto& docs = cache_ != nullptr ? cache_->documents : local_docs_;
  {
    std::unique_lock lock = lock_cache();
    auto it = docs.find(iri);
    if (it != docs.end()) return it->second;
  }
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
  RemoteDoc doc{rd.document, rd.document_url.empty() ? iri : rd.document_url};
  std::unique_lock lock = lock_cache();
  if (cache_ != nullptr) ++cache_->stats.documents_loaded;
  return docs.emplace(iri, std::move(doc)).first->second;  // (a node: stays where it is)
}

void Processor::process_remote(Builder& result, const json::Value& context,
                               const std::string& base_url,
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
    fail(json10_ ? DiagnosticCode("recursive context inclusion")
                 : DiagnosticCode("context overflow"),
         message, loc);
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
    std::lock_guard lock(cache_->mutex);
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
        const detail::SharedString in_base = result.base;
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
  const detail::SharedString in_base = result.base;
  const ContextPtr in_previous = result.previous;
  const bool saved_used = result.used_base, saved_touched = result.touched_base;
  result.used_base = false;
  result.touched_base = false;
  // CP 5.2.6 passes a copy of the remote contexts: what processing adds is
  // taken off again afterwards instead of copying every IRI in the list.
  RemoteContextsMark copy(remote_contexts);
  detail::DepLog log;
  if (cacheable) log.reserve(member_count(*loaded));
  {
    DepRecording recording(result, cacheable ? &log : nullptr);
    ChainEntry in_chain(chain_, iri);
    OwnerScope in_document(owner_, keep);
    process(result, nullptr, *loaded, doc_url, remote_contexts, override_protected, true, validate,
            /*in_remote=*/true);
  }
  if (cacheable && !result.touched_base && result.previous == in_previous) {
    delta.used_base = result.used_base;
    if (delta.used_base) delta.base = in_base;
    if (!log.opaque) {
      delta.deps = std::move(log.deps);
      delta.changes = result.overlay;
      delta.out_vocab = result.vocab;
      delta.out_language = result.language;
      delta.out_direction = result.direction;
    }
    result.freeze();
    std::lock_guard lock(cache_->mutex);
    store_remote(iri, flags, in_terms, delta.vocab, delta.language, delta.direction,
                 delta.used_base, in_base, result);
    if (!log.opaque) cache_->remote_deltas[iri].push_back(std::move(delta));
  }
  result.used_base = result.used_base || saved_used;
  result.touched_base = result.touched_base || saved_touched;
}

void Processor::store_remote(const std::string& iri, unsigned flags, const LayerPtr& in_terms,
                             const std::optional<std::string>& vocab,
                             const std::optional<std::string>& language,
                             const std::optional<std::string>& direction, bool used_base,
                             const detail::SharedString& base, const Builder& result) {
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

}  // namespace mospec::jsonld::internal

namespace mospec::jsonld {

using namespace internal;

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
    std::lock_guard lock(cache->mutex);
    // A scoped context passed by reference from its term definition is known by
    // address (the entry pins the definition), which saves hashing and
    // comparing its content; anything else is looked up by content.
    if (auto it = cache->owners.find(&local_context); it != cache->owners.end()) {
      owner = it->second.def.lock();
      if (owner && owner->local_context && &*owner->local_context == &local_context) {
        if (!it->second.hash) it->second.hash = hash_json(local_context);
        content_hash = *it->second.hash;
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
    std::lock_guard lock(cache->mutex);
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
        ActiveContext::Impl impl;
        impl.terms = e.out_terms;
        impl.base = in.base;
        impl.original_base = in.original_base;
        impl.vocab = e.out_vocab;
        impl.language = e.out_language;
        impl.direction = e.out_direction;
        impl.previous = expected_previous;
        ContextPtr out = internal::make_context(std::move(impl));
        store_exact(*cache, active, owner, local_context, base_url, flags, key, out);
        return out;
      }
    }
  }

  // Stores the term-state entry for a result computed from `active` (with
  // the cache's lock held).
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
    std::lock_guard lock(cache->mutex);
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
  if (delta_cacheable) log.reserve(member_count(local_context));
  {
    DepRecording recording(result, delta_cacheable ? &log : nullptr);
    proc.process(result, &active, local_context, base_url, remote, override_protected, propagate,
                 validate_scoped_context, /*in_remote=*/false);
  }
  const bool state_cacheable =
      exact_cacheable && !result.touched_base && result.previous == expected_previous;
  // (The delta takes the overlay before to_context() moves it into a layer.)
  std::optional<ContextCache::Impl::LocalDelta> local_delta;
  if (state_cacheable && delta_cacheable && !log.opaque) {
    ContextCache::Impl::LocalDelta& ld = local_delta.emplace();
    detail::Delta& d = ld.delta;
    d.flags = flags;
    d.vocab = in.vocab;
    d.language = in.language;
    d.direction = in.direction;
    d.used_base = result.used_base;
    if (d.used_base) d.base = in.base;
    d.deps = std::move(log.deps);
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
  }
  ContextPtr out = result.to_context();
  if (!exact_cacheable) return out;
  std::lock_guard lock(cache->mutex);
  if (local_delta) cache->local_deltas[delta_key].push_back(std::move(*local_delta));
  store_exact(*cache, active, owner, local_context, base_url, flags, key, out);
  if (state_cacheable) store_state(result);
  return out;
}

}  // namespace mospec::jsonld
