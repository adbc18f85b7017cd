// An in-memory RDF dataset: interned terms, deduplicated quads, indexed
// lookup for every (s, p, o, g) pattern, and the source location each quad
// came from (so later stages can point at file:line).
//
// Indexing: every position (subject, predicate, object, graph) has a posting
// list per term: the indexes of the quads holding that term there, in
// insertion order. A pattern is answered from the shortest posting list among
// its bound positions, filtered on the other bound positions, so lookups with a
// bound subject, or a bound (predicate, object) pair, cost the size of the
// smaller list rather than of the dataset. Posting lists are kept compact (one
// offsets array and one entry array per position, 4 bytes per quad and per
// term) for all but the most recently added quads, which are chained per term
// (first/last quad per term, next quad per quad: no allocation per term) until
// they are folded in; folding happens inside add() when that tail grows past a
// fraction of the dataset, so adding stays amortised O(1) and every const
// member is a pure read (safe to call from several threads at once).
// While automatic compaction is off (a bulk load), add() indexes nothing: the
// quads added since are scanned one by one by lookups until compact() folds
// them, or until add() chains them once compaction is back on.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rdf/id_hash_set.hpp"
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
  // Throws mospec::Error (code "invalid-term") when an id is not a term of
  // terms() (TermId::any(), or an id from another table).
  bool add(const Quad& q, SourceLoc where = {});
  size_t size() const { return quads_.size(); }
  std::span<const Quad> quads() const { return quads_; }
  SourceLoc location(size_t quad_index) const { return locations_[quad_index]; }
  bool contains(const Quad& q) const;
  // Index of the quad, or UINT32_MAX when absent.
  uint32_t find(const Quad& q) const;

  // Every quad matching the pattern; TermId::any() is a wildcard in any position.
  // Results are in insertion order.
  std::vector<uint32_t> match(TermId s, TermId p, TermId o, TermId g = TermId::any()) const;
  // Same, without materialising the result (stop by returning false).
  void for_each(TermId s, TermId p, TermId o, TermId g,
                const std::function<bool(const Quad&, uint32_t index)>& visit) const;
  // Same as for_each, inlined for hot loops: visit(const Quad&, uint32_t) -> bool.
  template <class Visit>
  void scan(TermId s, TermId p, TermId o, TermId g, Visit&& visit) const;
  // Number of matches (stops early at `limit`).
  size_t count(TermId s, TermId p, TermId o, TermId g = TermId::any(),
               size_t limit = SIZE_MAX) const;

  // The union of all graphs as triples in the default graph, deduplicated
  // (the "flattened union" later stages read).
  Dataset flattened_union() const;

  // Copies every quad (re-interning terms) into this dataset, keeping locations.
  // Blank nodes keep their labels: a blank node of `other` is the same node as
  // a blank node of this dataset with the same label. Readers give each
  // document its own label prefix (TermTable::fresh_blank_prefix), so datasets
  // read from different documents never share blank nodes by accident.
  void merge(const Dataset& other);

  // Folds every recently added quad into the compact indexes now.
  void compact();
  // While off, add() neither folds nor indexes (lookups scan the quads added
  // since, which stay correct but cost their number): a loader that adds
  // thousands of quads, looks nothing up in between and then compacts once
  // saves the per-quad index updates and the folds in between. Turning it back
  // on does not fold by itself; the next add() indexes what is pending.
  void set_auto_compact(bool on) { auto_compact_ = on; }
  // Removes the quads at these indexes (any order, duplicates allowed); the
  // others keep their order and locations, but not their indexes. Terms stay.
  void erase(std::span<const uint32_t> quad_indexes);
  // Room for `quads` quads in all, so a loader that knows its size grows once.
  void reserve(size_t quads);
  // Approximate heap use (terms, quads, locations, indexes).
  size_t memory_bytes() const;

 private:
  enum Position : uint8_t { kS, kP, kO, kG };

  // Posting lists for one position. Quads [0, frozen_) are in the compact
  // arrays; each later quad is chained, in insertion order, after the
  // previous later quad with the same term there.
  struct PostingIndex {
    static constexpr uint32_t kNone = UINT32_MAX;
    std::vector<uint32_t> offsets;  // entries of term t: [offsets[t], offsets[t+1])
    std::vector<uint32_t> entries;
    // By term id (sized lazily): the first and last chained quad, and how many.
    std::vector<uint32_t> first, last, count;
    std::vector<uint32_t> next;  // by quad - frozen_: the next chained quad, or kNone

    std::span<const uint32_t> frozen(TermId t) const {
      if (t.index + 1 >= offsets.size()) return {};
      return {entries.data() + offsets[t.index], entries.data() + offsets[t.index + 1]};
    }
    size_t recent_count(TermId t) const { return t.index < count.size() ? count[t.index] : 0; }
    uint32_t recent_first(TermId t) const {
      return t.index < first.size() ? first[t.index] : kNone;
    }
  };

  static TermId at(const Quad& q, int pos) {
    switch (pos) {
      case kS:
        return q.subject;
      case kP:
        return q.predicate;
      case kO:
        return q.object;
      default:
        return q.graph;
    }
  }
  static uint64_t hash_quad(const Quad& q);
  void rebuild_indexes();
  // Appends quad `id` (the next one not chained) to its terms' chains.
  void chain(uint32_t id);

  TermTable terms_;
  std::vector<Quad> quads_;
  std::vector<SourceLoc> locations_;
  detail::IdHashSet position_;  // quad -> index, for deduplication and contains()
  std::array<PostingIndex, 4> index_;
  uint32_t frozen_ = 0;   // quads below this index are in the compact arrays
  uint32_t chained_ = 0;  // quads in [frozen_, chained_) are chained; later ones are not indexed
  bool auto_compact_ = true;
};

template <class Visit>
void Dataset::scan(TermId s, TermId p, TermId o, TermId g, Visit&& visit) const {
  const std::array<TermId, 4> pattern{s, p, o, g};
  int bound = 0;
  for (TermId t : pattern) bound += t.is_any() ? 0 : 1;
  if (bound == 0) {
    for (uint32_t i = 0; i < quads_.size(); ++i)
      if (!visit(quads_[i], i)) return;
    return;
  }
  if (bound == 4) {
    uint32_t i = find(Quad{s, p, o, g});
    if (i != UINT32_MAX) visit(quads_[i], i);
    return;
  }
  // Drive from the shortest posting list among the bound positions.
  int best = -1;
  size_t best_size = SIZE_MAX;
  for (int pos = 0; pos < 4; ++pos) {
    if (pattern[pos].is_any()) continue;
    if (pattern[pos].index >= terms_.size()) return;  // not a term of this dataset
    size_t n = index_[pos].frozen(pattern[pos]).size() + index_[pos].recent_count(pattern[pos]);
    if (n < best_size) {
      best = pos;
      best_size = n;
    }
  }
  const auto n_quads = static_cast<uint32_t>(quads_.size());
  if (best_size == 0 && chained_ == n_quads) return;
  auto matches = [&](const Quad& q, int skip) {
    for (int pos = 0; pos < 4; ++pos)
      if (pos != skip && !pattern[pos].is_any() && at(q, pos) != pattern[pos]) return false;
    return true;
  };
  const PostingIndex& index = index_[best];
  for (uint32_t i : index.frozen(pattern[best])) {
    const Quad& q = quads_[i];
    if (matches(q, best) && !visit(q, i)) return;
  }
  for (uint32_t i = index.recent_first(pattern[best]); i != PostingIndex::kNone;
       i = index.next[i - frozen_]) {
    const Quad& q = quads_[i];
    if (matches(q, best) && !visit(q, i)) return;
  }
  for (uint32_t i = chained_; i < n_quads; ++i) {  // added while not indexing
    const Quad& q = quads_[i];
    if (matches(q, -1) && !visit(q, i)) return;
  }
}

// For a misspelt reference: the IRI, among the subjects of `data`, nearest in
// spelling to `iri` within its namespace (the part up to its last '/' or '#'),
// or "" when none is within a typo's distance (support/spelling.hpp).
std::string nearest_subject_iri(const Dataset& data, std::string_view iri);

}  // namespace mospec::rdf
