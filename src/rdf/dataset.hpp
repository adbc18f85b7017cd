// An in-memory RDF dataset: interned terms, deduplicated quads, indexed
// lookup for every (s, p, o, g) pattern, and the source location each quad
// came from (so later stages can point at file:line).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "rdf/term.hpp"
#include "support/diagnostics.hpp"

namespace mospec::rdf {

struct Quad {
  TermId subject, predicate, object;
  TermId graph = TermId::default_graph();
  friend bool operator==(const Quad&, const Quad&) = default;
  friend auto operator<=>(const Quad&, const Quad&) = default;
};

class Dataset {
 public:
  Dataset() = default;
  Dataset(const Dataset&) = delete;
  Dataset& operator=(const Dataset&) = delete;
  Dataset(Dataset&&) = default;
  Dataset& operator=(Dataset&&) = default;

  TermTable& terms() { return terms_; }
  const TermTable& terms() const { return terms_; }

  // Returns false (and keeps the first location) when the quad is already present.
  bool add(const Quad& q, SourceLoc where = {});
  size_t size() const { return quads_.size(); }
  std::span<const Quad> quads() const { return quads_; }
  SourceLoc location(size_t quad_index) const { return locations_[quad_index]; }
  bool contains(const Quad& q) const;

  // Every quad matching the pattern; TermId::any() is a wildcard in any position.
  // Results are in insertion order.
  std::vector<uint32_t> match(TermId s, TermId p, TermId o, TermId g = TermId::any()) const;
  // Same, without materialising the result (stop by returning false).
  void for_each(TermId s, TermId p, TermId o, TermId g,
                const std::function<bool(const Quad&, uint32_t index)>& visit) const;

  // The union of all graphs as triples in the default graph, deduplicated
  // (the "flattened union" later stages read).
  Dataset flattened_union() const;

  // Copies every quad (re-interning terms) into this dataset, keeping locations.
  void merge(const Dataset& other);

 private:
  TermTable terms_;
  std::vector<Quad> quads_;
  std::vector<SourceLoc> locations_;
  // implementation-defined indices (e.g. per-position posting lists + a hash set)
  struct QuadHash {
    size_t operator()(const Quad& q) const noexcept;
  };
  std::unordered_map<Quad, uint32_t, QuadHash> position_;
  std::unordered_map<uint32_t, std::vector<uint32_t>> by_subject_, by_predicate_, by_object_,
      by_graph_;
};

}  // namespace mospec::rdf
