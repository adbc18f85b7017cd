#include "jsonld/to_rdf.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <memory_resource>
#include <string>
#include <vector>

#include "jsonld/context.hpp"
#include "jsonld/expand.hpp"
#include "jsonld/loader.hpp"
#include "rdf/id_hash_set.hpp"
#include "rdf/iri.hpp"
#include "rdf/term.hpp"
#include "support/arena.hpp"
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

// GCC and Clang's 128-bit integers (__extension__: not ISO C++).
__extension__ using Uint128 = unsigned __int128;

int bit_width(Uint128 v) {
  const auto hi = static_cast<uint64_t>(v >> 64);
  return hi != 0 ? 64 + std::bit_width(hi) : std::bit_width(static_cast<uint64_t>(v));
}

// The sign of x - t * 10^p (-1, 0 or 1), exactly, for a finite x > 0 and
// t < 10^17; 2 when the exponents are beyond what 128 bits hold (the caller
// then takes the slow exact path). x = m * 2^q with m < 2^53, and both sides
// are scaled to integers: m * 5^r * 2^(q + r) against t when p = -r < 0,
// m * 2^(q - p) against t * 5^p otherwise; every product stays below 2^123.
int compare_exact(double x, uint64_t t, int p) {
  int e2 = 0;
  const double fraction = std::frexp(x, &e2);  // x = fraction * 2^e2, fraction in [0.5, 1)
  Uint128 lhs = static_cast<uint64_t>(std::ldexp(fraction, 53));
  int q = e2 - 53;
  Uint128 rhs = t;
  auto pow5 = [](int n) {
    Uint128 v = 1;
    for (int i = 0; i < n; ++i) v *= 5;
    return v;
  };
  if (p >= 0) {
    if (p > 27) return 2;  // t * 5^27 < 2^120
    rhs *= pow5(p);
    q -= p;
  } else {
    if (-p > 30) return 2;  // m * 5^30 < 2^123
    lhs *= pow5(-p);
    q -= p;
  }
  // Compare lhs * 2^q with rhs (both below 2^123); a shift that would pass
  // 2^127 decides the comparison by itself.
  if (q >= 0) {
    if (bit_width(lhs) + q > 127) return 1;
    lhs <<= q;
  } else {
    if (bit_width(rhs) - q > 127) return -1;
    rhs <<= -q;
  }
  return lhs < rhs ? -1 : lhs > rhs ? 1 : 0;
}

// Into `out` (replacing what it held): the converter keeps one string for
// every number's lexical form, so only the first allocates.
void double_lexical(double d, std::string& out) {
  if (!std::isfinite(d) || d == 0) {
    out = double_lexical_exact(d);
    return;
  }
  // 17 correctly rounded significant digits ("d.dddddddddddddddde±XX"). Unless
  // the 17th is a 5 (a possible tie), rounding them to 16 gives what rounding
  // the exact value to 16 digits gives: every 16-digit rounding boundary is a
  // 17-digit number ending in 5, and correct rounding to 17 digits keeps the
  // value on the same side of it. When the 17th is a 5, those 17 digits are
  // the boundary itself, and an exact comparison of the value with them says
  // which way to round (up on a tie, as ECMAScript does).
  char buf[48];
  const double magnitude = std::fabs(d);
  const auto written =
      std::to_chars(buf, buf + sizeof buf, magnitude, std::chars_format::scientific, 16);
  if (written.ec != std::errc() || written.ptr - buf < 20 || buf[1] != '.' || buf[18] != 'e') {
    out = double_lexical_exact(d);
    return;
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
  bool round_up = buf[17] > '5';
  if (buf[17] == '5') {
    uint64_t boundary = 0;  // the 17 digits as an integer
    for (char c : digits) boundary = boundary * 10 + static_cast<uint64_t>(c - '0');
    boundary = boundary * 10 + 5;
    const int sign = compare_exact(magnitude, boundary, exponent - 16);
    if (sign == 2) {
      out = double_lexical_exact(d);
      return;
    }
    round_up = sign >= 0;
  }
  if (round_up) {
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
  out.clear();
  if (d < 0) out += '-';
  out += digits[0];
  out += '.';
  out.append(digits + 1, static_cast<size_t>(last));
  out += 'E';
  char exp_buf[8];
  const auto exp_end = std::to_chars(exp_buf, exp_buf + sizeof exp_buf, exponent).ptr;
  out.append(exp_buf, exp_end);
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
//
// The node map is built and dropped whole within one conversion, so its
// containers draw from one monotonic arena (the Converter's): a few large
// blocks instead of an allocation per node, property and value list, and no
// frees one by one.
using Arena = mospec::Arena;

// Node-map keys (IRIs, "_:" labels, properties, types) as dense numbers. Each
// key is hashed once, where generate() meets it; the node map and emit() then
// index arrays by symbol instead of hashing the (long, shared-prefix) IRI
// strings again. Texts are views of strings that outlive the conversion: the
// expanded document's, or labels in the Converter's arena.
class Symbols {
 public:
  static constexpr uint32_t kNone = UINT32_MAX;

  explicit Symbols(Arena* arena) : text_(arena), hash_(arena) {}
  uint32_t intern(std::string_view s) {
    const uint64_t hash = rdf::detail::hash_text(s);
    const uint32_t found = index_.find(hash, [&](uint32_t id) { return text_[id] == s; });
    if (found != kNone) return found;
    const auto id = static_cast<uint32_t>(text_.size());
    text_.push_back(s);
    hash_.push_back(hash);
    index_.insert(hash, id);
    return id;
  }
  std::string_view text(uint32_t id) const { return text_[id]; }
  // rdf::detail::hash_text(text(id)), kept for the term table.
  uint64_t hash(uint32_t id) const { return hash_[id]; }
  size_t size() const { return text_.size(); }

 private:
  rdf::detail::IdHashSet index_;
  std::pmr::vector<std::string_view> text_;
  std::pmr::vector<uint64_t> hash_;
};

struct Item {
  enum class Kind : uint8_t { Value, Ref, List };
  Kind kind = Kind::Value;
  uint32_t id = Symbols::kNone;        // Kind::Ref: node map key
  const json::Value* value = nullptr;  // Kind::Value: the value object
  std::pmr::vector<Item> list;         // Kind::List (given the arena when made)
  SourceLoc where;                     // the subject node object's "@id" (or the object)
};

struct Node {
  explicit Node(Arena* arena) : types(arena), properties(arena) {}
  SourceLoc where;
  std::pmr::vector<std::pair<uint32_t, SourceLoc>> types;
  // In the order first met; emit() visits them ordered by property. A node
  // has a handful, so a scan finds one faster than a map would.
  std::pmr::vector<std::pair<uint32_t, std::pmr::vector<Item>>> properties;
  const json::Value* index = nullptr;

  // The index of `property` in `properties`, added if new (its value list in
  // the node's arena).
  size_t slot(uint32_t property) {
    for (size_t i = 0; i < properties.size(); ++i) {
      if (properties[i].first == property) return i;
    }
    properties.emplace_back(property, std::pmr::vector<Item>(properties.get_allocator()));
    return properties.size() - 1;
  }
};

// The nodes of one graph, by subject symbol; emit() visits them ordered by
// subject.
class Graph {
 public:
  explicit Graph(Arena* arena) : arena_(arena), nodes_(arena), ids_(arena), by_id_(arena) {}
  bool empty() const { return nodes_.empty(); }
  // The node of `id` and whether it was created now. Nodes never move.
  std::pair<Node*, bool> try_emplace(uint32_t id) {
    if (id >= by_id_.size()) by_id_.resize(std::max<size_t>(id + 1, 2 * by_id_.size()), kNone);
    uint32_t& n = by_id_[id];
    const bool fresh = n == kNone;
    if (fresh) {
      n = static_cast<uint32_t>(nodes_.size());
      nodes_.emplace_back(arena_);
      ids_.push_back(id);
    }
    return {&nodes_[n], fresh};
  }
  // Node indexes ordered by subject.
  std::vector<uint32_t> order(const Symbols& symbols) const {
    std::vector<uint32_t> out(ids_.size());
    for (uint32_t i = 0; i < out.size(); ++i) out[i] = i;
    std::sort(out.begin(), out.end(), [&](uint32_t a, uint32_t b) {
      return symbols.text(ids_[a]) < symbols.text(ids_[b]);
    });
    return out;
  }
  uint32_t id(uint32_t i) const { return ids_[i]; }
  Node& node(uint32_t i) { return nodes_[i]; }

 private:
  static constexpr uint32_t kNone = UINT32_MAX;
  Arena* arena_;
  std::pmr::deque<Node> nodes_;
  std::pmr::vector<uint32_t> ids_;
  std::pmr::vector<uint32_t> by_id_;  // by symbol: index in nodes_, or kNone
};

// A graph of the node map with the symbol of its name (kNone: the default graph).
struct NamedGraph {
  NamedGraph(Arena* arena, uint32_t name_symbol) : name(name_symbol), graph(arena) {}
  uint32_t name;
  Graph graph;
};

struct Triple {
  rdf::TermId s, p, o;
  SourceLoc where;
};

// A term of the output table resolved on first use, so terms are interned in
// the order the conversion first needs them (as with a plain lookup each time).
class LazyIri {
 public:
  explicit constexpr LazyIri(std::string_view iri) : iri_(iri) {}
  rdf::TermId get(rdf::TermTable& terms) {
    if (id_.is_any()) id_ = terms.iri(iri_);
    return id_;
  }

 private:
  std::string_view iri_;
  rdf::TermId id_ = rdf::TermId::any();
};

class Converter {
 public:
  Converter(rdf::Dataset& out, const Options& options, std::pmr::memory_resource* scratch)
      : out_(out), options_(options), arena_(16 * 1024, scratch) {}

  void run(const json::Value& expanded) {
    generate(expanded, graph_named("@default"sv, Symbols::kNone), nullptr, nullptr, Symbols::kNone,
             nullptr, SourceLoc{});
    emit();
  }

 private:
  // Per symbol: what it stands for once converted, and (for a document's
  // blank-node label) the fresh label it was given.
  struct SymbolInfo {
    rdf::TermId term = kUnresolved;  // kUnresolved, TermId::any() (ill-formed), or the term
    uint32_t relabeled = Symbols::kNone;
  };
  static constexpr rdf::TermId kUnresolved{UINT32_MAX - 1};

  uint32_t symbol(std::string_view text) {
    const uint32_t id = symbols_.intern(text);
    if (id >= info_.size()) info_.resize(symbols_.size());
    return id;
  }
  // The symbol of a node-map key written in the document: blank-node labels
  // are replaced by fresh ones.
  uint32_t key(std::string_view text) {
    return is_blank_id(text) ? relabel(symbol(text)) : symbol(text);
  }

  // Where a value of the active property goes: the property's values of the
  // active subject, created on first use (an empty property adds no entry).
  struct Target {
    Node* subject = nullptr;
    uint32_t property = Symbols::kNone;
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
  // `label`: the symbol of the document's label, or kNone for a node without one.
  uint32_t relabel(uint32_t label) {
    if (label != Symbols::kNone && info_[label].relabeled != Symbols::kNone) {
      return info_[label].relabeled;
    }
    const rdf::TermId fresh = out_.terms().fresh_blank();
    const std::string_view name = out_.terms()[fresh].value;
    auto* text = static_cast<char*>(arena_.allocate(name.size() + 2, 1));
    text[0] = '_';
    text[1] = ':';
    std::memcpy(text + 2, name.data(), name.size());
    const uint32_t key = symbol({text, name.size() + 2});
    info_[key].term = fresh;
    if (label != Symbols::kNone) info_[label].relabeled = key;
    return key;
  }

  std::string file_of(SourceLoc loc) const {
    return options_.loader != nullptr ? options_.loader->files().path(loc.file) : std::string();
  }

  static bool same_value(const Item& a, const Item& b) {
    return a.kind == Item::Kind::Value && b.kind == Item::Kind::Value && *a.value == *b.value;
  }

  // The node map of the graph named `name` (created empty).
  Graph& graph_named(std::string_view name, uint32_t name_symbol) {
    return graphs_.try_emplace(name, &arena_, name_symbol).first->second.graph;
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

  // `target`: where values of the active property goes (unset: no active
  // subject or property). `reverse_subject`: set instead when a reverse
  // property is being processed (then `reverse_property` names it).
  void generate(const json::Value& element, Graph& graph, std::pmr::vector<Item>* list,
                const Item* reverse_subject, uint32_t reverse_property, Target* target,
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
      Item item{Item::Kind::Value, Symbols::kNone, &element, {}, subject_where};
      if (list != nullptr) {
        list->push_back(std::move(item));
      } else if (target != nullptr && *target) {
        add_to(target->get(), std::move(item));
      }
      return;
    }
    if (const json::Value* list_members = list_kw) {
      Item result{Item::Kind::List, Symbols::kNone, nullptr, std::pmr::vector<Item>(&arena_),
                  subject_where};
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
    uint32_t id;
    if (const json::Value* v = id_kw) {
      // A non-string @id (only possible for ignored keyword-like values) stays
      // empty: never well-formed, so its triples are dropped.
      id = key(v->is_string() ? std::string_view(v->as_string()) : std::string_view());
    } else {
      id = relabel(Symbols::kNone);
    }
    auto [node_ptr, created] = graph.try_emplace(id);
    Node& node = *node_ptr;
    if (created) {
      node.where = where;
      node.properties.reserve(properties.size());  // each property key is one slot
    }

    if (reverse_subject != nullptr) {
      if (!symbols_.text(reverse_property).empty()) {
        Item ref = *reverse_subject;
        ref.where = where;
        node.properties[node.slot(reverse_property)].second.push_back(std::move(ref));
      }
    } else if (list != nullptr) {
      list->push_back(Item{Item::Kind::Ref, id, nullptr, {}, subject_where});
    } else if (target != nullptr && *target) {
      target->get().push_back(Item{Item::Kind::Ref, id, nullptr, {}, subject_where});
    }

    if (const json::Value* types = type_kw) {
      auto add_type = [&](const json::Value& t) {
        if (t.is_string()) node.types.emplace_back(key(t.as_string()), where);
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
                    "node <" + std::string(symbols_.text(id)) + "> has conflicting @index values " +
                        json::dump(*node.index) + " and " + json::dump(*index),
                    file_of(at), at.line, at.column);
      }
      node.index = index;
    }

    if (const json::Value* reverse = reverse_kw; reverse && reverse->is_object()) {
      Item referenced{Item::Kind::Ref, id, nullptr, {}, where};
      const json::Object& map = reverse->as_object();
      for (std::string_view property : map.sorted_keys()) {
        generate(*map.find(property), graph, nullptr, &referenced, key(property), nullptr, where);
      }
    }

    if (const json::Value* g = graph_kw) {
      generate(*g, graph_named(symbols_.text(id), id), nullptr, nullptr, Symbols::kNone, nullptr,
               where);
    }
    if (const json::Value* included = included_kw) {
      generate(*included, graph, nullptr, nullptr, Symbols::kNone, nullptr, where);
    }

    std::sort(properties.begin(), properties.end(),
              [&members](size_t a, size_t b) { return members.key(a) < members.key(b); });
    for (size_t i : properties) {
      Target values{&node, key(members.key(i))};
      generate(members.value(i), graph, nullptr, nullptr, Symbols::kNone, &values, where);
    }
  }

  // ---------------------------------------------------------------------------
  // Deserialize JSON-LD to RDF (API spec 8.1.2).

  // The RDF term of a node-map key, TermId::any() when it is not a
  // well-formed IRI (resolved once per symbol).
  rdf::TermId resource(uint32_t id) {
    rdf::TermId& term = info_[id].term;
    if (term == kUnresolved) {
      const std::string_view text = symbols_.text(id);
      // Every "_:" key is a relabeled one, whose term relabel() set; this is
      // only a fallback.
      term = is_blank_id(text) ? out_.terms().blank(text.substr(2))
                               : out_.terms().well_formed_iri(text, symbols_.hash(id));
    }
    return term;
  }

  void emit() {
    rdf::TermTable& terms = out_.terms();
    const rdf::TermId rdf_type = terms.iri(vocab::rdf::type);
    for (auto& [graph_name, named] : graphs_) {
      Graph& graph = named.graph;
      if (graph.empty()) continue;  // nothing was put in it
      rdf::TermId graph_term = rdf::TermId::default_graph();
      if (named.name == Symbols::kNone) {
        if (!options_.default_graph.empty()) graph_term = terms.iri(options_.default_graph);
      } else {
        graph_term = resource(named.name);
        if (graph_term.is_any()) continue;
      }
      for (uint32_t n : graph.order(symbols_)) {
        Node& node = graph.node(n);
        const rdf::TermId subject = resource(graph.id(n));
        if (subject.is_any()) continue;
        for (const auto& [type, where] : node.types) {
          if (const rdf::TermId t = resource(type); !t.is_any()) {
            out_.add({subject, rdf_type, t, graph_term}, where);
          }
        }
        std::sort(node.properties.begin(), node.properties.end(),
                  [this](const auto& a, const auto& b) {
                    return symbols_.text(a.first) < symbols_.text(b.first);
                  });
        for (const auto& [property, values] : node.properties) {
          if (is_blank_id(symbols_.text(property)) && !options_.produce_generalized_rdf) continue;
          const rdf::TermId predicate = resource(property);
          if (predicate.is_any()) continue;
          for (const Item& item : values) {
            list_triples_.clear();
            if (const rdf::TermId object = object_to_rdf(item, list_triples_); !object.is_any()) {
              out_.add({subject, predicate, object, graph_term}, item.where);
            }
            for (const Triple& t : list_triples_) out_.add({t.s, t.p, t.o, graph_term}, t.where);
          }
        }
      }
    }
  }

  // Object to RDF Conversion (API spec 8.1.3); TermId::any() means "drop the
  // triple".
  rdf::TermId object_to_rdf(const Item& item, std::vector<Triple>& list_triples) {
    switch (item.kind) {
      case Item::Kind::Ref:
        return resource(item.id);
      case Item::Kind::List:
        return list_to_rdf(item, list_triples);
      case Item::Kind::Value:
        break;
    }
    constexpr rdf::TermId kDrop = rdf::TermId::any();
    rdf::TermTable& terms = out_.terms();
    // One pass over the value object's members (expansion left at most these).
    const json::Value *value_ptr = nullptr, *type = nullptr, *language = nullptr,
                      *direction = nullptr;
    const json::Object& object = item.value->as_object();
    for (size_t i = 0; i < object.size(); ++i) {
      const std::string_view key = object.key(i);
      if (key == "@value"sv) {
        value_ptr = &object.value(i);
      } else if (key == "@type"sv) {
        type = &object.value(i);
      } else if (key == "@language"sv) {
        language = &object.value(i);
      } else if (key == "@direction"sv) {
        direction = &object.value(i);
      }
    }
    const json::Value& value = *value_ptr;

    // The datatype's term when @type gives one (resolved by symbol, like node
    // keys); a default from the value's kind otherwise.
    rdf::TermId datatype = kUnresolved;
    bool json_literal = false;
    if (type != nullptr) {
      if (!type->is_string()) return kDrop;
      if (type->as_string() == "@json"sv) {
        json_literal = true;
      } else {
        datatype = resource(symbol(type->as_string()));
        if (datatype.is_any()) return kDrop;
      }
    }
    if (language != nullptr &&
        (!language->is_string() || !is_well_formed_language(language->as_string()))) {
      return kDrop;
    }

    std::string_view lexical;
    if (json_literal) {
      try {
        lexical_storage_ = json::canonicalize(value);
      } catch (const Error& e) {
        // canonicalize() knows the line and column, not the file.
        const Diagnostic& d = e.diagnostic();
        throw Error(e.code(), d.message, d.file.empty() ? file_of(value.location()) : d.file,
                    d.line, d.column);
      }
      lexical = lexical_storage_;
      datatype = rdf_json_.get(terms);
    } else if (value.is_bool()) {
      lexical = value.as_bool() ? "true" : "false";
      if (datatype == kUnresolved) datatype = xsd_boolean_.get(terms);
    } else if (value.is_number()) {
      const double d = value.as_number();
      // A JSON *string* typed xsd:double keeps its lexical form; only JSON
      // numbers are put in canonical form.
      if (std::fmod(d, 1.0) != 0 || std::fabs(d) >= 1e21 || !std::isfinite(d) ||
          (datatype != kUnresolved && terms[datatype].value == kXsdDouble)) {
        double_lexical(d, lexical_storage_);
        lexical = lexical_storage_;
        if (datatype == kUnresolved) datatype = xsd_double_.get(terms);
      } else {
        lexical = lexical_storage_ = integer_lexical(d);
        if (datatype == kUnresolved) datatype = xsd_integer_.get(terms);
      }
    } else if (value.is_string()) {
      lexical = value.as_string();
      if (datatype == kUnresolved) {
        datatype =
            language != nullptr ? rdf::TermTable::rdf_lang_string() : rdf::TermTable::xsd_string();
      }
    } else {
      return kDrop;  // arrays/objects/null need @json; expansion rejects them
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
      const rdf::TermId xsd_string = rdf::TermTable::xsd_string();
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
    if (language != nullptr) return terms.literal(lexical, datatype, language->as_string());
    return terms.literal(lexical, datatype);
  }

  // List to RDF Conversion (API spec 8.1.4).
  rdf::TermId list_to_rdf(const Item& list, std::vector<Triple>& list_triples) {
    rdf::TermTable& terms = out_.terms();
    if (list.list.empty()) return rdf_nil_.get(terms);
    std::pmr::vector<rdf::TermId> bnodes(&arena_);
    bnodes.reserve(list.list.size());
    for (size_t i = 0; i < list.list.size(); ++i) bnodes.push_back(terms.fresh_blank());
    const rdf::TermId first = rdf_first_.get(terms);
    const rdf::TermId rest = rdf_rest_.get(terms);
    const rdf::TermId nil = rdf_nil_.get(terms);
    for (size_t i = 0; i < list.list.size(); ++i) {
      const Item& item = list.list[i];
      std::vector<Triple> embedded;
      if (const rdf::TermId object = object_to_rdf(item, embedded); !object.is_any()) {
        list_triples.push_back({bnodes[i], first, object, item.where});
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
  Arena arena_;
  Symbols symbols_{&arena_};
  std::pmr::vector<SymbolInfo> info_{&arena_};                   // by symbol
  std::pmr::map<std::string_view, NamedGraph> graphs_{&arena_};  // ordered by graph name
  std::vector<Triple> list_triples_;  // emit()'s scratch, reused per value
  std::string lexical_storage_;       // object_to_rdf()'s scratch
  LazyIri xsd_boolean_{kXsdBoolean}, xsd_double_{kXsdDouble}, xsd_integer_{kXsdInteger},
      rdf_json_{kRdfJson}, rdf_first_{vocab::rdf::first}, rdf_rest_{vocab::rdf::rest},
      rdf_nil_{vocab::rdf::nil};
};

}  // namespace

void to_rdf(const json::Value& expanded, rdf::Dataset& out, const Options& options,
            std::pmr::memory_resource* scratch) {
  Converter(out, options, scratch).run(expanded);
}

void load_into(const json::Value& document, rdf::Dataset& out, const Options& options) {
  json::Value expanded = expand(document, options);
  to_rdf(expanded, out, options);
}

}  // namespace mospec::jsonld
