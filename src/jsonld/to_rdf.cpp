#include "jsonld/to_rdf.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "jsonld/context.hpp"
#include "jsonld/expand.hpp"
#include "jsonld/loader.hpp"
#include "rdf/term.hpp"

namespace mospec::jsonld {

namespace {

constexpr std::string_view kRdf = "http://www.w3.org/1999/02/22-rdf-syntax-ns#";
constexpr std::string_view kXsd = "http://www.w3.org/2001/XMLSchema#";
constexpr std::string_view kI18n = "https://www.w3.org/ns/i18n#";

std::string rdf_iri(std::string_view local) {
  return std::string(kRdf) + std::string(local);
}
std::string xsd_iri(std::string_view local) {
  return std::string(kXsd) + std::string(local);
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
bool is_hex(char c) {
  return is_digit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

// RFC 3987 well-formedness as far as it matters for RDF output: a scheme,
// no characters that IRIs exclude (space, controls, <>"{}|\^`), at most one
// '#', and percent signs that start an escape. Expansion leaves relative references in
// place when there is no base; those are not IRIs and their triples are dropped.
// Per byte after the scheme: 0 ordinary, 1 excluded (controls, space, DEL and
// <>"{}|\^`), 2 '#', 3 '%'.
constexpr std::array<uint8_t, 256> kIriByteClass = [] {
  std::array<uint8_t, 256> t{};
  for (int c = 0; c <= 0x20; ++c) t[static_cast<size_t>(c)] = 1;
  t[0x7f] = 1;
  for (char c : std::string_view("<>\"{}|\\^`")) t[static_cast<unsigned char>(c)] = 1;
  t['#'] = 2;
  t['%'] = 3;
  return t;
}();

bool is_well_formed_iri(std::string_view s) {
  if (s.empty() || !is_alpha(s[0])) return false;
  size_t colon = 0;
  for (size_t i = 1; i < s.size(); ++i) {
    char c = s[i];
    if (c == ':') {
      colon = i;
      break;
    }
    if (!is_alpha(c) && !is_digit(c) && c != '+' && c != '-' && c != '.') return false;
  }
  if (colon == 0) return false;
  bool fragment = false;  // a fragment may not contain another '#'
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  const size_t n = s.size();
  for (size_t i = colon + 1; i < n; ++i) {
    const uint8_t cls = kIriByteClass[p[i]];
    if (cls == 0) continue;
    if (cls == 1) return false;
    if (cls == 2) {
      if (fragment) return false;
      fragment = true;
    } else if (i + 2 >= n || !is_hex(s[i + 1]) || !is_hex(s[i + 2])) {
      return false;
    }
  }
  return true;
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
std::string double_lexical(double d) {
  if (std::isnan(d)) return "NaN";
  if (std::isinf(d)) return d > 0 ? "INF" : "-INF";
  if (d == 0) return "0.0E0";
  const bool negative = d < 0;
  const double mag = std::fabs(d);
  // printf rounds exact ties to even; ECMAScript rounds them up. A tie shows
  // as "5" then only zeros after the 16th significant digit; check the full
  // expansion (at most 767 digits for a double) only in that rare case.
  char buf[1100];
  std::snprintf(buf, sizeof buf, "%.40e", mag);
  std::string digits;  // 41 significant digits, no point
  const char* p = buf;
  for (; *p != 'e'; ++p) {
    if (*p != '.') digits += *p;
  }
  const int exponent40 = std::atoi(p + 1);  // read before buf is reused below
  bool tie = digits[16] == '5' && digits.find_first_not_of('0', 17) == std::string::npos;
  if (tie) {
    std::snprintf(buf, sizeof buf, "%.800e", mag);
    std::string full;
    for (const char* q = buf; *q != 'e'; ++q) {
      if (*q != '.') full += *q;
    }
    tie = full.find_first_not_of('0', 17) == std::string::npos;
  }
  std::string mantissa;
  int exponent = 0;
  if (tie) {
    // Round the first 16 digits up by hand.
    std::string m = digits.substr(0, 16);
    int i = 15;
    while (i >= 0 && m[static_cast<size_t>(i)] == '9') m[static_cast<size_t>(i--)] = '0';
    exponent = exponent40;
    if (i < 0) {
      m = "1" + m.substr(0, 15);
      ++exponent;
    } else {
      ++m[static_cast<size_t>(i)];
    }
    mantissa = m.substr(0, 1) + "." + m.substr(1);
  } else {
    std::snprintf(buf, sizeof buf, "%.15e", mag);
    std::string s = buf;
    size_t e = s.find('e');
    mantissa = s.substr(0, e);
    exponent = std::atoi(s.c_str() + e + 1);
  }
  size_t last = mantissa.find_last_not_of('0');
  if (mantissa[last] == '.') ++last;  // keep one fractional digit
  mantissa.erase(last + 1);
  return (negative ? "-" : "") + mantissa + "E" + std::to_string(exponent);
}

// ---------------------------------------------------------------------------
// Node map (API spec 7.2.2), kept in typed form: each entry remembers the
// expanded value it came from and where its subject was written.

struct Item {
  enum class Kind : uint8_t { Value, Ref, List };
  Kind kind = Kind::Value;
  const json::Value* value = nullptr;  // Kind::Value: the value object
  std::string id;                      // Kind::Ref: node map key (IRI or "_:" label)
  std::vector<Item> list;              // Kind::List
  SourceLoc where;                     // the subject node object's "@id" (or the object)
};

struct Node {
  SourceLoc where;
  std::vector<std::pair<std::string, SourceLoc>> types;
  std::map<std::string, std::vector<Item>> properties;  // ordered by property
  const json::Value* index = nullptr;
};

using Graph = std::map<std::string, Node>;  // ordered by subject

struct Triple {
  rdf::TermId s, p, o;
  SourceLoc where;
};

class Converter {
 public:
  Converter(rdf::Dataset& out, const Options& options) : out_(out), options_(options) {}

  void run(const json::Value& expanded) {
    generate(expanded, "@default", nullptr, nullptr, nullptr, nullptr, SourceLoc{});
    emit();
  }

 private:
  // Generate Blank Node Identifier: labels are drawn fresh from the output
  // dataset, so documents loaded into one dataset never share a blank node.
  std::string relabel(std::string_view label) {
    if (!label.empty()) {
      auto it = identifiers_.find(std::string(label));
      if (it != identifiers_.end()) return it->second;
    }
    rdf::TermId fresh = out_.terms().fresh_blank();
    std::string key = "_:" + std::string(out_.terms()[fresh].value);
    blank_terms_.emplace(key, fresh);
    if (!label.empty()) identifiers_.emplace(std::string(label), key);
    return key;
  }

  std::string file_of(SourceLoc loc) const {
    return options_.loader != nullptr ? options_.loader->files().path(loc.file) : std::string();
  }

  static SourceLoc node_location(const json::Value& element) {
    const json::Value* id = element.get("@id");
    if (id != nullptr && id->location().known()) return id->location();
    return element.location();
  }

  static bool same_value(const Item& a, const Item& b) {
    return a.kind == Item::Kind::Value && b.kind == Item::Kind::Value && *a.value == *b.value;
  }

  void add_to(std::vector<Item>& values, Item item) {
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

  // `subject`: the active subject's node-map key, or null. `reverse_subject`:
  // set instead when a reverse property is being processed.
  void generate(const json::Value& element, const std::string& graph_name,
                const std::string* subject, const Item* reverse_subject,
                const std::string* property, std::vector<Item>* list, SourceLoc subject_where) {
    if (element.is_array()) {
      for (const json::Value& item : element.as_array()) {
        generate(item, graph_name, subject, reverse_subject, property, list, subject_where);
      }
      return;
    }
    if (!element.is_object()) return;  // expansion never leaves free-floating scalars
    Graph& graph = graphs_[graph_name];
    Node* subject_node = subject != nullptr ? &graph[*subject] : nullptr;

    if (element.get("@value") != nullptr) {
      Item item{Item::Kind::Value, &element, {}, {}, subject_where};
      if (list != nullptr) {
        list->push_back(std::move(item));
      } else if (subject_node != nullptr && property != nullptr) {
        add_to(subject_node->properties[*property], std::move(item));
      }
      return;
    }
    if (const json::Value* members = element.get("@list")) {
      Item result{Item::Kind::List, nullptr, {}, {}, subject_where};
      generate(*members, graph_name, subject, reverse_subject, property, &result.list,
               subject_where);
      if (list != nullptr) {
        list->push_back(std::move(result));
      } else if (subject_node != nullptr && property != nullptr) {
        subject_node->properties[*property].push_back(std::move(result));
      }
      return;
    }

    // A node object.
    const SourceLoc where = node_location(element);
    std::string id;
    if (const json::Value* v = element.get("@id")) {
      // A non-string @id (only possible for ignored keyword-like values) stays
      // empty: never well-formed, so its triples are dropped.
      if (v->is_string())
        id = is_blank_id(v->as_string()) ? relabel(v->as_string()) : v->as_string();
    } else {
      id = relabel({});
    }
    auto [node_it, created] = graph.try_emplace(id);
    Node& node = node_it->second;
    if (created) node.where = where;

    if (reverse_subject != nullptr) {
      if (property != nullptr) {
        Item ref = *reverse_subject;
        ref.where = where;
        node.properties[*property].push_back(std::move(ref));
      }
    } else if (property != nullptr) {
      Item ref{Item::Kind::Ref, nullptr, id, {}, subject_where};
      if (list != nullptr) {
        list->push_back(std::move(ref));
      } else if (subject_node != nullptr) {
        subject_node->properties[*property].push_back(std::move(ref));
      }
    }

    if (const json::Value* types = element.get("@type")) {
      auto add_type = [&](const json::Value& t) {
        if (!t.is_string()) return;
        std::string type = is_blank_id(t.as_string()) ? relabel(t.as_string()) : t.as_string();
        node.types.emplace_back(std::move(type), where);
      };
      if (types->is_array()) {
        for (const json::Value& t : types->as_array()) add_type(t);
      } else {
        add_type(*types);
      }
    }

    if (const json::Value* index = element.get("@index")) {
      if (node.index != nullptr && !(*node.index == *index)) {
        SourceLoc at = index->location();
        throw Error("conflicting indexes",
                    "node <" + id + "> has conflicting @index values " + json::dump(*node.index) +
                        " and " + json::dump(*index),
                    file_of(at), at.line, at.column);
      }
      node.index = index;
    }

    if (const json::Value* reverse = element.get("@reverse"); reverse && reverse->is_object()) {
      Item referenced{Item::Kind::Ref, nullptr, id, {}, where};
      const json::Object& map = reverse->as_object();
      for (std::string_view key : map.sorted_keys()) {
        std::string prop = is_blank_id(key) ? relabel(key) : std::string(key);
        generate(*map.find(key), graph_name, nullptr, &referenced, &prop, nullptr, where);
      }
    }

    if (const json::Value* g = element.get("@graph")) {
      generate(*g, id, nullptr, nullptr, nullptr, nullptr, where);
    }
    if (const json::Value* included = element.get("@included")) {
      generate(*included, graph_name, nullptr, nullptr, nullptr, nullptr, where);
    }

    const json::Object& members = element.as_object();
    for (std::string_view key : members.sorted_keys()) {
      if (key.starts_with('@') && is_keyword(key)) continue;
      std::string prop = is_blank_id(key) ? relabel(key) : std::string(key);
      generate(*members.find(key), graph_name, &id, nullptr, &prop, nullptr, where);
    }
  }

  // ---------------------------------------------------------------------------
  // Deserialize JSON-LD to RDF (API spec 8.1.2).

  // The RDF term for a node-map key, or nullopt when it is not well-formed.
  std::optional<rdf::TermId> resource(std::string_view key) {
    if (is_blank_id(key)) {
      auto it = blank_terms_.find(std::string(key));
      if (it != blank_terms_.end()) return it->second;
      return out_.terms().blank(key.substr(2));
    }
    if (!is_well_formed_iri(key)) return std::nullopt;
    return out_.terms().iri(key);
  }

  void emit() {
    rdf::TermTable& terms = out_.terms();
    const rdf::TermId rdf_type = terms.iri(rdf_iri("type"));
    for (auto& [graph_name, graph] : graphs_) {
      rdf::TermId graph_term = rdf::TermId::default_graph();
      if (graph_name == "@default") {
        if (!options_.default_graph.empty()) graph_term = terms.iri(options_.default_graph);
      } else {
        std::optional<rdf::TermId> g = resource(graph_name);
        if (!g) continue;
        graph_term = *g;
      }
      for (auto& [subject_key, node] : graph) {
        std::optional<rdf::TermId> subject = resource(subject_key);
        if (!subject) continue;
        for (const auto& [type, where] : node.types) {
          if (std::optional<rdf::TermId> t = resource(type)) {
            out_.add({*subject, rdf_type, *t, graph_term}, where);
          }
        }
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

    std::optional<std::string> datatype;
    if (type != nullptr) {
      if (!type->is_string()) return std::nullopt;
      if (type->as_string() != "@json" && !is_well_formed_iri(type->as_string())) {
        return std::nullopt;
      }
      datatype = type->as_string();
    }
    if (language != nullptr &&
        (!language->is_string() || !is_well_formed_language(language->as_string()))) {
      return std::nullopt;
    }

    std::string lexical;
    if (datatype == "@json") {
      lexical = json::canonicalize(value);
      datatype = rdf_iri("JSON");
    } else if (value.is_bool()) {
      lexical = value.as_bool() ? "true" : "false";
      if (!datatype) datatype = xsd_iri("boolean");
    } else if (value.is_number()) {
      double d = value.as_number();
      // A JSON *string* typed xsd:double keeps its lexical form; only JSON
      // numbers are put in canonical form.
      if (std::fmod(d, 1.0) != 0 || std::fabs(d) >= 1e21 || !std::isfinite(d) ||
          datatype == xsd_iri("double")) {
        lexical = double_lexical(d);
        if (!datatype) datatype = xsd_iri("double");
      } else {
        lexical = integer_lexical(d);
        if (!datatype) datatype = xsd_iri("integer");
      }
    } else if (value.is_string()) {
      lexical = value.as_string();
      if (!datatype) {
        datatype = std::string(language != nullptr ? rdf::kRdfLangString : rdf::kXsdString);
      }
    } else {
      return std::nullopt;  // arrays/objects/null need @json; expansion rejects them
    }

    if (direction != nullptr && direction->is_string() &&
        options_.rdf_direction != RdfDirection::None) {
      std::string lang = language != nullptr ? to_lower(language->as_string()) : std::string();
      if (options_.rdf_direction == RdfDirection::I18nDatatype) {
        return terms.literal(lexical, std::string(kI18n) + lang + "_" + direction->as_string());
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
      return terms.literal(lexical, terms.iri(*datatype), language->as_string());
    }
    return terms.literal(lexical, terms.iri(*datatype));
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
  std::map<std::string, Graph> graphs_;                       // ordered by graph name
  std::unordered_map<std::string, std::string> identifiers_;  // document label -> key
  std::unordered_map<std::string, rdf::TermId> blank_terms_;  // key -> fresh blank node
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
