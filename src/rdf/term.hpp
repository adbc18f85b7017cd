// RDF terms, interned.
//
// A term is named by a TermId (an index into its TermTable). Comparing two ids
// of the same table compares the terms. All string_views handed out by a
// TermTable point into storage owned by the table and stay valid for its
// lifetime (the table never moves interned text, not even when the table
// itself is moved).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "rdf/id_hash_set.hpp"
#include "vocab/w3c.hpp"

namespace mospec::rdf {

inline constexpr std::string_view kXsdString = vocab::xsd::string;
inline constexpr std::string_view kRdfLangString = vocab::rdf::langString;
inline constexpr std::string_view kRdfDirLangString = vocab::rdf::dirLangString;

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

  bool is_iri() const { return kind == TermKind::Iri; }
  bool is_blank() const { return kind == TermKind::Blank; }
  bool is_literal() const { return kind == TermKind::Literal; }
};

class TermTable {
 public:
  TermTable();
  TermTable(const TermTable&) = delete;
  TermTable& operator=(const TermTable&) = delete;
  TermTable(TermTable&&) = default;
  TermTable& operator=(TermTable&&) = default;

  // Always interned by the constructor, so these ids are the same in every table.
  static constexpr TermId xsd_string() { return TermId{1}; }
  static constexpr TermId rdf_lang_string() { return TermId{2}; }
  static constexpr TermId rdf_dir_lang_string() { return TermId{3}; }

  TermId iri(std::string_view iri);
  // The id of `iri` (interned now if new), or TermId::any(), interning
  // nothing, when it is not a well-formed IRI (rdf::is_well_formed_iri). Each
  // distinct IRI is checked once per table however often it is asked for, so
  // a loader converting many documents that share a vocabulary checks it once.
  TermId well_formed_iri(std::string_view iri);
  // Same, for a caller that has hashed the IRI already (text_hash must be
  // detail::hash_text(iri)): the table does not hash it again.
  TermId well_formed_iri(std::string_view iri, uint64_t text_hash);
  TermId blank(std::string_view label);
  // A blank node whose label is unused in this table ("b0", "b1", ...).
  TermId fresh_blank();
  // A label prefix ("r0_", "r1_", ...) that no blank node in this table starts
  // with and that was never handed out before. Readers put it in front of every
  // label of one document so that documents never share blank nodes.
  std::string fresh_blank_prefix();

  // With the default datatype (index 0) the datatype is xsd:string, or
  // rdf:langString when a language is given, or rdf:dirLangString when a
  // language and a direction are given. An explicit datatype is kept as given.
  // The language tag is stored as written (no case folding).
  TermId literal(std::string_view lexical, TermId datatype = TermId::default_graph(),
                 std::string_view language = {}, std::string_view direction = {});
  TermId literal(std::string_view lexical, std::string_view datatype_iri);

  // Lookups without interning; return TermId::any() when absent.
  TermId find_iri(std::string_view iri) const;
  TermId find_blank(std::string_view label) const;
  TermId find_literal(std::string_view lexical, TermId datatype = TermId::default_graph(),
                      std::string_view language = {}, std::string_view direction = {}) const;
  // The id in this table of a term of another table (blank nodes by label).
  TermId find_equivalent(const TermTable& other, TermId id) const;
  // Interns a term of another table here (blank nodes keep their label).
  TermId import(const TermTable& other, TermId id);

  const Term& operator[](TermId id) const { return terms_[id.index]; }
  size_t size() const { return terms_.size(); }
  // Approximate heap use, for benchmarks and memory tests.
  size_t memory_bytes() const;

 private:
  std::string_view store(std::string_view text);
  TermId intern(const Term& t);
  TermId lookup(const Term& t, uint64_t hash) const;
  // Adds a term known to be absent (hash: its hash_term).
  TermId insert(const Term& t, uint64_t hash);
  Term literal_key(std::string_view lexical, TermId datatype, std::string_view language,
                   std::string_view direction) const;

  // Text lives in fixed blocks that are never reallocated, so views stay valid.
  std::vector<std::unique_ptr<char[]>> blocks_;
  size_t block_used_ = 0;
  size_t block_size_ = 0;
  size_t text_bytes_ = 0;

  std::vector<Term> terms_;
  detail::IdHashSet index_;
  // By term id (sized lazily): IRIs that well_formed_iri() has checked.
  std::vector<bool> well_formed_;
  // For every blank label containing '_', the part up to and including the
  // first '_' (so fresh_blank_prefix can prove a prefix unused in O(1)).
  std::unordered_set<std::string_view> blank_stems_;
  uint64_t next_fresh_ = 0;
  uint64_t next_prefix_ = 0;
};

// N-Triples/N-Quads rendering of a term ("<iri>", "_:label", "\"lex\"^^<dt>",
// "\"lex\"@en", "\"lex\"@en--ltr"), escaped as write_nquads does.
std::string to_ntriples(const TermTable&, TermId);
// Same, appended to `out` (avoids a temporary per term when writing documents).
void append_ntriples(std::string& out, const TermTable&, TermId);
// The body of a quoted literal in canonical N-Triples escaping (also valid
// Turtle): \" \\ \n \r as ECHAR, other control characters as \uXXXX.
void append_escaped_literal(std::string& out, std::string_view text);

}  // namespace mospec::rdf
