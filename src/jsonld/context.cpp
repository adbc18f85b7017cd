// Keywords, term definitions, ActiveContext and ContextCache. The algorithms
// that build contexts are in context_processing.hpp and the files it lists.
#include "jsonld/context.hpp"

#include "jsonld/context_processing.hpp"

namespace mospec::jsonld {

using namespace internal;

bool is_keyword(std::string_view s) {
  if (s.size() < 3 || s[0] != '@') return false;
  // By length, so that a key is compared with at most four keywords.
  switch (s.size()) {
    case 3:
      return s == "@id";
    case 4:
      return s == "@set";
    case 5:
      return s == "@type" || s == "@list" || s == "@none" || s == "@base" || s == "@json" ||
             s == "@nest";
    case 6:
      return s == "@value" || s == "@graph" || s == "@index" || s == "@vocab";
    case 7:
      return s == "@import" || s == "@prefix";
    case 8:
      return s == "@context" || s == "@reverse" || s == "@version";
    case 9:
      return s == "@language" || s == "@included";
    case 10:
      return s == "@container" || s == "@direction" || s == "@propagate" || s == "@protected";
    default:
      return false;
  }
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
         (local_context == o.local_context ||
          (local_context && o.local_context && *local_context == *o.local_context)) &&
         container == o.container && direction == o.direction && language == o.language &&
         index == o.index && nest == o.nest && type == o.type;
}

// ---------------------------------------------------------------------------
// ActiveContext

ContextPtr ActiveContext::initial(std::string base, const Options&) {
  Impl impl;
  impl.original_base = detail::SharedString(base);
  impl.base = impl.original_base;
  return internal::make_context(std::move(impl));
}

const std::string& ActiveContext::base() const {
  return impl_->base.str();
}
const std::string& ActiveContext::original_base() const {
  return impl_->original_base.str();
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

void ActiveContext::for_each_term(const std::function<void(std::string_view)>& visit) const {
  for (const TermLayer* l = impl_->terms.get(); l != nullptr; l = l->parent.get()) {
    for (const auto& [k, v] : l->defs) {
      if (v && find(k) != nullptr) visit(k);
    }
  }
}

bool ActiveContext::has_protected_terms() const {
  return impl_->terms && impl_->terms->protected_count != 0;
}

// ---------------------------------------------------------------------------
// ContextCache

ContextCache::ContextCache() : impl_(std::make_unique<Impl>()) {}
ContextCache::~ContextCache() = default;
ContextCache::Stats ContextCache::stats() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->stats;
}
void ContextCache::clear() {
  impl_ = std::make_unique<Impl>();
}

}  // namespace mospec::jsonld
