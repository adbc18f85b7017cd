// Create Term Definition (JSON-LD 1.1 Processing Algorithms 4.2).
#include "jsonld/context_processing.hpp"

namespace mospec::jsonld::internal {

void Processor::create_term(Builder& active, LocalCtx& lc, size_t idx, const TermArgs& args) {
  const std::string_view term = lc.obj->key(idx);
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
  ++terms_defined_;
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
    fail("keyword redefinition", "keyword " + std::string(term) + " cannot be redefined", where);
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
  TermValue v;
  bool simple_term = false;
  if (value.is_null() || value.is_string()) {
    v.id = &value;
    simple_term = value.is_string();
  } else if (value.is_object()) {
    v.scan(value.as_object());
  } else {
    fail("invalid term definition", name() + " must be defined by a string, null or an object",
         value.location());
  }
  // CTD 10
  auto def = std::make_shared<TermDefinition>();
  def->protected_ = args.protected_default;
  def->where = where;
  // CTD 11
  if (const json::Value* p = v.protected_) {
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
  if (const json::Value* t = v.type) {
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
  if (const json::Value* r = v.reverse) {
    if (v.id != nullptr || v.nest != nullptr) {
      fail("invalid reverse property", name() + ": @reverse cannot be combined with @id or @nest",
           r->location());
    }
    if (!r->is_string()) {
      fail("invalid IRI mapping", name() + ": @reverse must be a string", r->location());
    }
    if (has_keyword_form(r->as_string())) {
      warn(name() + ": @reverse value " + std::string(r->as_string()) +
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
    if (const json::Value* c = v.container) {
      if (!(c->is_null() ||
            (c->is_string() && (c->as_string() == "@set" || c->as_string() == "@index")))) {
        fail("invalid reverse property",
             name() + ": a reverse property's @container must be @set, @index or null",
             c->location());
      }
      if (c->is_string()) def->container.emplace(c->as_string());
    }
    def->reverse = true;
  } else if (const json::Value* id = v.id;
             id != nullptr && !(id->is_string() && id->as_string() == term)) {
    // CTD 14
    if (id->is_null()) {
      // CTD 14.1: kept (with no IRI mapping) to detect later redefinitions.
    } else {
      if (!id->is_string()) {
        fail("invalid IRI mapping", name() + ": @id must be a string or null", id->location());
      }
      const std::string_view idv = id->as_string();
      // CTD 14.2.2
      if (!is_keyword(idv) && has_keyword_form(idv)) {
        warn(name() + ": @id " + std::string(idv) +
                 " has the form of a keyword; the definition is ignored",
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
    def->iri = *active.vocab + std::string(term);
  } else {
    fail("invalid IRI mapping",
         name() + " has no @id and there is no @vocab to derive its IRI from", where);
  }
  // CTD 19
  if (const json::Value* c = v.container; c != nullptr && !def->reverse) {
    validate_container(term, *c, *def);
  }
  // CTD 20
  if (const json::Value* ix = v.index) {
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
  if (const json::Value* sc = v.context) {
    if (json10_) {
      fail("invalid term definition", name() + ": scoped contexts require json-ld-1.1",
           sc->location());
    }
    // CTD 21.3: processed now to report errors where the definition is
    // written; the result is discarded.
    ++scoped_validations_;
    try {
      Builder scratch;
      scratch.parent = &active;
      scratch.base = active.base;
      scratch.original_base = active.original_base;
      scratch.vocab = active.vocab;
      scratch.language = active.language;
      scratch.direction = active.direction;
      // (A copy of the remote contexts, as RemoteContextsMark gives.)
      RemoteContextsMark copy(*args.remote_contexts);
      process(scratch, nullptr, *sc, args.base_url, *args.remote_contexts, true, true, false,
              false);
      if (scratch.used_base) active.used_base = true;
    } catch (const Error& e) {
      fail("invalid scoped context",
           name() + ": invalid scoped context: " + e.diagnostic().message +
               (e.code() == "invalid scoped context" ? "" : " (" + e.code() + ")"),
           sc->location());
    }
    // CTD 21.4
    def->local_context = owner_ ? std::shared_ptr<const json::Value>(owner_, sc)
                                : std::make_shared<const json::Value>(*sc);
    def->base_url = args.base_url;
  }
  // CTD 22
  if (const json::Value* l = v.language; l != nullptr && v.type == nullptr) {
    if (!l->is_null() && !l->is_string()) {
      fail("invalid language mapping", name() + ": @language must be a string or null",
           l->location());
    }
    def->language = *l;
  }
  // CTD 23
  if (const json::Value* d = v.direction; d != nullptr && v.type == nullptr) {
    if (!(d->is_null() ||
          (d->is_string() && (d->as_string() == "ltr" || d->as_string() == "rtl")))) {
      fail("invalid base direction", name() + ": @direction must be \"ltr\", \"rtl\" or null",
           d->location());
    }
    def->direction = *d;
  }
  // CTD 24
  if (const json::Value* n = v.nest) {
    if (json10_) {
      fail("invalid term definition", name() + ": @nest requires json-ld-1.1", n->location());
    }
    if (!n->is_string() || (is_keyword(n->as_string()) && n->as_string() != "@nest")) {
      fail("invalid @nest value", name() + ": @nest must be a term or @nest", n->location());
    }
    def->nest = n->as_string();
  }
  // CTD 25
  if (const json::Value* p = v.prefix) {
    if (json10_ || term.find(':') != std::string::npos || term.find('/') != std::string::npos) {
      fail("invalid term definition",
           name() + ": @prefix requires json-ld-1.1 and a term without ':' or '/'", p->location());
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
  if (v.unexpected != std::string::npos) {
    fail("invalid term definition",
         name() + ": unexpected entry " + quoted(v.obj->key(v.unexpected)),
         v.obj->key_location(v.unexpected));
  }
  // CTD 27
  TermPtr final_def = def;
  if (!args.override_protected && previous && previous->protected_) {
    if (!(*def == *previous)) {
      std::string first;
      if (previous->where.known()) {
        first = " (protected definition at ";
        if (opts_.loader != nullptr && previous->where.file != 0) {
          first += format_place(opts_.loader->files().path(previous->where.file),
                                previous->where.line, previous->where.column);
        } else {
          first += "line " + std::to_string(previous->where.line) + ", column " +
                   std::to_string(previous->where.column);
        }
        first += ")";
      }
      fail("protected term redefinition", name() + " is protected and cannot be redefined" + first,
           where);
    }
    final_def = previous;
  }
  if (cache_ != nullptr && final_def->local_context && final_def == def) {
    std::lock_guard lock(cache_->mutex);
    cache_->register_owner(final_def);
  }
  // CTD 28
  active.set(term, std::move(final_def));
  lc.state[idx] = LocalCtx::Defined;
}

void Processor::TermValue::scan(const json::Object& o) {
  obj = &o;
  for (size_t i = 0; i < o.size(); ++i) {
    const std::string_view k = o.key(i);
    const json::Value** slot = nullptr;
    // By length, so that a key is compared with at most three keywords.
    switch (k.size()) {
      case 3:
        if (k == "@id") slot = &id;
        break;
      case 5:
        if (k == "@type") {
          slot = &type;
        } else if (k == "@nest") {
          slot = &nest;
        }
        break;
      case 6:
        if (k == "@index") slot = &index;
        break;
      case 7:
        if (k == "@prefix") slot = &prefix;
        break;
      case 8:
        if (k == "@context") {
          slot = &context;
        } else if (k == "@reverse") {
          slot = &reverse;
        }
        break;
      case 9:
        if (k == "@language") slot = &language;
        break;
      case 10:
        if (k == "@container") {
          slot = &container;
        } else if (k == "@direction") {
          slot = &direction;
        } else if (k == "@protected") {
          slot = &protected_;
        }
        break;
      default:
        break;
    }
    if (slot != nullptr) {
      *slot = &o.value(i);
    } else if (unexpected == std::string::npos) {
      unexpected = i;
    }
  }
}

void Processor::validate_container(std::string_view term, const json::Value& c,
                                   TermDefinition& def) {
  auto bad = [&](const std::string& why) {
    fail("invalid container mapping", "term " + quoted(term) + ": " + why, c.location());
  };
  // CTD 19.2
  if (json10_) {
    if (!c.is_string()) bad("@container must be a string in json-ld-1.0");
    const std::string_view s = c.as_string();
    if (s == "@graph" || s == "@id" || s == "@type")
      bad("@container " + std::string(s) + " requires json-ld-1.1");
  }
  std::set<std::string> values;
  auto add = [&](const json::Value& e) {
    static constexpr std::array<std::string_view, 7> kContainers = {
        "@graph", "@id", "@index", "@language", "@list", "@set", "@type"};
    if (!e.is_string() ||
        std::find(kContainers.begin(), kContainers.end(), e.as_string()) == kContainers.end()) {
      bad("@container values must be @graph, @id, @index, @language, @list, @set or @type");
    }
    values.emplace(e.as_string());
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

}  // namespace mospec::jsonld::internal
