// IRI Expansion (JSON-LD 1.1 Processing Algorithms 4.3): during context
// processing (Processor::expand) and for expansion (expand_iri()).
#include "jsonld/context_processing.hpp"

namespace mospec::jsonld::internal {

std::optional<std::string> Processor::expand(Builder& active, std::string_view value,
                                             bool document_relative, bool vocab, LocalCtx* lc,
                                             const std::optional<TermArgs>& args) {
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
      std::string out;
      out.reserve(pdef->iri->size() + suffix.size());
      out.append(*pdef->iri).append(suffix);
      return out;
    }
    // IE 6.5
    if (rdf::is_absolute_iri(value)) return std::string(value);
  }
  // IE 7
  if (vocab && active.vocab) {
    std::string out;
    out.reserve(active.vocab->size() + value.size());
    out.append(*active.vocab).append(value);
    return out;
  }
  // IE 8
  if (document_relative) return rdf::resolve_iri(active.base_iri(), value);
  // IE 9
  return std::string(value);
}

}  // namespace mospec::jsonld::internal

namespace mospec::jsonld {

using namespace internal;

std::optional<std::string> expand_iri(const ActiveContext& active, std::string_view value,
                                      bool document_relative, bool vocab) {
  return internal::expand_iri(active, value, document_relative, vocab, nullptr);
}

namespace internal {

std::optional<std::string> expand_iri(const ActiveContext& active, std::string_view value,
                                      bool document_relative, bool vocab, bool* is_term) {
  std::string out;
  if (!expand_iri_into(out, active, value, document_relative, vocab, is_term)) return std::nullopt;
  return out;
}

bool expand_iri_into(std::string& out, const ActiveContext& active, std::string_view value,
                     bool document_relative, bool vocab, bool* is_term) {
  // IE 1
  if (!value.empty() && value[0] == '@') {
    if (is_keyword(value)) {
      out.assign(value);
      return true;
    }
    // IE 2
    if (has_keyword_form(value)) return false;
  }
  const TermDefinition* def = active.find(value);
  if (is_term != nullptr) *is_term = def != nullptr;
  if (def != nullptr) {
    // IE 4, 5
    if ((def->iri && is_keyword(*def->iri)) || vocab) {
      if (!def->iri) return false;
      out.assign(*def->iri);
      return true;
    }
  }
  // IE 6
  const size_t colon = value.find(':', 1);
  if (colon != std::string_view::npos) {
    const std::string_view prefix = value.substr(0, colon);
    const std::string_view suffix = value.substr(colon + 1);
    if (prefix == "_" || suffix.starts_with("//")) {
      out.assign(value);
      return true;
    }
    const TermDefinition* pdef = active.find(prefix);
    if (pdef != nullptr && pdef->iri && pdef->prefix) {
      out.assign(*pdef->iri).append(suffix);
      return true;
    }
    if (rdf::is_absolute_iri(value)) {
      out.assign(value);
      return true;
    }
  }
  // IE 7
  if (vocab && active.vocab()) {
    out.assign(*active.vocab()).append(value);
    return true;
  }
  // IE 8
  if (document_relative) {
    active.impl().base.iri_base().resolve_into(out, value);
    return true;
  }
  out.assign(value);
  return true;
}

}  // namespace internal

}  // namespace mospec::jsonld
