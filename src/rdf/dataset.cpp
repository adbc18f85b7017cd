#include "rdf/dataset.hpp"

#include <algorithm>
#include <string>

#include "support/spelling.hpp"

namespace mospec::rdf {

namespace {
// Below this many recent quads the chained tail is cheap enough; above it the
// tail is folded into the compact arrays once it reaches half the frozen part,
// which keeps the total folding work linear in the number of quads added.
constexpr size_t kMinTail = 512;
}  // namespace

uint64_t Dataset::hash_quad(const Quad& q) {
  // Two words of two ids each, mixed: a third of the cost of mixing each id
  // on its own, and term ids are small and dense, so a full mix is needed
  // only once per word.
  const uint64_t sp = (static_cast<uint64_t>(q.subject.index) << 32) | q.predicate.index;
  const uint64_t og = (static_cast<uint64_t>(q.object.index) << 32) | q.graph.index;
  return detail::mix64(detail::mix64(sp) ^ og);
}

uint32_t Dataset::find(const Quad& q) const {
  return position_.find(hash_quad(q), [&](uint32_t i) { return quads_[i] == q; });
}

bool Dataset::contains(const Quad& q) const {
  return find(q) != UINT32_MAX;
}

bool Dataset::add(const Quad& q, SourceLoc where) {
  // An id from another table (or the wildcard) would corrupt the indexes.
  for (int pos = 0; pos < 4; ++pos) {
    if (at(q, pos).index >= terms_.size()) {
      static constexpr const char* kNames[] = {"subject", "predicate", "object", "graph"};
      throw Error("invalid-term", std::string("Dataset::add: ") + kNames[pos] + " id " +
                                      std::to_string(at(q, pos).index) +
                                      " is not a term of this dataset (" +
                                      std::to_string(terms_.size()) + " terms)");
    }
  }
  const uint64_t h = hash_quad(q);
  if (position_.find(h, [&](uint32_t i) { return quads_[i] == q; }) != UINT32_MAX) return false;
  const auto id = static_cast<uint32_t>(quads_.size());
  quads_.push_back(q);
  locations_.push_back(where);
  position_.insert(h, id);
  if (!auto_compact_) return true;  // indexed by compact(), or by a later add()
  const size_t tail = quads_.size() - frozen_;
  if (tail > kMinTail && tail * 2 > frozen_) {
    rebuild_indexes();
  } else {
    while (chained_ < quads_.size()) chain(chained_);
  }
  return true;
}

void Dataset::chain(uint32_t id) {
  const Quad& q = quads_[id];
  for (int pos = 0; pos < 4; ++pos) {
    PostingIndex& index = index_[pos];
    const uint32_t t = at(q, pos).index;
    if (t >= index.first.size()) {
      // Doubling: terms are interned one by one between adds, and growing
      // to each new term id in turn would cost three resizes per add.
      const size_t n = std::max<size_t>({terms_.size(), t + 1, 2 * index.first.size()});
      index.first.resize(n, PostingIndex::kNone);
      index.last.resize(n, PostingIndex::kNone);
      index.count.resize(n, 0);
    }
    index.next.push_back(PostingIndex::kNone);
    if (index.last[t] == PostingIndex::kNone) {
      index.first[t] = id;
    } else {
      index.next[index.last[t] - frozen_] = id;
    }
    index.last[t] = id;
    ++index.count[t];
  }
  chained_ = id + 1;
}

void Dataset::reserve(size_t quads) {
  quads_.reserve(quads);
  locations_.reserve(quads);
  position_.reserve(quads);
}

void Dataset::erase(std::span<const uint32_t> quad_indexes) {
  std::vector<char> gone(quads_.size(), 0);
  for (uint32_t i : quad_indexes) {
    if (i < gone.size()) gone[i] = 1;
  }
  size_t kept = 0;
  for (size_t i = 0; i < quads_.size(); ++i) {
    if (gone[i]) continue;
    quads_[kept] = quads_[i];
    locations_[kept] = locations_[i];
    ++kept;
  }
  quads_.resize(kept);
  locations_.resize(kept);
  position_.clear();
  for (size_t i = 0; i < kept; ++i)
    position_.insert(hash_quad(quads_[i]), static_cast<uint32_t>(i));
  rebuild_indexes();
}

void Dataset::compact() {
  if (frozen_ != quads_.size()) rebuild_indexes();
}

void Dataset::rebuild_indexes() {
  const size_t n_terms = terms_.size();
  for (int pos = 0; pos < 4; ++pos) {
    PostingIndex& index = index_[pos];
    // Counting sort by term id; filling in quad order keeps each list in
    // insertion order. Counts go two slots up so that filling moves each
    // term's start one slot down, onto where offsets[t] must end up.
    // The position's field, picked once (at() would branch per quad).
    static constexpr TermId Quad::*kField[] = {&Quad::subject, &Quad::predicate, &Quad::object,
                                               &Quad::graph};
    const TermId Quad::*field = kField[pos];
    std::vector<uint32_t>& offsets = index.offsets;
    offsets.assign(n_terms + 2, 0);
    for (const Quad& q : quads_) ++offsets[(q.*field).index + 2];
    for (size_t t = 2; t < n_terms + 2; ++t) offsets[t] += offsets[t - 1];
    index.entries.resize(quads_.size());
    const auto n_quads = static_cast<uint32_t>(quads_.size());
    for (uint32_t i = 0; i < n_quads; ++i)
      index.entries[offsets[(quads_[i].*field).index + 1]++] = i;
    offsets.pop_back();  // [offsets[t], offsets[t + 1]) are now the quads of t
    // No chained quads are left; chain() sizes these again when one comes.
    index.first.clear();
    index.last.clear();
    index.count.clear();
    index.next.clear();
  }
  frozen_ = static_cast<uint32_t>(quads_.size());
  chained_ = frozen_;
}

std::vector<uint32_t> Dataset::match(TermId s, TermId p, TermId o, TermId g) const {
  std::vector<uint32_t> out;
  scan(s, p, o, g, [&](const Quad&, uint32_t i) {
    out.push_back(i);
    return true;
  });
  return out;
}

void Dataset::for_each(TermId s, TermId p, TermId o, TermId g,
                       const std::function<bool(const Quad&, uint32_t index)>& visit) const {
  scan(s, p, o, g, visit);
}

size_t Dataset::count(TermId s, TermId p, TermId o, TermId g, size_t limit) const {
  size_t n = 0;
  scan(s, p, o, g, [&](const Quad&, uint32_t) { return ++n < limit; });
  return n;
}

Dataset Dataset::flattened_union() const {
  Dataset out;
  out.set_auto_compact(false);  // folded once at the end
  std::vector<TermId> mapped(terms_.size(), TermId::any());
  auto map = [&](TermId t) {
    TermId& m = mapped[t.index];
    if (m.is_any()) m = out.terms_.import(terms_, t);
    return m;
  };
  for (size_t i = 0; i < quads_.size(); ++i) {
    const Quad& q = quads_[i];
    out.add(Quad{map(q.subject), map(q.predicate), map(q.object), TermId::default_graph()},
            locations_[i]);
  }
  out.compact();
  out.set_auto_compact(true);
  return out;
}

void Dataset::merge(const Dataset& other) {
  if (&other == this) return;
  std::vector<TermId> mapped(other.terms_.size(), TermId::any());
  auto map = [&](TermId t) {
    TermId& m = mapped[t.index];
    if (m.is_any()) m = terms_.import(other.terms_, t);
    return m;
  };
  for (size_t i = 0; i < other.quads_.size(); ++i) {
    const Quad& q = other.quads_[i];
    add(Quad{map(q.subject), map(q.predicate), map(q.object), map(q.graph)}, other.locations_[i]);
  }
}

size_t Dataset::memory_bytes() const {
  size_t bytes = terms_.memory_bytes() + quads_.capacity() * sizeof(Quad) +
                 locations_.capacity() * sizeof(SourceLoc) + position_.memory_bytes();
  for (const PostingIndex& index : index_) {
    bytes += (index.offsets.capacity() + index.entries.capacity()) * sizeof(uint32_t);
    bytes += (index.first.capacity() + index.last.capacity() + index.count.capacity() +
              index.next.capacity()) *
             sizeof(uint32_t);
  }
  return bytes;
}

std::string nearest_subject_iri(const Dataset& data, std::string_view iri) {
  const auto namespace_of = [](std::string_view i) {
    const size_t k = i.find_last_of("#/");
    return k == std::string_view::npos ? std::string_view{} : i.substr(0, k + 1);
  };
  const std::string_view ns = namespace_of(iri);
  Nearest nearest(iri.substr(ns.size()));
  std::string_view best;
  const TermTable& terms = data.terms();
  std::vector<char> offered(terms.size(), 0);
  for (const Quad& q : data.quads()) {
    if (offered[q.subject.index] || !terms[q.subject].is_iri()) continue;
    offered[q.subject.index] = 1;
    const std::string_view candidate = terms[q.subject].value;
    if (candidate == iri || namespace_of(candidate) != ns) continue;
    nearest.offer(candidate.substr(ns.size()));
    if (nearest.best().data() == candidate.data() + ns.size()) best = candidate;
  }
  return std::string(best);
}

}  // namespace mospec::rdf
