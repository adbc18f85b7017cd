#include "rdf/isomorphism.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <unordered_map>

#include "rdf/nquads.hpp"

namespace mospec::rdf {

namespace {

constexpr uint32_t kNotBlank = UINT32_MAX;

uint64_t hash_text(std::string_view s) {
  return std::hash<std::string_view>{}(s);
}

// Everything the search needs about one dataset: its blank nodes (numbered
// densely), the quads that mention them, and table-independent hashes of its
// other terms so that colours computed on both sides are comparable.
struct Side {
  explicit Side(const Dataset& data) : data(data) {
    const TermTable& terms = data.terms();
    blank_of.assign(terms.size(), kNotBlank);
    term_hash.assign(terms.size(), 0);
    for (uint32_t i = 0; i < data.size(); ++i) {
      const Quad& q = data.quads()[i];
      bool has_blank = false;
      for (TermId t : {q.subject, q.predicate, q.object, q.graph}) {
        if (terms[t].kind == TermKind::Blank) {
          has_blank = true;
          if (blank_of[t.index] == kNotBlank) {
            blank_of[t.index] = static_cast<uint32_t>(blanks.size());
            blanks.push_back(t);
          }
        } else if (term_hash[t.index] == 0) {
          term_hash[t.index] = content_hash(terms, t);
        }
      }
      if (has_blank) {
        mixed.push_back(q);
      } else {
        ground.push_back(q);
      }
    }
  }

  static uint64_t content_hash(const TermTable& terms, TermId id) {
    const Term& t = terms[id];
    uint64_t h = detail::mix64(static_cast<uint64_t>(t.kind) + 1);
    h = detail::combine(h, hash_text(t.value));
    if (t.kind == TermKind::Literal) {
      h = detail::combine(h, hash_text(terms[t.datatype].value));
      h = detail::combine(h, hash_text(t.language));
      h = detail::combine(h, hash_text(t.direction));
    }
    return h | 1;  // never 0, which marks "not computed"
  }

  const Dataset& data;
  std::vector<uint32_t> blank_of;   // term index -> blank number, or kNotBlank
  std::vector<TermId> blanks;       // blank number -> term
  std::vector<uint64_t> term_hash;  // term index -> content hash (non-blank terms)
  std::vector<Quad> ground, mixed;
};

using Colours = std::vector<uint64_t>;

// One round of colour refinement: a blank node's new colour hashes its old
// colour with the multiset of (position, colours of the quad) over every quad
// it occurs in. The multiset is summed, so quad order does not matter.
Colours refine_once(const Side& side, const Colours& colours) {
  Colours sums(colours.size(), 0);
  for (const Quad& q : side.mixed) {
    const std::array<TermId, 4> terms{q.subject, q.predicate, q.object, q.graph};
    std::array<uint64_t, 4> h{};
    for (int k = 0; k < 4; ++k) {
      uint32_t b = side.blank_of[terms[k].index];
      h[k] = b == kNotBlank ? side.term_hash[terms[k].index] : colours[b];
    }
    uint64_t quad_hash =
        detail::combine(detail::combine(detail::mix64(h[0]), h[1]), detail::combine(h[2], h[3]));
    for (int k = 0; k < 4; ++k) {
      uint32_t b = side.blank_of[terms[k].index];
      if (b != kNotBlank) sums[b] += detail::combine(quad_hash, static_cast<uint64_t>(k));
    }
  }
  Colours next(colours.size());
  for (size_t i = 0; i < colours.size(); ++i) next[i] = detail::combine(colours[i], sums[i]);
  return next;
}

// Number of distinct colours, by open addressing into a reused buffer: this
// runs once per refinement round, and sorting made it the hot spot.
class DistinctCounter {
 public:
  size_t operator()(const Colours& colours) {
    size_t capacity = 16;
    while (capacity < colours.size() * 2) capacity *= 2;
    slots_.assign(capacity, 0);
    const size_t mask = capacity - 1;
    size_t n = 0;
    bool zero = false;  // 0 marks an empty slot, so the colour 0 is tracked apart
    for (uint64_t c : colours) {
      if (c == 0) {
        zero = true;
        continue;
      }
      for (size_t i = detail::mix64(c) & mask;; i = (i + 1) & mask) {
        if (slots_[i] == c) break;
        if (slots_[i] == 0) {
          slots_[i] = c;
          ++n;
          break;
        }
      }
    }
    return n + (zero ? 1 : 0);
  }

 private:
  std::vector<uint64_t> slots_;
};

class Matcher {
 public:
  Matcher(const Side& a, const Side& b) : a_(a), b_(b) {
    // Non-blank terms of a, translated into b's table once.
    translated_.assign(a.data.terms().size(), TermId::any());
    for (const auto* list : {&a.ground, &a.mixed})
      for (const Quad& q : *list)
        for (TermId t : {q.subject, q.predicate, q.object, q.graph})
          if (a.blank_of[t.index] == kNotBlank && translated_[t.index].is_any())
            translated_[t.index] = b.data.terms().find_equivalent(a.data.terms(), t);
  }

  bool ground_quads_match() const {
    if (a_.ground.size() != b_.ground.size()) return false;
    for (const Quad& q : a_.ground) {
      Quad t{translated_[q.subject.index], translated_[q.predicate.index],
             translated_[q.object.index], translated_[q.graph.index]};
      if (t.subject.is_any() || t.predicate.is_any() || t.object.is_any() || t.graph.is_any() ||
          !b_.data.contains(t))
        return false;
    }
    return true;
  }

  bool search(Colours ca, Colours cb) {
    // Refine both sides in lock step until neither gains colours.
    size_t na = distinct_(ca), nb = distinct_(cb);
    for (;;) {
      Colours ra = refine_once(a_, ca), rb = refine_once(b_, cb);
      size_t ma = distinct_(ra), mb = distinct_(rb);
      ca = std::move(ra);
      cb = std::move(rb);
      if (ma != mb) return false;
      if (ma == na && mb == nb) break;
      na = ma;
      nb = mb;
    }
    Colours sa = ca, sb = cb;
    std::sort(sa.begin(), sa.end());
    std::sort(sb.begin(), sb.end());
    if (sa != sb) return false;

    // Individualise a node of the smallest colour class that is not yet a
    // singleton, trying every same-coloured partner on the other side.
    uint64_t pick = 0;
    size_t pick_size = SIZE_MAX;
    for (size_t i = 0; i < sa.size();) {
      size_t j = i;
      while (j < sa.size() && sa[j] == sa[i]) ++j;
      if (j - i > 1 && j - i < pick_size) {
        pick = sa[i];
        pick_size = j - i;
      }
      i = j;
    }
    if (pick_size == SIZE_MAX) return verify(ca, cb);

    const size_t x = static_cast<size_t>(std::find(ca.begin(), ca.end(), pick) - ca.begin());
    const uint64_t marked = detail::combine(pick, 0x1d1d1d1dULL);
    for (size_t y = 0; y < cb.size(); ++y) {
      if (cb[y] != pick) continue;
      Colours na2 = ca, nb2 = cb;
      na2[x] = marked;
      nb2[y] = marked;
      if (search(std::move(na2), std::move(nb2))) return true;
    }
    return false;
  }

 private:
  // Every colour is a singleton: the bijection is forced; check it.
  bool verify(const Colours& ca, const Colours& cb) const {
    std::unordered_map<uint64_t, uint32_t> in_b;
    for (uint32_t i = 0; i < cb.size(); ++i) in_b.emplace(cb[i], i);
    auto map = [&](TermId t) {
      uint32_t blank = a_.blank_of[t.index];
      if (blank == kNotBlank) return translated_[t.index];
      auto it = in_b.find(ca[blank]);
      return it == in_b.end() ? TermId::any() : b_.blanks[it->second];
    };
    for (const Quad& q : a_.mixed) {
      Quad t{map(q.subject), map(q.predicate), map(q.object), map(q.graph)};
      if (t.subject.is_any() || t.predicate.is_any() || t.object.is_any() || t.graph.is_any() ||
          !b_.data.contains(t))
        return false;
    }
    return true;
  }

  const Side& a_;
  const Side& b_;
  std::vector<TermId> translated_;
  DistinctCounter distinct_;
};

// A quad rendered with every blank node shown as "_:*".
std::string abstract_line(const Dataset& d, const Quad& q) {
  std::string line;
  for (TermId t : {q.subject, q.predicate, q.object, q.graph}) {
    if (t == TermId::default_graph()) continue;
    if (!line.empty()) line += ' ';
    if (d.terms()[t].kind == TermKind::Blank) {
      line += "_:*";
    } else {
      append_ntriples(line, d.terms(), t);
    }
  }
  return line + " .";
}

}  // namespace

bool isomorphic(const Dataset& a, const Dataset& b) {
  if (a.size() != b.size()) return false;
  const Side sa(a), sb(b);
  if (sa.blanks.size() != sb.blanks.size() || sa.mixed.size() != sb.mixed.size()) return false;
  Matcher matcher(sa, sb);
  if (!matcher.ground_quads_match()) return false;
  if (sa.blanks.empty()) return true;
  return matcher.search(Colours(sa.blanks.size(), 1), Colours(sb.blanks.size(), 1));
}

std::string describe_difference(const Dataset& a, const Dataset& b, size_t max_lines) {
  if (isomorphic(a, b)) return {};
  std::map<std::string, long> balance;  // > 0: more in a, < 0: more in b
  for (const Quad& q : a.quads()) ++balance[abstract_line(a, q)];
  for (const Quad& q : b.quads()) --balance[abstract_line(b, q)];
  std::string out = "first has " + std::to_string(a.size()) + " quads, second has " +
                    std::to_string(b.size()) + "\n";
  size_t lines = 0;
  for (int side : {1, -1}) {
    for (const auto& [line, n] : balance) {
      if (n * side <= 0) continue;
      if (lines == max_lines) {
        out += "...\n";
        return out;
      }
      out += side > 0 ? "only in first:  " : "only in second: ";
      out += line;
      if (n * side > 1) out += " (x" + std::to_string(n * side) + ")";
      out += '\n';
      ++lines;
    }
  }
  if (lines == 0)
    out +=
        "same quads up to blank-node labels, but no blank-node bijection maps one onto the "
        "other\n";
  return out;
}

}  // namespace mospec::rdf
