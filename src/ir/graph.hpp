// The one graph reader lowering uses: a loaded model's quads read as the
// flattened union (every file's graph as one set of triples, as `mospec rdf
// --format ntriples` prints it) without copying them into a new dataset.
//
// Answers are those of the flattened union:
//   - objects(), subjects() and instances() are deduplicated and sorted by the
//     terms' lexical forms (so the IR's order never depends on term ids or on
//     the order files were loaded in);
//   - where() gives the location of the first statement (in load order) that
//     mentions the subject and has a known location, counting a triple stated
//     in several files only at its first statement.
// Lookups go through the dataset's posting lists (rdf/dataset.hpp), so each
// costs about the number of statements about its subject, not the model's size.
//
// The reader keeps a reference to the dataset, which must outlive it.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rdf/dataset.hpp"
#include "support/diagnostics.hpp"

namespace mospec::ir {

class Graph {
 public:
  using TermId = rdf::TermId;

  explicit Graph(const rdf::Dataset& dataset);

  const rdf::Dataset& dataset() const { return dataset_; }
  const rdf::TermTable& terms() const { return dataset_.terms(); }

  // The IRI's term, or TermId::any() when the model never mentions it.
  TermId term(std::string_view iri) const { return dataset_.terms().find_iri(iri); }
  std::string_view str(TermId t) const { return dataset_.terms()[t].value; }

  // Objects of (s, p, ?o), subjects of (?s, p, o), and instances of `type`
  // (subjects of rdf:type type); deduplicated, sorted by lexical form. Empty
  // when any given term is absent.
  // Every statement about `s` (duplicates across the model's graphs
  // included), with its location, in the dataset's order.
  struct Statement {
    TermId predicate, object;
    SourceLoc where;
  };
  std::vector<Statement> statements(TermId s) const;
  // statements(s) one by one, without building the list.
  template <class Visit>
  void each_statement(TermId s, Visit&& visit) const {
    if (s.is_any()) return;
    dataset_.scan(s, TermId::any(), TermId::any(), TermId::any(),
                  [&](const rdf::Quad& q, uint32_t i) {
                    visit(Statement{q.predicate, q.object, dataset_.location(i)});
                    return true;
                  });
  }
  std::vector<TermId> objects(TermId s, TermId p) const;
  std::vector<TermId> subjects(TermId p, TermId o) const;
  std::vector<TermId> instances(TermId type) const;
  // The first of objects(s, p), if any.
  std::optional<TermId> object(TermId s, TermId p) const;
  // The one object of (s, p, ?o) without building objects(s, p): any() when
  // there is none; `several` set (and the answer unspecified) when there are
  // two or more distinct ones.
  TermId single_object(TermId s, TermId p, bool& several) const;

  // A subject read property by property (lowering's data): in one pass over
  // its statements, for each of `predicates` its single_object() answer, and
  // which of `types` it has (bit k: has_type(s, types[k]); at most 64 types).
  // An absent `s` reads as nothing (not as has_type's "any subject").
  struct Value {
    TermId first = TermId::any();
    bool several = false;
  };
  struct Reading {
    bool defined = false;  // defined(s)
    uint64_t types = 0;
  };
  Reading read(TermId s, std::span<const TermId> predicates, std::span<Value> values,
               std::span<const TermId> types) const;

  // Whether (s rdf:type type) is stated (any subject when s is absent).
  bool has_type(TermId s, TermId type) const;
  // Whether some statement has `s` as its subject.
  bool defined(TermId s) const;

  // Where `s` is described (see above); unknown when nothing locates it.
  SourceLoc where(TermId s) const;
  // Where (s, p, o) is stated; where(s) when that triple has no known location.
  SourceLoc where(TermId s, TermId p, TermId o) const;

  // The members of the RDF list starting at `head`, in order (the first
  // rdf:first of each cell; stops at rdf:nil, a cell without rdf:first or
  // rdf:rest, or after 10000 cells).
  std::vector<TermId> list(TermId head) const;

  // A literal's numeric value by the XSD lexical rules of its datatype
  // (rdf::xsd::number()); nothing for a non-literal, an ill-formed lexical form or
  // a value that is not finite (INF, NaN).
  std::optional<double> number(TermId lit) const;
  // number() of object(s, p).
  std::optional<double> number(TermId s, TermId p) const;

  // The graphs (files) that state something about `subject`, copied into a new
  // dataset as triples of its default graph, with their locations: the graph
  // of the file that describes a robot's chain, for runtime::chain_from_rdf,
  // without other files' statements (task poses between the robot's frames).
  rdf::Dataset graphs_describing(TermId subject) const;
  // The graphs graphs_describing(subject) copies: those with a statement about
  // `subject`, in the order they first have one.
  std::vector<TermId> graphs_of(TermId subject) const;

 private:
  // Whether quad `i` is the first statement of its triple (in any graph).
  bool first_statement(uint32_t i) const;
  // `terms` deduplicated and sorted by lexical form.
  std::vector<TermId> sorted_unique(std::vector<TermId> terms) const;

  const rdf::Dataset& dataset_;
  TermId rdf_type_, rdf_first_, rdf_rest_, rdf_nil_;
};

}  // namespace mospec::ir
