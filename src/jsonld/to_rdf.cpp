#include "jsonld/to_rdf.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <map>
#include <memory_resource>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "jsonld/context.hpp"
#include "jsonld/expand.hpp"
#include "jsonld/loader.hpp"
#include "rdf/id_hash_set.hpp"
#include "rdf/iri.hpp"
#include "rdf/term.hpp"
#include "vocab/w3c.hpp"

namespace mospec::jsonld {

namespace {

using namespace std::string_view_literals;

constexpr std::string_view kRdf = vocab::rdf::ns;
constexpr std::string_view kI18n = vocab::i18n::ns;
constexpr std::string_view kRdfJson = vocab::rdf::JSON;
constexpr std::string_view kXsdBoolean = vocab::xsd::boolean;
constexpr std::string_view kXsdDouble = vocab::xsd::double_;
constexpr std::string_view kXsdInteger = vocab::xsd::integer;

struct StringHash {
  using is_transparent = void;
  size_t operator()(std::string_view s) const noexcept { return rdf::detail::hash_text(s); }
};

std::string rdf_iri(std::string_view local) {
  return std::string(kRdf) + std::string(local);
}

bool is_blank_id(std::string_view s) {
  return s.starts_with("_:");
}

bool is_alpha(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// BCP 47 shape (subtags of 1-8 alphanumerics, the first alphabetic); the
// registry itself is not consulted.
bool is_well_formed_language(std::string_view s) {
  size_t start = 0;
  bool first = true;
  while (true) {
    size_t end = s.find('-', start);
    std::string_view sub = s.substr(start, end == std::string_view::npos ? s.npos : end - start);
    if (sub.empty() || sub.size() > 8) return false;
    for (char c : sub) {
      if (first ? !is_alpha(c) : !(is_alpha(c) || is_digit(c))) return false;
    }
    first = false;
    if (end == std::string_view::npos) return true;
    start = end + 1;
  }
}

std::string to_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

// Canonical xsd:integer form of an integral double below 1e21 (JavaScript's
// toFixed(0); -0 prints as "0").
std::string integer_lexical(double d) {
  if (d == 0) return "0";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f", d);
  return buf;
}

// Canonical xsd:double form as the spec computes it: toExponential(15), i.e.
// the mantissa rounded to 15 fractional digits, then trailing zeros trimmed
// (keeping one). Rounding to 15 digits rather than printing the shortest
// round-trip form is what other processors do: 0.0922959556 becomes
// "9.229595559999999E-2", and the upstream corpus expects exactly that.
std::string double_lexical_exact(double d);

std::string double_lexical(double d) {
  if (!std::isfinite(d) || d == 0) return double_lexical_exact(d);
  // 17 correctly rounded significant digits ("d.dddddddddddddddde±XX"). Unless
  // the 17th is a 5 (a possible tie, left to double_lexical_exact), rounding
  // them to 16 gives what rounding the exact value to 16 digits gives: every
  // 16-digit rounding boundary is a 17-digit number ending in 5, and correct
  // rounding to 17 digits keeps the value on the same side of it.
  char buf[48];
  const auto written =
      std::to_chars(buf, buf + sizeof buf, std::fabs(d), std::chars_format::scientific, 16);
  if (written.ec != std::errc() || written.ptr - buf < 20 || buf[1] != '.' || buf[18] != 'e' ||
      buf[17] == '5') {
    return double_lexical_exact(d);
  }
  char digits[16];
  digits[0] = buf[0];
  std::memcpy(digits + 1, buf + 2, 15);
  int exponent = 0;
  {
    const char* p = buf + 19;
    const bool negative_exponent = *p == '-';
    if (*p == '-' || *p == '+') ++p;
    for (; p < written.ptr; ++p) exponent = exponent * 10 + (*p - '0');
    if (negative_exponent) exponent = -exponent;
  }
  if (buf[17] > '5') {
    int i = 15;
    while (i >= 0 && digits[i] == '9') digits[i--] = '0';
    if (i < 0) {
      digits[0] = '1';  // 9.99..9 rounds up to 1.00..0E(x+1)
      ++exponent;
    } else {
      ++digits[i];
    }
  }
  int last = 15;
  while (last > 1 && digits[last] == '0') --last;  // keep one fractional digit
  std::string out;
  out.reserve(24);
  if (d < 0) out += '-';
  out += digits[0];
  out += '.';
  out.append(digits + 1, static_cast<size_t>(last));
  out += 'E';
  char exp_buf[8];
  const auto exp_end = std::to_chars(exp_buf, exp_buf + sizeof exp_buf, exponent).ptr;
  out.append(exp_buf, exp_end);
  return out;
}

// The same, from the exact value in every case (ties included).
std::string double_lexical_exact(double d) {
  if (std::isnan(d)) return "NaN";
  if (std::isinf(d)) return d > 0 ? "INF" : "-INF";
  if (d == 0) return "0.0E0";
  const bool negative = d < 0;
  const double mag = std::fabs(d);
  char buf[1100];
  std::string mantissa;  // "d.ddddddddddddddd"
  int exponent = 0;
  // printf rounds exact ties to even; ECMAScript rounds them up. A tie's 17
  // correctly rounded significant digits end in the tie's "5", so any other
  // 17th digit rules one out (17 digits cost far less than the 41 below: this
  // runs for every number of a model). to_chars with a precision writes what
  // printf would.
  auto written = std::to_chars(buf, buf + sizeof buf - 1, mag, std::chars_format::scientific, 16);
  bool tie = buf[17] == '5';  // buf is "d.dddddddddddddddde..."
  std::string digits;         // 41 significant digits, no point
  if (tie) {
    // A "5" then only zeros up to the 41st digit; then the full expansion (at
    // most 767 digits for a double) decides, in this rare case only.
    written = std::to_chars(buf, buf + sizeof buf - 1, mag, std::chars_format::scientific, 40);
    *written.ptr = '\0';
    const char* p = buf;
    for (; *p != 'e'; ++p) {
      if (*p != '.') digits += *p;
    }
    exponent = std::atoi(p + 1);  // read before buf is reused below
    tie = digits[16] == '5' && digits.find_first_not_of('0', 17) == std::string::npos;
    if (tie) {
      std::snprintf(buf, sizeof buf, "%.800e", mag);
      std::string full;
      for (const char* q = buf; *q != 'e'; ++q) {
        if (*q != '.') full += *q;
      }
      tie = full.find_first_not_of('0', 17) == std::string::npos;
    }
  }
  if (tie) {
    // Round the first 16 digits up by hand.
    std::string m = digits.substr(0, 16);
    int i = 15;
    while (i >= 0 && m[static_cast<size_t>(i)] == '9') m[static_cast<size_t>(i--)] = '0';
    if (i < 0) {
      m.insert(m.begin(), '1');
      m.pop_back();
      ++exponent;
    } else {
      ++m[static_cast<size_t>(i)];
    }
    mantissa.assign(1, m[0]);
    mantissa.append(".").append(m, 1, std::string::npos);
  } else {
    written = std::to_chars(buf, buf + sizeof buf - 1, mag, std::chars_format::scientific, 15);
    *written.ptr = '\0';
    const char* e = std::find(buf, written.ptr, 'e');
    mantissa.assign(buf, static_cast<size_t>(e - buf));
    exponent = std::atoi(e + 1);
  }
  size_t last = mantissa.find_last_not_of('0');
  if (mantissa[last] == '.') ++last;  // keep one fractional digit
  mantissa.erase(last + 1);
  std::string out = negative ? "-" : "";
  out.append(mantissa).append("E").append(std::to_string(exponent));
  return out;
}

// ---------------------------------------------------------------------------
// Node map (API spec 7.2.2), kept in typed form: each entry remembers the
// expanded value it came from and where its subject was written.

// Node-map keys (IRIs and "_:" labels) are views of strings that outlive the
// conversion: the expanded document's, or labels owned by the Converter.
//
// The node map is built and dropped whole within one conversion, so its
// containers draw from one monotonic arena (the Converter's): a few large
// blocks instead of an allocation per node, property and value list, and no
// frees one by one.
using Arena = std::pmr::monotonic_buffer_resource;

struct Item {
  enum class Kind : uint8_t { Value, Ref, List };
  Kind kind = Kind::Value;
  const json::Value* value = nullptr;  // Kind::Value: the value object
  std::string_view id;                 // Kind::Ref: node map key (IRI or "_:" label)
  std::pmr::vector<Item> list;         // Kind::List (given the arena when made)
  SourceLoc where;                     // the subject node object's "@id" (or the object)
};

struct Node {
  explicit Node(Arena* arena) : types(arena), properties(arena) {}
  SourceLoc where;
  std::pmr::vector<std::pair<std::string_view, SourceLoc>> types;
  // In the order first met; emit() visits them ordered by property. A node
  // has a handful, so a scan finds one faster than a map would.
  std::pmr::vector<std::pair<std::string_view, std::pmr::vector<Item>>> properties;
  const json::Value* index = nullptr;

  // The index of `property` in `properties`, added if new (its value list in
  // the node's arena).
  size_t slot(std::string_view property) {
    for (size_t i = 0; i < properties.size(); ++i) {
      if (properties[i].first == property) return i;
    }
    properties.emplace_back(property, std::pmr::vector<Item>(properties.get_allocator()));
    return properties.size() - 1;
  }
};

// The nodes of one graph by subject, hashed; emit() visits them ordered by
// subject.
class Graph {
 public:
  explicit Graph(Arena* arena) : arena_(arena), nodes_(arena), ids_(arena), by_id_(arena) {}
  bool empty() const { return nodes_.empty(); }
  // The node of `id` and whether it was created now. Nodes never move.
  std::pair<Node*, bool> try_emplace(std::string_view id) {
    auto [it, fresh] = by_id_.try_emplace(id, static_cast<uint32_t>(nodes_.size()));
    if (fresh) {
      nodes_.emplace_back(arena_);
      ids_.push_back(id);
    }
    return {&nodes_[it->second], fresh};
  }
  // Node indexes ordered by subject.
  std::vector<uint32_t> order() const {
    std::vector<uint32_t> out(ids_.size());
    for (uint32_t i = 0; i < out.size(); ++i) out[i] = i;
    std::sort(out.begin(), out.end(), [this](uint32_t a, uint32_t b) { return ids_[a] < ids_[b]; });
    return out;
  }
  std::string_view id(uint32_t i) const { return ids_[i]; }
  Node& node(uint32_t i) { return nodes_[i]; }

 private:
  Arena* arena_;
  std::pmr::deque<Node> nodes_;
  std::pmr::vector<std::string_view> ids_;
  std::pmr::unordered_map<std::string_view, uint32_t, StringHash> by_id_;
};

struct Triple {
  rdf::TermId s, p, o;
  SourceLoc where;
};

class Converter {
 public:
  Converter(rdf::Dataset& out, const Options& options) : out_(out), options_(options) {}

  void run(const json::Value& expanded) {
    generate(expanded, graph_named("@default"), nullptr, nullptr, {}, nullptr, SourceLoc{});
    emit();
  }

 private:
  // Where a value of the active property goes: the property's values of the
  // active subject, created on first use (an empty property adds no entry).
  struct Target {
    Node* subject = nullptr;
    std::string_view property;
    size_t slot = SIZE_MAX;  // in subject->properties, once created
    explicit operator bool() const { return subject != nullptr; }
    std::pmr::vector<Item>& get() {
      // An index, not a pointer: nested nodes may add properties to the same
      // subject, which moves its property vector.
      if (slot == SIZE_MAX) slot = subject->slot(property);
      return subject->properties[slot].second;
    }
  };

  // Generate Blank Node Identifier: labels are drawn fresh from the output
  // dataset, so documents loaded into one dataset never share a blank node.
  std::string_view relabel(std::string_view label) {
    if (!label.empty()) {
      auto it = identifiers_.find(label);
      if (it != identifiers_.end()) return it->second;
    }
    rdf::TermId fresh = out_.terms().fresh_blank();
    std::string key = "_:";
    key += out_.terms()[fresh].value;
    std::string_view stored = blank_terms_.emplace(std::move(key), fresh).first->first;
    if (!label.empty()) identifiers_.emplace(std::string(label), stored);
    return stored;
  }

  std::string file_of(SourceLoc loc) const {
    return options_.loader != nullptr ? options_.loader->files().path(loc.file) : std::string();
  }

  static bool same_value(const Item& a, const Item& b) {
    return a.kind == Item::Kind::Value && b.kind == Item::Kind::Value && *a.value == *b.value;
  }

  // The node map of the graph named `name` (created empty).
  Graph& graph_named(std::string_view name) {
    return graphs_.try_emplace(name, &arena_).first->second;
  }

  void add_to(std::pmr::vector<Item>& values, Item item) {
    // Duplicates only change the output where a value object becomes a fresh
    // blank node (compound literals); elsewhere the dataset deduplicates quads.
    if (item.kind == Item::Kind::Value && options_.rdf_direction == RdfDirection::CompoundLiteral &&
        item.value->get("@direction")) {
      for (const Item& existing : values) {
        if (same_value(existing, item)) return;
      }
    }
    values.push_back(std::move(item));
  }

  // `target`: where values of the active property go (unset: no active
  // subject or property). `reverse_subject`: set instead when a reverse
  // property is being processed (then `reverse_property` names it).
  void generate(const json::Value& element, Graph& graph, std::pmr::vector<Item>* list,
                const Item* reverse_subject, std::string_view reverse_property, Target* target,
                SourceLoc subject_where) {
    if (element.is_array()) {
      for (const json::Value& item : element.as_array()) {
        generate(item, graph, list, reverse_subject, reverse_property, target, subject_where);
      }
      return;
    }
    if (!element.is_object()) return;  // expansion never leaves free-floating scalars
    const json::Object& members = element.as_object();
    // One pass over the members: the keywords this algorithm reads, and the
    // positions of the other keys (the node's properties).
    const json::Value *value_kw = nullptr, *list_kw = nullptr, *id_kw = nullptr, *type_kw = nullptr,
                      *index_kw = nullptr, *reverse_kw = nullptr, *graph_kw = nullptr,
                      *included_kw = nullptr;
    std::pmr::vector<size_t> properties(&arena_);  // value objects have none: no allocation
    for (size_t i = 0; i < members.size(); ++i) {
      const std::string_view key = members.key(i);
      if (!key.starts_with('@') || !is_keyword(key)) {
        if (properties.empty()) properties.reserve(members.size() - i);
        properties.push_back(i);
        continue;
      }
      const json::Value* v = &members.value(i);
      if (key == "@value"sv) {
        value_kw = v;
      } else if (key == "@list"sv) {
        list_kw = v;
      } else if (key == "@id"sv) {
        id_kw = v;
      } else if (key == "@type"sv) {
        type_kw = v;
      } else if (key == "@index"sv) {
        index_kw = v;
      } else if (key == "@reverse"sv) {
        reverse_kw = v;
      } else if (key == "@graph"sv) {
        graph_kw = v;
      } else if (key == "@included"sv) {
        included_kw = v;
      }
    }

    if (value_kw != nullptr) {
      Item item{Item::Kind::Value, &element, {}, {}, subject_where};
      if (list != nullptr) {
        list->push_back(std::move(item));
      } else if (target != nullptr && *target) {
        add_to(target->get(), std::move(item));
      }
      return;
    }
    if (const json::Value* list_members = list_kw) {
      Item result{Item::Kind::List, nullptr, {}, std::pmr::vector<Item>(&arena_), subject_where};
      generate(*list_members, graph, &result.list, reverse_subject, reverse_property, target,
               subject_where);
      if (list != nullptr) {
        list->push_back(std::move(result));
      } else if (target != nullptr && *target) {
        target->get().push_back(std::move(result));
      }
      return;
    }

    // A node object.
    const SourceLoc where =
        id_kw != nullptr && id_kw->location().known() ? id_kw->location() : element.location();
    std::string_view id;
    if (const json::Value* v = id_kw) {
      // A non-string @id (only possible for ignored keyword-like values) stays
      // empty: never well-formed, so its triples are dropped.
      if (v->is_string())
        id = is_blank_id(v->as_string()) ? relabel(v->as_string())
                                         : std::string_view(v->as_string());
    } else {
      id = relabel({});
    }
    auto [node_ptr, created] = graph.try_emplace(id);
    Node& node = *node_ptr;
    if (created) {
      node.where = where;
      node.properties.reserve(properties.size());  // each property key is one slot
    }

    if (reverse_subject != nullptr) {
      if (!reverse_property.empty()) {
        Item ref = *reverse_subject;
        ref.where = where;
        node.properties[node.slot(reverse_property)].second.push_back(std::move(ref));
      }
    } else if (list != nullptr) {
      list->push_back(Item{Item::Kind::Ref, nullptr, id, {}, subject_where});
    } else if (target != nullptr && *target) {
      target->get().push_back(Item{Item::Kind::Ref, nullptr, id, {}, subject_where});
    }

    if (const json::Value* types = type_kw) {
      auto add_type = [&](const json::Value& t) {
        if (!t.is_string()) return;
        std::string_view type =
            is_blank_id(t.as_string()) ? relabel(t.as_string()) : std::string_view(t.as_string());
        node.types.emplace_back(type, where);
      };
      if (types->is_array()) {
        for (const json::Value& t : types->as_array()) add_type(t);
      } else {
        add_type(*types);
      }
    }

    if (const json::Value* index = index_kw) {
      if (node.index != nullptr && !(*node.index == *index)) {
        SourceLoc at = index->location();
        throw Error("conflicting indexes",
                    "node <" + std::string(id) + "> has conflicting @index values " +
                        json::dump(*node.index) + " and " + json::dump(*index),
                    file_of(at), at.line, at.column);
      }
      node.index = index;
    }

    if (const json::Value* reverse = reverse_kw; reverse && reverse->is_object()) {
      Item referenced{Item::Kind::Ref, nullptr, id, {}, where};
      const json::Object& map = reverse->as_object();
      for (std::string_view key : map.sorted_keys()) {
        std::string_view prop = is_blank_id(key) ? relabel(key) : key;
        generate(*map.find(key), graph, nullptr, &referenced, prop, nullptr, where);
      }
    }

    if (const json::Value* g = graph_kw) {
      generate(*g, graph_named(id), nullptr, nullptr, {}, nullptr, where);
    }
    if (const json::Value* included = included_kw) {
      generate(*included, graph, nullptr, nullptr, {}, nullptr, where);
    }

    std::sort(properties.begin(), properties.end(),
              [&members](size_t a, size_t b) { return members.key(a) < members.key(b); });
    for (size_t i : properties) {
      std::string_view key = members.key(i);
      Target values{&node, is_blank_id(key) ? relabel(key) : key};
      generate(members.value(i), graph, nullptr, nullptr, {}, &values, where);
    }
  }

  // ---------------------------------------------------------------------------
  // Deserialize JSON-LD to RDF (API spec 8.1.2).

  // The RDF term for a node-map key, or nullopt when it is not well-formed.
  std::optional<rdf::TermId> resource(std::string_view key) {
    if (is_blank_id(key)) {
      auto it = blank_terms_.find(key);
      if (it != blank_terms_.end()) return it->second;
      return out_.terms().blank(key.substr(2));
    }
    const rdf::TermId iri = well_formed_iri(key);
    if (iri.is_any()) return std::nullopt;
    return iri;
  }

  // The term of an IRI, TermId::any() when it is not well-formed (memoised).
  rdf::TermId well_formed_iri(std::string_view iri) {
    auto [it, fresh] = iri_terms_.try_emplace(iri, rdf::TermId::any());
    if (fresh && rdf::is_well_formed_iri(iri)) it->second = out_.terms().iri(iri);
    return it->second;
  }

  // The term of an IRI known to be well-formed (memoised like resource()).
  rdf::TermId iri_term(std::string_view iri) {
    auto [it, fresh] = iri_terms_.try_emplace(iri, rdf::TermId::any());
    if (fresh) it->second = out_.terms().iri(iri);
    return it->second;
  }

  void emit() {
    rdf::TermTable& terms = out_.terms();
    const rdf::TermId rdf_type = terms.iri(rdf_iri("type"));
    for (auto& [graph_name, graph] : graphs_) {
      if (graph.empty()) continue;  // nothing was put in it
      rdf::TermId graph_term = rdf::TermId::default_graph();
      if (graph_name == "@default"sv) {
        if (!options_.default_graph.empty()) graph_term = terms.iri(options_.default_graph);
      } else {
        std::optional<rdf::TermId> g = resource(graph_name);
        if (!g) continue;
        graph_term = *g;
      }
      for (uint32_t n : graph.order()) {
        Node& node = graph.node(n);
        std::optional<rdf::TermId> subject = resource(graph.id(n));
        if (!subject) continue;
        for (const auto& [type, where] : node.types) {
          if (std::optional<rdf::TermId> t = resource(type)) {
            out_.add({*subject, rdf_type, *t, graph_term}, where);
          }
        }
        std::sort(node.properties.begin(), node.properties.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& [property, values] : node.properties) {
          if (is_blank_id(property) && !options_.produce_generalized_rdf) continue;
          std::optional<rdf::TermId> predicate = resource(property);
          if (!predicate) continue;
          for (const Item& item : values) {
            std::vector<Triple> list_triples;
            if (std::optional<rdf::TermId> object = object_to_rdf(item, list_triples)) {
              out_.add({*subject, *predicate, *object, graph_term}, item.where);
            }
            for (const Triple& t : list_triples) out_.add({t.s, t.p, t.o, graph_term}, t.where);
          }
        }
      }
    }
  }

  // Object to RDF Conversion (API spec 8.1.3); nullopt means "drop the triple".
  std::optional<rdf::TermId> object_to_rdf(const Item& item, std::vector<Triple>& list_triples) {
    switch (item.kind) {
      case Item::Kind::Ref:
        return resource(item.id);
      case Item::Kind::List:
        return list_to_rdf(item, list_triples);
      case Item::Kind::Value:
        break;
    }
    rdf::TermTable& terms = out_.terms();
    const json::Value& object = *item.value;
    const json::Value& value = *object.get("@value");
    const json::Value* type = object.get("@type");
    const json::Value* language = object.get("@language");
    const json::Value* direction = object.get("@direction");

    std::optional<std::string_view> datatype;
    if (type != nullptr) {
      if (!type->is_string()) return std::nullopt;
      if (type->as_string() != "@json"sv && well_formed_iri(type->as_string()).is_any()) {
        return std::nullopt;
      }
      datatype = type->as_string();
    }
    if (language != nullptr &&
        (!language->is_string() || !is_well_formed_language(language->as_string()))) {
      return std::nullopt;
    }

    std::string lexical_storage;
    std::string_view lexical;
    if (datatype == "@json"sv) {
      try {
        lexical = lexical_storage = json::canonicalize(value);
      } catch (const Error& e) {
        // canonicalize() knows the line and column, not the file.
        const Diagnostic& d = e.diagnostic();
        throw Error(e.code(), d.message, d.file.empty() ? file_of(value.location()) : d.file,
                    d.line, d.column);
      }
      datatype = kRdfJson;
    } else if (value.is_bool()) {
      lexical = value.as_bool() ? "true" : "false";
      if (!datatype) datatype = kXsdBoolean;
    } else if (value.is_number()) {
      double d = value.as_number();
      // A JSON *string* typed xsd:double keeps its lexical form; only JSON
      // numbers are put in canonical form.
      if (std::fmod(d, 1.0) != 0 || std::fabs(d) >= 1e21 || !std::isfinite(d) ||
          datatype == kXsdDouble) {
        lexical = lexical_storage = double_lexical(d);
        if (!datatype) datatype = kXsdDouble;
      } else {
        lexical = lexical_storage = integer_lexical(d);
        if (!datatype) datatype = kXsdInteger;
      }
    } else if (value.is_string()) {
      lexical = value.as_string();
      if (!datatype) datatype = language != nullptr ? rdf::kRdfLangString : rdf::kXsdString;
    } else {
      return std::nullopt;  // arrays/objects/null need @json; expansion rejects them
    }

    if (direction != nullptr && direction->is_string() &&
        options_.rdf_direction != RdfDirection::None) {
      std::string lang = language != nullptr ? to_lower(language->as_string()) : std::string();
      if (options_.rdf_direction == RdfDirection::I18nDatatype) {
        std::string dt(kI18n);
        dt.append(lang).append("_").append(direction->as_string());
        return terms.literal(lexical, dt);
      }
      rdf::TermId literal = terms.fresh_blank();
      const rdf::TermId xsd_string = terms.iri(rdf::kXsdString);
      list_triples.push_back(
          {literal, terms.iri(rdf_iri("value")), terms.literal(lexical, xsd_string), item.where});
      if (language != nullptr) {
        list_triples.push_back(
            {literal, terms.iri(rdf_iri("language")), terms.literal(lang, xsd_string), item.where});
      }
      list_triples.push_back({literal, terms.iri(rdf_iri("direction")),
                              terms.literal(direction->as_string(), xsd_string), item.where});
      return literal;
    }
    if (language != nullptr) {
      return terms.literal(lexical, iri_term(*datatype), language->as_string());
    }
    return terms.literal(lexical, iri_term(*datatype));
  }

  // List to RDF Conversion (API spec 8.1.4).
  rdf::TermId list_to_rdf(const Item& list, std::vector<Triple>& list_triples) {
    rdf::TermTable& terms = out_.terms();
    if (list.list.empty()) return terms.iri(rdf_iri("nil"));
    std::vector<rdf::TermId> bnodes;
    bnodes.reserve(list.list.size());
    for (size_t i = 0; i < list.list.size(); ++i) bnodes.push_back(terms.fresh_blank());
    const rdf::TermId first = terms.iri(rdf_iri("first"));
    const rdf::TermId rest = terms.iri(rdf_iri("rest"));
    const rdf::TermId nil = terms.iri(rdf_iri("nil"));
    for (size_t i = 0; i < list.list.size(); ++i) {
      const Item& item = list.list[i];
      std::vector<Triple> embedded;
      if (std::optional<rdf::TermId> object = object_to_rdf(item, embedded)) {
        list_triples.push_back({bnodes[i], first, *object, item.where});
      }
      list_triples.push_back(
          {bnodes[i], rest, i + 1 < bnodes.size() ? bnodes[i + 1] : nil, item.where});
      list_triples.insert(list_triples.end(), embedded.begin(), embedded.end());
    }
    return bnodes.front();
  }

  rdf::Dataset& out_;
  const Options& options_;
  // Declared first: destroyed after everything that draws from it.
  Arena arena_{16 * 1024};
  std::pmr::map<std::string_view, Graph> graphs_{&arena_};  // ordered by graph name
  // IRI -> its term, TermId::any() when not well-formed.
  std::pmr::unordered_map<std::string_view, rdf::TermId, StringHash> iri_terms_{&arena_};
  // Document label -> key (a view of a blank_terms_ key).
  std::unordered_map<std::string, std::string_view, StringHash, std::equal_to<>> identifiers_;
  // Key -> fresh blank node (node-based: the keys never move).
  std::unordered_map<std::string, rdf::TermId, StringHash, std::equal_to<>> blank_terms_;
};

}  // namespace

void to_rdf(const json::Value& expanded, rdf::Dataset& out, const Options& options) {
  Converter(out, options).run(expanded);
}

void load_into(const json::Value& document, rdf::Dataset& out, const Options& options) {
  json::Value expanded = expand(document, options);
  to_rdf(expanded, out, options);
}

}  // namespace mospec::jsonld
