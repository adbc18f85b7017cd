// JSON-LD 1.1 Expansion Algorithm (API spec 5.1.2), Value Expansion (5.3.2) and
// the expand() API method (9.x, JsonLdProcessor.expand). Step numbers in the
// comments refer to those sections.
#include "jsonld/expand.hpp"

#include <algorithm>
#include <cstddef>
#include <memory_resource>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "jsonld/context.hpp"
#include "jsonld/context_processing.hpp"
#include "jsonld/loader.hpp"
#include "rdf/iri.hpp"
#include "support/arena.hpp"
#include "support/spelling.hpp"

namespace mospec::jsonld {
namespace {

using namespace std::string_view_literals;

using json::Array;
using json::Object;
using json::Value;

// The active property: nullopt is the spec's null.
using ActiveProperty = std::optional<std::string_view>;

constexpr std::string_view kGraph = "@graph";
constexpr std::string_view kReverse = "@reverse";
constexpr std::string_view kIncluded = "@included";

std::string_view kind_name(const Value& v) {
  return json::kind_name(v.kind());
}

bool has_key(const Value& v, std::string_view key) {
  return v.get(key) != nullptr;
}
bool is_value_object(const Value& v) {
  return has_key(v, "@value");
}
bool is_list_object(const Value& v) {
  return has_key(v, "@list");
}

// A graph object has @graph and otherwise at most @id and @index (@context is
// gone after expansion).
bool is_graph_object(const Value& v) {
  if (!v.is_object() || !has_key(v, "@graph")) return false;
  const Object& o = v.as_object();
  for (size_t i = 0; i < o.size(); ++i) {
    const std::string_view k = o.key(i);
    if (k != "@graph"sv && k != "@id"sv && k != "@index"sv) return false;
  }
  return true;
}

// `s` as a message quotes it between double quotes: quote, backslash and
// control characters escaped JSON-style, so a message never carries raw bytes.
std::string escaped_for_message(std::string_view s) {
  std::string out;
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\u00";
      out += kHex[u >> 4];
      out += kHex[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

// An absolute IRI by syntax: a scheme and none of the characters RFC 3987
// excludes from IRIs (space, controls, <>"{}|\^`).
bool is_iri(std::string_view s) {
  if (!rdf::is_absolute_iri(s)) return false;
  return std::none_of(s.begin(), s.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u <= 0x20 || u == 0x7f ||
           std::string_view("<>\"{}|\\^`").find(c) != std::string_view::npos;
  });
}

bool is_node_object(const Value& v) {
  return v.is_object() && !has_key(v, "@value") && !has_key(v, "@list") && !has_key(v, "@set");
}

// Moves `v` into an array (null becomes the empty array), keeping the
// location; a new array lives in `mem`.
Value to_array(Value v, json::Resource* mem) {
  if (v.is_array()) return v;
  SourceLoc loc = v.location();
  Value out;
  Array& a = out.emplace_array(mem);
  if (!v.is_null()) {
    a.reserve(1);
    a.push_back(std::move(v));
  }
  out.set_location(loc);
  return out;
}

// Inserts `v` under `key` (new or replaced) and records where the key was written.
Value& put(Object& obj, std::string_view key, Value v, SourceLoc key_loc) {
  const size_t before = obj.size();
  Value& slot = obj.set(key, std::move(v));
  if (obj.size() > before) obj.set_key_location(obj.size() - 1, key_loc);
  return slot;
}

// The spec's "add value" with `as array` true: values of an array are appended
// one by one. New arrays live where `obj` does.
void add_value(Object& obj, std::string_view key, Value v, SourceLoc key_loc) {
  Value* slot = obj.find(key);
  if (slot == nullptr) {
    // A new key: an array value becomes its array as it is; anything else a
    // one-element array, built in the new member.
    Value& values = obj.append_new(key, Value());
    obj.set_key_location(obj.size() - 1, key_loc);
    if (v.is_array()) {
      values = std::move(v);
    } else {
      const SourceLoc loc = v.location();
      Array& a = values.emplace_array(obj.resource());
      a.reserve(1);
      a.push_back(std::move(v));
      values.set_location(loc);
    }
    return;
  }
  if (!slot->is_array()) {
    *slot = to_array(std::move(*slot), obj.resource());
  }
  Array& arr = slot->as_array();
  if (v.is_array()) {
    for (Value& item : v.as_array()) arr.push_back(std::move(item));
  } else {
    arr.push_back(std::move(v));
  }
}

// Concatenates `existing` (made an array) followed by `added` (made an array).
Value concat(Value existing, Value added, json::Resource* mem) {
  Value out = to_array(std::move(existing), mem);
  Value tail = to_array(std::move(added), mem);
  for (Value& item : tail.as_array()) out.as_array().push_back(std::move(item));
  return out;
}

Value string_at(std::string_view s, SourceLoc loc, json::Resource* mem) {
  Value v(s, mem);
  v.set_location(loc);
  return v;
}

// A deep copy of `v` (an input value kept in the output) in `mem`.
Value copy_to(const Value& v, json::Resource* mem) {
  Value out;
  switch (v.kind()) {
    case json::Kind::Null:
    case json::Kind::Boolean:
    case json::Kind::Number:
      out = v;
      break;
    case json::Kind::String:
      out.emplace_string(mem) = v.as_string();
      break;
    case json::Kind::Array: {
      Array& a = out.emplace_array(mem);
      a.reserve(v.as_array().size());
      for (const Value& item : v.as_array()) a.push_back(copy_to(item, mem));
      break;
    }
    case json::Kind::Object: {
      const Object& o = v.as_object();
      Object& c = out.emplace_object(mem);
      c.reserve(o.size());
      for (size_t i = 0; i < o.size(); ++i) {
        c.append_new(o.key(i), copy_to(o.value(i), mem));
        c.set_key_location(i, o.key_location(i));
      }
      break;
    }
  }
  out.set_location(v.location());
  return out;
}

// Whether some term of `ctx` is a keyword alias. Contexts rarely have one, and
// without one no term lookup can turn a key into a keyword.
bool has_keyword_aliases(const ActiveContext& ctx) {
  const LayerPtr& terms = ctx.impl().terms;
  return terms && terms->keyword_aliases != 0;
}

// Whether `key` IRI-expands to `keyword` in `ctx`, without building the
// expansion: only a keyword itself or a keyword alias can (IRI Expansion steps
// 1, 2 and 4), which keeps this check off the allocator in the per-node scans.
bool expands_to(const ActiveContext& ctx, std::string_view key, std::string_view keyword) {
  if (key == keyword) return true;
  if (is_keyword(key) || has_keyword_form(key) || !has_keyword_aliases(ctx)) return false;
  const TermDefinition* def = ctx.find(key);
  return def != nullptr && def->iri && *def->iri == keyword;
}

// The keyword `key` IRI-expands to in `ctx` (itself, or the keyword it is an
// alias of), or empty: expands_to for every keyword at once.
std::string_view keyword_of(const ActiveContext& ctx, std::string_view key) {
  if (is_keyword(key)) return key;
  if (has_keyword_form(key) || !has_keyword_aliases(ctx)) return {};
  const TermDefinition* def = ctx.find(key);
  if (def != nullptr && def->iri && is_keyword(*def->iri)) return *def->iri;
  return {};
}

// Whether a term definition's container mapping holds `c`. The mapping has at
// most three entries, so a scan beats std::set::count, which would build a
// std::string key for every lookup.
bool has_container(const std::set<std::string>& container, std::string_view c) {
  for (const std::string& entry : container) {
    if (entry == c) return true;
  }
  return false;
}

// Visiting order of an object's members: insertion order, or code-point order
// when `sorted`.
std::vector<size_t> member_order(const Object& o, bool sorted) {
  std::vector<size_t> idx(o.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  if (sorted) {
    std::sort(idx.begin(), idx.end(), [&o](size_t a, size_t b) { return o.key(a) < o.key(b); });
  }
  return idx;
}

class Expander {
 public:
  // The output's strings, arrays and objects live in `mem`.
  Expander(const Options& options, json::Resource* mem) : opts_(options), mem_(mem) {}

  // The Expansion Algorithm (5.1.2).
  // `active` is taken by reference: most elements are scalars and arrays,
  // which need no copy of it (a copy is two atomic reference-count updates).
  Value expand(const ContextPtr& active, ActiveProperty ap, const Value& element,
               const std::string& base_url, bool from_map) {
    const TermDefinition* ap_def = ap ? active->find(*ap) : nullptr;
    return expand(active, ap, ap_def, element, base_url, from_map);
  }

 private:
  // The same, given `ap_def`: the term definition of `ap` in `active` (step 3),
  // which the caller has looked up already.
  Value expand(const ContextPtr& active, ActiveProperty ap, const TermDefinition* ap_def,
               const Value& element, const std::string& base_url, bool from_map);

  // A finding reported after the node's @id is known.
  struct Pending {
    SourceLoc loc;
    DiagnosticCode code;
    std::string message;  // "(node ...)" is appended when reported
  };

  // Shared state of steps 13 and 14 for one element (nested values included).
  struct ObjectState {
    // The result is built where the output lives (assigning an object built
    // elsewhere would copy it there).
    explicit ObjectState(json::Resource* mem) : result(mem) {}
    ContextPtr type_scoped;
    bool input_type_json = false;  // step 12's input type is @json
    Object result;
    std::vector<Pending> pending;
  };

  // `ap_def`: the term definition of `ap` in `active` (looked up once by expand()).
  Value expand_object(const ContextPtr& entry, ActiveProperty ap, const TermDefinition* ap_def,
                      const Value& element, const std::string& base_url, bool from_map);
  void expand_entries(const ContextPtr& active, ActiveProperty ap, const Object& element,
                      const std::string& base_url, ObjectState& st);
  void expand_keyword(const ContextPtr& active, ActiveProperty ap, std::string_view key,
                      SourceLoc key_loc, std::string_view expanded_property, const Value& value,
                      const std::string& base_url, ObjectState& st,
                      std::vector<std::pair<std::string, SourceLoc>>& nests);
  Value expand_language_map(const ActiveContext& active, const TermDefinition* def,
                            const Value& value);
  Value expand_index_map(const ContextPtr& active, std::string_view key, const TermDefinition& def,
                         const Value& value, const std::string& base_url, ObjectState& st);
  Value expand_value(const ActiveContext& active, ActiveProperty ap, const Value& value) {
    return expand_value(active, ap ? active.find(*ap) : nullptr, value);
  }
  // `def`: the active property's term definition in `active`, or null.
  Value expand_value(const ActiveContext& active, const TermDefinition* def, const Value& value);
  Value finish_object(ActiveProperty ap, ObjectState& st, SourceLoc element_loc);

  // The IRI in iri_, valid until the next IRI expansion; null when it
  // expands to nothing.
  const std::string* expand_type_iri(const ActiveContext& type_scoped, const Value& v,
                                     ObjectState& st);
  void note_dropped_key(const ActiveContext& active, std::string_view key, SourceLoc loc,
                        ObjectState& st);
  static std::string did_you_mean(const ActiveContext& active, std::string_view word);
  // The warning for an @id (or @id-coerced value) that expands to a malformed
  // IRI, which toRdf drops with its triples; nullopt when `iri` is fine.
  std::optional<Pending> malformed_id(const std::string& iri, const Value& value) const;

  // Options::property_prefix_seen: records a property IRI of the result.
  void note_property(std::string_view iri) const {
    if (opts_.property_prefix_seen != nullptr && iri.starts_with(opts_.property_prefix))
      *opts_.property_prefix_seen = true;
  }

  // process_context() for the scoped context of `def`, a term definition of
  // `active`. With a context cache, the answer is remembered for this
  // expansion: the cache would return the same context for the same inputs
  // (`def` lives as long as `active`, which the memo keeps), and its own
  // lookup costs a hash of the base URL and several comparisons, at most
  // nodes of a document.
  ContextPtr scoped_context(const ContextPtr& active, const TermDefinition& def,
                            bool override_protected, bool propagate);

  struct ScopedKey {
    const ActiveContext* active;
    const TermDefinition* def;
    unsigned flags;
    bool operator==(const ScopedKey&) const = default;
  };
  struct ScopedKeyHash {
    size_t operator()(const ScopedKey& k) const noexcept {
      const auto a = reinterpret_cast<uintptr_t>(k.active);
      const auto d = reinterpret_cast<uintptr_t>(k.def);
      return std::hash<uintptr_t>{}(a * 31 + d * 7 + k.flags);
    }
  };
  struct ScopedEntry {
    ContextPtr active;  // keeps the key's context, and so its definition, alive
    ContextPtr result;
  };
  std::unordered_map<ScopedKey, ScopedEntry, ScopedKeyHash> scoped_;

  std::string file_name(SourceLoc loc) const;
  [[noreturn]] void fail(DiagnosticCode code, std::string message, SourceLoc loc) const;
  void flush(ObjectState& st, const Object& result, ActiveProperty ap) const;

  // Output helpers: values built in mem_.
  Value array_of(Value v) const { return to_array(std::move(v), mem_); }
  Value string_at(std::string_view s, SourceLoc loc) const {
    return jsonld::string_at(s, loc, mem_);
  }
  Value concat(Value existing, Value added) const {
    return jsonld::concat(std::move(existing), std::move(added), mem_);
  }
  Value copy(const Value& v) const { return copy_to(v, mem_); }

  const Options& opts_;
  json::Resource* mem_;
  // The IRI most recently expanded for the output, before it is copied there.
  std::string iri_;
};

ContextPtr Expander::scoped_context(const ContextPtr& active, const TermDefinition& def,
                                    bool override_protected, bool propagate) {
  // Without a cache every call processes the context again (and reports
  // what it reports again), so there is nothing to remember.
  if (!opts_.context_cache) {
    return process_context(active, *def.local_context, def.base_url, opts_, nullptr,
                           override_protected, propagate, true);
  }
  const ScopedKey key{active.get(), &def, (override_protected ? 1u : 0u) | (propagate ? 2u : 0u)};
  auto it = scoped_.find(key);
  if (it != scoped_.end()) return it->second.result;
  ContextPtr result = process_context(active, *def.local_context, def.base_url, opts_, nullptr,
                                      override_protected, propagate, true);
  scoped_.emplace(key, ScopedEntry{active, result});
  return result;
}

std::string Expander::file_name(SourceLoc loc) const {
  if (!loc.known()) return {};
  if (opts_.loader != nullptr) {
    const std::string& p = opts_.loader->files().path(loc.file);
    if (!p.empty()) return p;
  }
  return "<input>";
}

void Expander::fail(DiagnosticCode code, std::string message, SourceLoc loc) const {
  throw Error(code, std::move(message), file_name(loc), loc.line, loc.column);
}

void Expander::note_dropped_key(const ActiveContext& active, std::string_view key, SourceLoc loc,
                                ObjectState& st) {
  if (opts_.diagnostics == nullptr) return;
  st.pending.push_back({loc, "dropped-key",
                        "key \"" + std::string(key) + "\" expands to no IRI and is dropped" +
                            did_you_mean(active, key)});
}

// "; did you mean \"term\"?" naming the active context's term nearest to a
// word that is none of them (a typo of a property or type), or "".
std::string Expander::did_you_mean(const ActiveContext& active, std::string_view word) {
  Nearest nearest(word);
  active.for_each_term([&](std::string_view term) { nearest.offer(term); });
  if (nearest.best().empty()) return "";
  return "; did you mean \"" + std::string(nearest.best()) + "\"?";
}

std::optional<Expander::Pending> Expander::malformed_id(const std::string& iri,
                                                        const Value& value) const {
  if (opts_.diagnostics == nullptr || iri.starts_with("_:") || is_keyword(iri)) return std::nullopt;
  std::string problem = rdf::iri_problem(iri);
  if (problem.empty()) return std::nullopt;
  std::string shown = escaped_for_message(value.as_string());
  return Pending{value.location(), "malformed-id",
                 "@id value \"" + shown + "\" is not a well-formed IRI (" + problem +
                     "); JSON-LD drops it and the triples that use it"};
}

// IRI-expands an @type value against the type-scoped context (13.4.4.4). A value
// that is no term, no compact/absolute IRI and not caught by @vocab silently
// becomes a document-relative IRI; that is reported as "undefined-type".
const std::string* Expander::expand_type_iri(const ActiveContext& type_scoped, const Value& v,
                                             ObjectState& st) {
  const std::string_view s = v.as_string();
  bool is_term = false;
  if (!internal::expand_iri_into(iri_, type_scoped, s, true, true, &is_term)) return nullptr;
  const std::string* iri = &iri_;
  if (opts_.diagnostics != nullptr && s.find(':') == std::string::npos && !is_keyword(s) &&
      !is_term && !type_scoped.vocab()) {
    st.pending.push_back({v.location(), "undefined-type",
                          "@type value \"" + std::string(s) +
                              "\" is not a defined term and resolves against the base to <" + *iri +
                              ">" + did_you_mean(type_scoped, s)});
  }
  return iri;
}

void Expander::flush(ObjectState& st, const Object& result, ActiveProperty ap) const {
  if (st.pending.empty()) return;
  std::string node;
  const Value* id = result.find("@id");
  if (id != nullptr && id->is_string()) {
    const std::string_view s = id->as_string();
    node = s.rfind("_:", 0) == 0 ? " (node " + std::string(s) + ")"
                                 : " (node <" + std::string(s) + ">)";
  } else if (ap && *ap == kReverse) {
    // The keys of an @reverse map belong to the enclosing node, reported at them.
    node = " (in @reverse)";
  } else if (result.contains("@value")) {
    node = " (value object)";
  } else {
    node = " (node without @id)";
  }
  for (Pending& p : st.pending) {
    opts_.diagnostics->report(Diagnostic{Severity::Warning, file_name(p.loc), p.loc.line,
                                         p.loc.column, std::move(p.code), p.message + node});
  }
  st.pending.clear();
}

Value Expander::expand(const ContextPtr& active, ActiveProperty ap, const TermDefinition* ap_def,
                       const Value& element, const std::string& base_url, bool from_map) {
  // 1
  if (element.is_null()) return Value();
  // 3 (2 concerns frame expansion only): ap_def
  // 4
  if (element.is_scalar()) {
    if (!ap || *ap == kGraph) return Value();  // 4.1 free-floating scalar
    if (ap_def != nullptr && ap_def->local_context) {
      const ContextPtr scoped = scoped_context(active, *ap_def, false, true);  // 4.2
      return expand_value(*scoped, ap, element);                               // 4.3
    }
    return expand_value(*active, ap_def, element);  // 4.3
  }
  // 5
  if (element.is_array()) {
    const bool list_container = ap_def != nullptr && has_container(ap_def->container, "@list");
    Value out;
    out.emplace_array(mem_);
    out.set_location(element.location());
    Array& result = out.as_array();
    result.reserve(element.as_array().size());
    for (const Value& item : element.as_array()) {
      Value expanded = expand(active, ap, ap_def, item, base_url, from_map);  // 5.2.1
      if (list_container && expanded.is_array()) {                            // 5.2.2
        SourceLoc loc = expanded.location();
        Object list(mem_);
        list.append_new("@list", std::move(expanded));
        expanded = Value(std::move(list));
        expanded.set_location(loc);
      }
      if (expanded.is_array()) {  // 5.2.3
        for (Value& v : expanded.as_array()) result.push_back(std::move(v));
      } else if (!expanded.is_null()) {
        result.push_back(std::move(expanded));
      }
    }
    return out;
  }
  // 6
  return expand_object(active, ap, ap_def, element, base_url, from_map);
}

Value Expander::expand_object(const ContextPtr& entry, ActiveProperty ap,
                              const TermDefinition* ap_def, const Value& element,
                              const std::string& base_url, bool from_map) {
  const Object& obj = element.as_object();
  // 3: the property-scoped context comes from the context we were called with.
  // The caller's `entry` keeps that context, and so `ap_def`, alive after
  // `active` moves on.
  ContextPtr active = entry;
  if (ap_def != nullptr && !ap_def->local_context) ap_def = nullptr;

  // 7: a type-scoped context does not propagate into new node objects.
  if (active->previous() && !from_map) {
    bool has_value = false;
    bool only_id = obj.size() == 1;
    for (size_t i = 0; i < obj.size(); ++i) {
      const std::string_view keyword = keyword_of(*active, obj.key(i));
      if (keyword == "@value"sv) has_value = true;
      if (keyword != "@id"sv) only_id = false;
    }
    if (!has_value && !only_id) active = active->previous();
  }
  // 8
  if (ap_def != nullptr) {
    active = scoped_context(active, *ap_def, true, true);
  }
  // 9
  if (const Value* ctx = obj.find("@context")) {
    active = process_context(active, *ctx, base_url, opts_);
  }

  ObjectState st(mem_);
  // 10
  st.type_scoped = active;
  // 11, 12: keys are visited in code-point order; every @type entry applies the
  // type-scoped contexts of its values, in code-point order of the values.
  const ContextPtr& tsc = st.type_scoped;  // st.type_scoped is not reassigned
  std::vector<size_t> type_entries;        // stays unallocated for the usual single "@type"
  size_t single_type = obj.size();
  for (size_t i = 0; i < obj.size(); ++i) {
    if (!expands_to(*tsc, obj.key(i), "@type")) continue;
    if (single_type == obj.size()) {
      single_type = i;
    } else {
      if (type_entries.empty()) type_entries.push_back(single_type);
      type_entries.push_back(i);
    }
  }
  std::sort(type_entries.begin(), type_entries.end(),
            [&obj](size_t a, size_t b) { return obj.key(a) < obj.key(b); });
  if (type_entries.empty() && single_type != obj.size()) type_entries.push_back(single_type);
  auto apply_type_scoped = [&](std::string_view term) {
    const TermDefinition* def = tsc->find(term);
    if (def != nullptr && def->local_context) {
      active = scoped_context(active, *def, false, false);
    }
  };
  for (size_t i : type_entries) {
    const Value& v = obj.value(i);
    if (v.is_string()) {
      apply_type_scoped(v.as_string());
    } else if (v.is_array()) {
      // A node's types are a handful: sorted on the stack, not the heap.
      alignas(std::string_view) std::byte buffer[8 * sizeof(std::string_view)];
      Arena scratch(buffer, sizeof buffer);
      std::pmr::vector<std::string_view> terms(&scratch);
      terms.reserve(v.as_array().size());
      for (const Value& t : v.as_array()) {
        if (t.is_string()) terms.push_back(t.as_string());
      }
      std::sort(terms.begin(), terms.end());
      for (std::string_view term : terms) apply_type_scoped(term);
    }
  }
  // 12: the last value of the first @type entry. Only whether it is @json
  // matters (13.4.7.1, 15), and only @json or an alias of it expands to @json.
  if (!type_entries.empty()) {
    const Value& v = obj.value(type_entries.front());
    const Value* last = v.is_array() ? (v.as_array().empty() ? nullptr : &v.as_array().back()) : &v;
    st.input_type_json =
        last != nullptr && last->is_string() && expands_to(*active, last->as_string(), "@json");
  }

  // 13, 14
  st.result.reserve(obj.size());
  expand_entries(active, ap, obj, base_url, st);
  return finish_object(ap, st, element.location());
}

void Expander::expand_entries(const ContextPtr& active, ActiveProperty ap, const Object& element,
                              const std::string& base_url, ObjectState& st) {
  std::vector<std::pair<std::string, SourceLoc>> nests;
  Object& result = st.result;
  // 13
  // Insertion order needs no index vector; `ordered` sorts one.
  const std::vector<size_t> order =
      opts_.ordered ? member_order(element, true) : std::vector<size_t>();
  for (size_t n = 0; n < element.size(); ++n) {
    const size_t i = opts_.ordered ? order[n] : n;
    const std::string_view key = element.key(i);
    const Value& value = element.value(i);
    const SourceLoc key_loc = element.key_location(i);
    if (key == "@context"sv) continue;  // 13.1
    // 13.2, sharing the term lookup with 13.5: for a defined term, IRI
    // Expansion (vocab true) returns its IRI mapping (steps 4 and 5).
    const TermDefinition* def = nullptr;
    // A defined term's IRI is viewed in its definition (which `active`
    // keeps alive), not copied.
    std::optional<std::string> expanded_storage;
    const std::string* expanded = nullptr;
    if (!key.empty() && key[0] != '@' && (def = active->find(key)) != nullptr) {
      if (def->iri) expanded = &*def->iri;
    } else {
      expanded_storage = expand_iri(*active, key);
      if (expanded_storage) expanded = &*expanded_storage;
    }
    // 13.3
    if (expanded == nullptr ||
        (expanded->find(':') == std::string::npos && !is_keyword(*expanded))) {
      note_dropped_key(*active, key, key_loc, st);
      continue;
    }
    const std::string_view expanded_property = *expanded;
    // 13.4
    if (is_keyword(expanded_property)) {
      expand_keyword(active, ap, key, key_loc, expanded_property, value, base_url, st, nests);
      continue;
    }
    // 13.5
    static const std::set<std::string> kNoContainer;
    const std::set<std::string>& container = def != nullptr ? def->container : kNoContainer;
    auto has = [&container](std::string_view c) { return has_container(container, c); };
    Value expanded_value;
    if (def != nullptr && def->type && *def->type == "@json"sv) {  // 13.6
      Object lit(mem_);
      lit.append_new("@value", copy(value));
      lit.append_new("@type", Value("@json", mem_));
      expanded_value = Value(std::move(lit));
      expanded_value.set_location(value.location());
    } else if (has("@language") && value.is_object()) {  // 13.7
      expanded_value = expand_language_map(*active, def, value);
    } else if ((has("@index") || has("@type") || has("@id")) && value.is_object()) {  // 13.8
      expanded_value = expand_index_map(active, key, *def, value, base_url, st);
    } else {  // 13.9
      // `def` is what step 3 looks up: key's definition in `active`.
      expanded_value = expand(active, std::string_view(key), def, value, base_url, false);
    }
    // 13.10
    if (expanded_value.is_null()) continue;
    // 13.11
    if (has("@list") && !is_list_object(expanded_value)) {
      SourceLoc loc = expanded_value.location();
      Object list(mem_);
      list.append_new("@list", array_of(std::move(expanded_value)));
      expanded_value = Value(std::move(list));
      expanded_value.set_location(loc);
    }
    // 13.12
    if (has("@graph") && !has("@id") && !has("@index")) {
      expanded_value = array_of(std::move(expanded_value));
      for (Value& ev : expanded_value.as_array()) {
        SourceLoc loc = ev.location();
        Object g(mem_);
        g.append_new("@graph", array_of(std::move(ev)));
        ev = Value(std::move(g));
        ev.set_location(loc);
      }
    }
    // 13.13
    if (def != nullptr && def->reverse) {
      Value* rm = result.find("@reverse");
      if (rm == nullptr) rm = &put(result, "@reverse", Value(Object(mem_)), key_loc);
      expanded_value = array_of(std::move(expanded_value));
      for (Value& item : expanded_value.as_array()) {
        if (is_value_object(item) || is_list_object(item)) {
          fail("invalid reverse property value",
               "reverse property \"" + std::string(key) + "\" cannot take a value or list object",
               item.location());
        }
        note_property(expanded_property);
        add_value(rm->as_object(), expanded_property, std::move(item), key_loc);
      }
    } else {  // 13.14
      note_property(expanded_property);
      add_value(result, expanded_property, std::move(expanded_value), key_loc);
    }
  }

  // 14
  if (opts_.ordered) {
    std::sort(nests.begin(), nests.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
  }
  for (const auto& [nesting_key, nest_loc] : nests) {
    const Value* nv = element.find(nesting_key);
    std::vector<const Value*> nested_values;
    if (nv->is_array()) {
      for (const Value& v : nv->as_array()) nested_values.push_back(&v);
    } else {
      nested_values.push_back(nv);
    }
    for (const Value* nested : nested_values) {
      // 14.2.1
      bool bad = !nested->is_object();
      if (!bad) {
        const Object& no = nested->as_object();
        for (size_t i = 0; i < no.size() && !bad; ++i)
          bad = expands_to(*active, no.key(i), "@value");
      }
      if (bad) {
        fail("invalid @nest value",
             "\"" + std::string(nesting_key) + "\" (@nest) must hold node objects, found " +
                 std::string(kind_name(*nested)) + (nested->is_object() ? " with @value" : ""),
             nested->location().known() ? nested->location() : nest_loc);
      }
      // 14.2.2: steps 3 and 8 for the nesting key, then 13 and 14.
      ContextPtr nested_active = active;
      const TermDefinition* nk_def = active->find(nesting_key);
      if (nk_def != nullptr && nk_def->local_context) {
        nested_active = scoped_context(active, *nk_def, true, true);
      }
      expand_entries(nested_active, std::string_view(nesting_key), nested->as_object(), base_url,
                     st);
    }
  }
}

void Expander::expand_keyword(const ContextPtr& active, ActiveProperty ap, std::string_view key,
                              SourceLoc key_loc, std::string_view expanded_property,
                              const Value& value, const std::string& base_url, ObjectState& st,
                              std::vector<std::pair<std::string, SourceLoc>>& nests) {
  Object& result = st.result;
  const bool v10 = opts_.processing_mode == ProcessingMode::JsonLd10;
  const std::string_view ep = expanded_property;
  // 13.4.1
  if (ap && *ap == kReverse) {
    fail("invalid reverse property map",
         "keyword \"" + std::string(key) + "\" (" + std::string(ep) +
             ") is not allowed inside @reverse",
         key_loc);
  }
  // 13.4.2
  if (result.contains(ep) && ep != "@included"sv && (ep != "@type"sv || v10)) {
    fail(
        "colliding keywords",
        "key \"" + std::string(key) + "\" expands to " + std::string(ep) + ", which is already set",
        key_loc);
  }
  Value expanded_value;
  if (ep == "@id"sv) {  // 13.4.3
    if (!value.is_string()) {
      fail("invalid @id value",
           "\"" + std::string(key) + "\" must be a string, found " + std::string(kind_name(value)),
           value.location());
    }
    if (!internal::expand_iri_into(iri_, *active, value.as_string(), true, false, nullptr)) {
      // A keyword-like @id ("@ignoreMe") expands to null. The suite (expand
      // 0122, toRdf e122) keeps "@id": null so that the node is not mistaken for
      // a blank node and its triples are dropped.
      if (opts_.diagnostics != nullptr) {
        st.pending.push_back({value.location(), "dropped-id",
                              "@id value \"" + std::string(value.as_string()) +
                                  "\" expands to no IRI; the node's triples are dropped"});
      }
      Value null_id;
      null_id.set_location(value.location());
      put(result, "@id", std::move(null_id), key_loc);
      return;
    }
    if (auto warning = malformed_id(iri_, value)) st.pending.push_back(std::move(*warning));
    expanded_value = string_at(iri_, value.location());
  } else if (ep == "@type"sv) {  // 13.4.4
    bool ok = value.is_string();
    if (value.is_array()) {
      ok = std::all_of(value.as_array().begin(), value.as_array().end(),
                       [](const Value& v) { return v.is_string(); });
    }
    if (!ok) {
      fail("invalid type value",
           "\"" + std::string(key) + "\" must be a string or an array of strings, found " +
               std::string(kind_name(value)),
           value.location());
    }
    const ActiveContext& tsc = *st.type_scoped;
    if (value.is_string()) {
      if (const std::string* iri = expand_type_iri(tsc, value, st)) {
        expanded_value = string_at(*iri, value.location());
      }
    } else {
      Array types(mem_);
      types.reserve(value.as_array().size());
      for (const Value& t : value.as_array()) {
        if (const std::string* iri = expand_type_iri(tsc, t, st)) {
          types.push_back(string_at(*iri, t.location()));
        }
      }
      expanded_value = Value(std::move(types));
      expanded_value.set_location(value.location());
    }
    if (Value* existing = result.find("@type")) {  // 13.4.4.5
      expanded_value = concat(std::move(*existing), std::move(expanded_value));
    }
  } else if (ep == "@graph"sv) {  // 13.4.5
    expanded_value = array_of(expand(active, kGraph, value, base_url, false));
  } else if (ep == "@included"sv) {  // 13.4.6
    if (v10) return;
    // The spec passes null as active property, which would silently drop
    // free-floating values before the node-object check below; the suite
    // (in07-in09) expects them to be rejected, so "@included" is used instead.
    expanded_value = array_of(expand(active, kIncluded, value, base_url, false));
    for (const Value& item : expanded_value.as_array()) {
      if (!is_node_object(item)) {
        fail("invalid @included value",
             "\"" + std::string(key) + "\" must hold node objects, found " +
                 (item.is_object() ? std::string("a value, list or set object")
                                   : std::string(kind_name(item))),
             item.location().known() ? item.location() : value.location());
      }
    }
    if (Value* existing = result.find("@included")) {
      expanded_value = concat(std::move(*existing), std::move(expanded_value));
    }
  } else if (ep == "@value"sv) {  // 13.4.7
    if (st.input_type_json) {
      if (v10) {
        fail("invalid value object value", "@json literals need processing mode json-ld-1.1",
             value.location());
      }
      expanded_value = copy(value);
    } else if (!value.is_null() && !value.is_scalar()) {
      fail("invalid value object value",
           "\"" + std::string(key) + "\" must be a string, number, boolean or null, found " +
               std::string(kind_name(value)),
           value.location());
    } else {
      expanded_value = copy(value);
    }
    if (expanded_value.is_null()) {  // 13.4.7.4
      put(result, "@value", std::move(expanded_value), key_loc);
      return;
    }
  } else if (ep == "@language"sv) {  // 13.4.8
    if (!value.is_string()) {
      fail("invalid language-tagged string",
           "\"" + std::string(key) + "\" must be a string, found " + std::string(kind_name(value)),
           value.location());
    }
    expanded_value = copy(value);
  } else if (ep == "@direction"sv) {  // 13.4.9
    if (v10) return;
    if (!value.is_string() || (value.as_string() != "ltr" && value.as_string() != "rtl")) {
      fail("invalid base direction",
           "\"" + std::string(key) + "\" must be \"ltr\" or \"rtl\", found " +
               (value.is_string() ? "\"" + std::string(value.as_string()) + "\""
                                  : std::string(kind_name(value))),
           value.location());
    }
    expanded_value = copy(value);
  } else if (ep == "@index"sv) {  // 13.4.10
    if (!value.is_string()) {
      fail("invalid @index value",
           "\"" + std::string(key) + "\" must be a string, found " + std::string(kind_name(value)),
           value.location());
    }
    expanded_value = copy(value);
  } else if (ep == "@list"sv) {        // 13.4.11
    if (!ap || *ap == kGraph) return;  // free-floating list
    expanded_value = array_of(expand(active, ap, value, base_url, false));
  } else if (ep == "@set"sv) {  // 13.4.12
    expanded_value = expand(active, ap, value, base_url, false);
  } else if (ep == "@reverse"sv) {  // 13.4.13
    if (!value.is_object()) {
      fail("invalid @reverse value",
           "\"" + std::string(key) + "\" must be an object, found " + std::string(kind_name(value)),
           value.location());
    }
    Value ev = expand(active, kReverse, value, base_url, false);  // 13.4.13.2
    if (!ev.is_object()) return;
    Object& eo = ev.as_object();
    // 13.4.13.3: reversed twice is forward.
    if (Value* twice = eo.find("@reverse")) {
      Object& tw = twice->as_object();
      for (size_t i = 0; i < tw.size(); ++i) {
        add_value(result, tw.key(i), std::move(tw.value(i)), tw.key_location(i));
      }
    }
    // 13.4.13.4
    bool has_other = false;
    for (size_t i = 0; i < eo.size(); ++i) has_other = has_other || eo.key(i) != "@reverse"sv;
    if (has_other) {
      Value* rm = result.find("@reverse");
      if (rm == nullptr) rm = &put(result, "@reverse", Value(Object(mem_)), key_loc);
      for (size_t i = 0; i < eo.size(); ++i) {
        if (eo.key(i) == "@reverse"sv) continue;
        Value items = array_of(std::move(eo.value(i)));
        for (Value& item : items.as_array()) {
          if (is_value_object(item) || is_list_object(item)) {
            fail("invalid reverse property value",
                 "reverse property \"" + std::string(eo.key(i)) +
                     "\" cannot take a value or list object",
                 item.location());
          }
          add_value(rm->as_object(), eo.key(i), std::move(item), eo.key_location(i));
        }
      }
    }
    return;                      // 13.4.13.5
  } else if (ep == "@nest"sv) {  // 13.4.14
    if (std::none_of(nests.begin(), nests.end(),
                     [&key](const auto& n) { return n.first == key; })) {
      nests.emplace_back(key, key_loc);
    }
    return;
  } else {
    // Other keywords (@context handled earlier; framing keywords are not
    // supported) are ignored, as frame expansion is off.
    return;
  }
  // 13.4.16
  if (expanded_value.is_null()) return;
  put(result, ep, std::move(expanded_value), key_loc);
}

// 13.7: a language map.
Value Expander::expand_language_map(const ActiveContext& active, const TermDefinition* def,
                                    const Value& value) {
  Value out;
  out.emplace_array(mem_);
  out.set_location(value.location());
  // 13.7.2
  std::optional<std::string> direction = active.default_direction();
  if (def != nullptr && def->direction) {
    direction = def->direction->is_string()
                    ? std::optional<std::string>(def->direction->as_string())
                    : std::nullopt;
  }
  const Object& map = value.as_object();
  for (size_t i : member_order(map, opts_.ordered)) {  // 13.7.4
    const std::string_view language = map.key(i);
    const Value& lv = map.value(i);
    std::vector<const Value*> items;
    if (lv.is_array()) {
      for (const Value& it : lv.as_array()) items.push_back(&it);
    } else {
      items.push_back(&lv);
    }
    bool none = language == "@none"sv;
    if (!none) {
      std::optional<std::string> e = expand_iri(active, language);
      none = e && *e == "@none"sv;
    }
    for (const Value* item : items) {
      if (item->is_null()) continue;  // 13.7.4.2.1
      if (!item->is_string()) {       // 13.7.4.2.2
        fail("invalid language map value",
             "language map entry \"" + std::string(language) + "\" must hold strings, found " +
                 std::string(kind_name(*item)),
             item->location());
      }
      Object v(mem_);  // 13.7.4.2.3
      v.append_new("@value", copy(*item));
      if (!none) v.append_new("@language", string_at(language, map.key_location(i)));
      if (direction) v.append_new("@direction", Value(*direction, mem_));
      Value vv(std::move(v));
      vv.set_location(item->location());
      out.as_array().push_back(std::move(vv));
    }
  }
  return out;
}

// 13.8: an index, id or type map.
Value Expander::expand_index_map(const ContextPtr& active, std::string_view key,
                                 const TermDefinition& def, const Value& value,
                                 const std::string& base_url, ObjectState& st) {
  Value out;
  out.emplace_array(mem_);
  out.set_location(value.location());
  const std::set<std::string>& container = def.container;
  auto has = [&container](std::string_view c) { return has_container(container, c); };
  const bool id_or_type = has("@id") || has("@type");
  const std::string index_key = def.index ? *def.index : std::string("@index");  // 13.8.2
  const Object& map = value.as_object();
  for (size_t i : member_order(map, opts_.ordered)) {  // 13.8.3
    const std::string_view index = map.key(i);
    const SourceLoc index_loc = map.key_location(i);
    const Value& index_value = map.value(i);
    // 13.8.3.1
    ContextPtr map_context = active;
    if (id_or_type) {
      if (active->previous()) map_context = active->previous();
      if (has("@type")) {
        const TermDefinition* idef = map_context->find(index);
        if (idef != nullptr && idef->local_context) {
          map_context = scoped_context(map_context, *idef, false, true);
        }
      }
    }
    // 13.8.3.4
    std::optional<std::string> expanded_index = expand_iri(*active, index);
    const bool none = expanded_index && *expanded_index == "@none"sv;
    // 13.8.3.5, 13.8.3.6
    Value items =
        array_of(expand(map_context, std::string_view(key), array_of(index_value), base_url, true));
    for (Value& item : items.as_array()) {            // 13.8.3.7
      if (has("@graph") && !is_graph_object(item)) {  // 13.8.3.7.1
        SourceLoc loc = item.location();
        Object g(mem_);
        g.append_new("@graph", array_of(std::move(item)));
        item = Value(std::move(g));
        item.set_location(loc);
      }
      if (has("@index") && index_key != "@index"sv && !none) {  // 13.8.3.7.2
        Value reexpanded =
            expand_value(*active, std::string_view(index_key), string_at(index, index_loc));
        if (is_value_object(item)) {
          fail("invalid value object",
               "value in property-valued index \"" + std::string(key) + "\" under \"" +
                   std::string(index) + "\" must not be a value object",
               item.location());
        }
        // An index key that expands to nothing cannot hold the index: nothing to add.
        std::optional<std::string> eik = expand_iri(*active, index_key);
        if (eik && item.is_object()) {
          Object& io = item.as_object();
          Value values = array_of(std::move(reexpanded));
          if (Value* existing = io.find(*eik)) {
            values = concat(std::move(values), std::move(*existing));
          }
          note_property(*eik);
          put(io, std::move(*eik), std::move(values), index_loc);
        }
      } else if (has("@index") && !has_key(item, "@index") && !none) {  // 13.8.3.7.3
        put(item.as_object(), "@index", string_at(index, index_loc), index_loc);
      } else if (has("@id") && !has_key(item, "@id") && !none) {  // 13.8.3.7.4
        std::optional<std::string> id = expand_iri(*active, index, true, false);
        put(item.as_object(), "@id", id ? string_at(std::move(*id), index_loc) : Value(),
            index_loc);
      } else if (has("@type") && !none) {  // 13.8.3.7.5
        Value types;
        types.emplace_array(mem_);
        if (const std::string* t = expand_type_iri(*active, string_at(index, index_loc), st)) {
          types.as_array().push_back(string_at(*t, index_loc));
        }
        if (Value* existing = item.as_object().find("@type")) {
          types = concat(std::move(types), std::move(*existing));
        }
        put(item.as_object(), "@type", std::move(types), index_loc);
      }
      out.as_array().push_back(std::move(item));  // 13.8.3.7.6
    }
  }
  return out;
}

// Value Expansion (5.3.2).
Value Expander::expand_value(const ActiveContext& active, const TermDefinition* def,
                             const Value& value) {
  const std::optional<std::string>* type = def != nullptr ? &def->type : nullptr;
  if (type != nullptr && *type && value.is_string()) {
    // 1, 2
    if (**type == "@id"sv || **type == "@vocab"sv) {
      const bool iri = internal::expand_iri_into(iri_, active, value.as_string(), true,
                                                 **type == "@vocab"sv, nullptr);
      if (iri) {
        if (auto w = malformed_id(iri_, value)) {
          opts_.diagnostics->report(Diagnostic{Severity::Warning, file_name(w->loc), w->loc.line,
                                               w->loc.column, std::move(w->code),
                                               std::move(w->message)});
        }
      }
      Value out;
      Value& id = out.emplace_object(mem_).append_new("@id", Value());
      if (iri) {
        id.emplace_string(mem_) = iri_;
        id.set_location(value.location());
      }
      out.set_location(value.location());
      return out;
    }
  }
  // 3 (built in place: the value object is returned, not moved into a Value)
  Value out;
  Object& result = out.emplace_object(mem_);
  result.reserve(2);
  result.append_new("@value", copy(value));
  if (type != nullptr && *type && **type != "@id"sv && **type != "@vocab"sv &&
      **type != "@none"sv) {
    result.append_new("@type", string_at(**type, value.location()));  // 4
  } else if (value.is_string()) {                                     // 5
    // 5.1, 5.2: a term's own mapping (even null) wins over the defaults.
    const Value* language = nullptr;
    std::optional<std::string> language_default;
    if (def != nullptr && def->language) {
      language = &*def->language;
    } else {
      language_default = active.default_language();
    }
    std::optional<std::string> direction;
    if (def != nullptr && def->direction) {
      if (def->direction->is_string()) direction = def->direction->as_string();
    } else {
      direction = active.default_direction();
    }
    if (language != nullptr && language->is_string()) {
      result.append_new("@language", copy(*language));
    } else if (language == nullptr && language_default) {
      result.append_new("@language", Value(*language_default, mem_));
    }
    if (direction) result.append_new("@direction", Value(*direction, mem_));
  }
  out.set_location(value.location());
  return out;
}

// Steps 15 to 20.
Value Expander::finish_object(ActiveProperty ap, ObjectState& st, SourceLoc element_loc) {
  Object& result = st.result;
  if (opts_.diagnostics != nullptr) flush(st, result, ap);
  if (Value* v = result.find("@value")) {  // 15
    // 15.1
    const Value* type = result.find("@type");
    const bool lang_or_dir = result.contains("@language") || result.contains("@direction");
    for (size_t i = 0; i < result.size(); ++i) {
      const std::string_view k = result.key(i);
      if (k != "@direction"sv && k != "@index"sv && k != "@language"sv && k != "@type"sv &&
          k != "@value"sv) {
        fail("invalid value object", "value object must not contain \"" + std::string(k) + "\"",
             result.key_location(i).known() ? result.key_location(i) : element_loc);
      }
    }
    if (type != nullptr && lang_or_dir) {
      fail("invalid value object",
           "value object must not have both @type and @language or @direction",
           type->location().known() ? type->location() : element_loc);
    }
    const bool json_literal =
        type != nullptr && type->is_string() && type->as_string() == "@json"sv;
    if (json_literal) {
      // 15.2: any JSON value is a JSON literal.
    } else if (v->is_null() || (v->is_array() && v->as_array().empty())) {  // 15.3
      return Value();
    } else if (!v->is_string() && result.contains("@language")) {  // 15.4
      fail("invalid language-tagged value",
           "only strings can be language-tagged, found " + std::string(kind_name(*v)),
           v->location().known() ? v->location() : element_loc);
    } else if (type != nullptr) {  // 15.5
      if (!type->is_string() || !is_iri(type->as_string())) {
        fail("invalid typed value",
             "@type of a value object must be an IRI, found " +
                 (type->is_string() ? "\"" + std::string(type->as_string()) + "\""
                                    : std::string(kind_name(*type))),
             type->location().known() ? type->location() : element_loc);
      }
    }
  } else if (Value* t = result.find("@type")) {  // 16
    if (!t->is_array()) *t = array_of(std::move(*t));
  } else if (result.contains("@set") || result.contains("@list")) {  // 17
    if (result.size() > 2 || (result.size() == 2 && !result.contains("@index"))) {
      fail("invalid set or list object",
           "@set/@list object may only contain @index besides @set or @list", element_loc);
    }
    if (Value* s = result.find("@set")) {  // 17.2
      Value set = std::move(*s);
      return set;
    }
  }
  // 18
  if (result.size() == 1 && result.contains("@language")) return Value();
  // 19
  if (!ap || *ap == kGraph) {
    if (result.empty() || result.contains("@value") || result.contains("@list")) return Value();
    if (result.size() == 1 && result.contains("@id")) return Value();
  }
  Value out(std::move(result));
  out.set_location(element_loc);
  return out;
}

}  // namespace

json::Value expand(const json::Value& input, const Options& options, json::Resource* output) {
  // The active context starts with the base option as base IRI and original base.
  ContextPtr active = ActiveContext::initial(options.base, options);
  // expandContext: an object with @context contributes that entry's value.
  if (options.expand_context) {
    const Value& ec = *options.expand_context;
    const Value* local = ec.get("@context");
    active = process_context(active, local != nullptr ? *local : ec, options.base, options);
  }
  Expander expander(options, output);
  Value out = expander.expand(active, std::nullopt, input, options.base, false);
  // Post-processing: a lone @graph is unwrapped; null becomes []; always an array.
  if (out.is_object() && out.as_object().size() == 1) {
    if (Value* g = out.as_object().find("@graph")) {
      Value graph = std::move(*g);
      out = std::move(graph);
    }
  }
  SourceLoc loc = input.location();
  out = to_array(std::move(out), output);
  if (!out.location().known()) out.set_location(loc);
  return out;
}

}  // namespace mospec::jsonld
