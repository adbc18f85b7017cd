// RDF terms, interned.
//
// A term is named by a TermId (an index into its TermTable). Comparing two ids
// of the same table compares the terms. All string_views handed out by a
// TermTable point into storage owned by the table and stay valid for its
// lifetime (the table never moves interned text).
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace mospec::rdf {

inline constexpr std::string_view kXsdString = "http://www.w3.org/2001/XMLSchema#string";
inline constexpr std::string_view kRdfLangString =
    "http://www.w3.org/1999/02/22-rdf-syntax-ns#langString";
inline constexpr std::string_view kRdfDirLangString =
    "http://www.w3.org/1999/02/22-rdf-syntax-ns#dirLangString";

enum class TermKind : uint8_t {
  DefaultGraph,  // only valid in the graph position of a quad
  Iri,
  Blank,
  Literal,
};

struct TermId {
  uint32_t index = 0;  // 0 is the default graph
  static constexpr TermId default_graph() { return TermId{0}; }
  static constexpr TermId any() { return TermId{UINT32_MAX}; }  // wildcard in patterns
  constexpr bool is_any() const { return index == UINT32_MAX; }
  friend constexpr bool operator==(TermId, TermId) = default;
  friend constexpr auto operator<=>(TermId, TermId) = default;
};

struct Term {
  TermKind kind = TermKind::DefaultGraph;
  std::string_view value;      // IRI, blank-node label (without "_:"), or lexical form
  TermId datatype;             // literals: the datatype IRI (xsd:string, rdf:langString, ...)
  std::string_view language;   // literals: language tag as written (may be empty)
  std::string_view direction;  // literals: "ltr", "rtl" or empty
};

class TermTable {
 public:
  TermTable();
  TermTable(const TermTable&) = delete;
  TermTable& operator=(const TermTable&) = delete;
  TermTable(TermTable&&) = default;
  TermTable& operator=(TermTable&&) = default;

  TermId iri(std::string_view iri);
  TermId blank(std::string_view label);
  // A blank node whose label is unused in this table ("b0", "b1", ...).
  TermId fresh_blank();
  // datatype defaults to xsd:string; a non-empty language makes it rdf:langString
  // unless a datatype is given explicitly.
  TermId literal(std::string_view lexical, TermId datatype = TermId::default_graph(),
                 std::string_view language = {}, std::string_view direction = {});
  TermId literal(std::string_view lexical, std::string_view datatype_iri);

  // Lookup without interning; returns nullopt-like TermId::any() when absent.
  TermId find_iri(std::string_view iri) const;

  const Term& operator[](TermId id) const { return terms_[id.index]; }
  size_t size() const { return terms_.size(); }

 private:
  std::string_view store(std::string_view text);
  TermId intern(const Term& t);

  std::deque<std::string> text_;  // stable storage for views
  std::vector<Term> terms_;
  std::unordered_map<std::string, uint32_t> index_;  // key encodes kind + fields
  uint64_t next_fresh_ = 0;
};

// N-Triples/N-Quads rendering of a term ("<iri>", "_:label", "\"lex\"^^<dt>", "\"lex\"@en").
std::string to_ntriples(const TermTable&, TermId);

}  // namespace mospec::rdf
