#include "ir/graph.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <unordered_map>

#include "rdf/xsd.hpp"
#include "vocab/w3c.hpp"

namespace mospec::ir {

Graph::Graph(const rdf::Dataset& dataset)
    : dataset_(dataset),
      rdf_type_(term(vocab::rdf::type)),
      rdf_first_(term(vocab::rdf::first)),
      rdf_rest_(term(vocab::rdf::rest)),
      rdf_nil_(term(vocab::rdf::nil)) {}

std::vector<Graph::Statement> Graph::statements(TermId s) const {
  std::vector<Statement> out;
  if (s.is_any()) return out;
  dataset_.scan(s, TermId::any(), TermId::any(), TermId::any(),
                [&](const rdf::Quad& q, uint32_t i) {
                  out.push_back({q.predicate, q.object, dataset_.location(i)});
                  return true;
                });
  return out;
}

Graph::TermId Graph::single_object(TermId s, TermId p, bool& several) const {
  several = false;
  TermId first = TermId::any();
  if (s.is_any() || p.is_any()) return first;
  dataset_.scan(s, p, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t) {
    if (first.is_any()) {
      first = q.object;
      return true;
    }
    if (q.object == first) return true;  // the same triple in another graph
    several = true;
    return false;
  });
  return first;
}

Graph::Reading Graph::read(TermId s, std::span<const TermId> predicates, std::span<Value> values,
                           std::span<const TermId> types) const {
  Reading r;
  for (Value& v : values) v = {};
  if (s.is_any()) return r;
  const size_t n = std::min(predicates.size(), values.size());
  dataset_.scan(s, TermId::any(), TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t) {
    r.defined = true;
    if (q.predicate == rdf_type_ && !rdf_type_.is_any()) {
      for (size_t k = 0; k < types.size() && k < 64; ++k) {
        if (q.object == types[k] && !types[k].is_any()) r.types |= uint64_t{1} << k;
      }
    }
    for (size_t k = 0; k < n; ++k) {
      if (q.predicate != predicates[k] || predicates[k].is_any()) continue;
      Value& v = values[k];
      if (v.first.is_any()) {
        v.first = q.object;
      } else if (v.first != q.object) {
        v.several = true;
      }
    }
    return true;
  });
  return r;
}

std::vector<Graph::TermId> Graph::sorted_unique(std::vector<TermId> terms) const {
  // By lexical form; distinct terms with one form (an IRI and a string, say)
  // by id, so that copies of one term end up side by side.
  std::sort(terms.begin(), terms.end(), [&](TermId a, TermId b) {
    const int c = str(a).compare(str(b));
    return c != 0 ? c < 0 : a.index < b.index;
  });
  // The same term twice is a triple stated in several files.
  terms.erase(std::unique(terms.begin(), terms.end()), terms.end());
  return terms;
}

std::vector<Graph::TermId> Graph::objects(TermId s, TermId p) const {
  std::vector<TermId> out;
  if (s.is_any() || p.is_any()) return out;
  out.reserve(8);  // grown once for most lists, not four times
  dataset_.scan(s, p, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t) {
    out.push_back(q.object);
    return true;
  });
  return sorted_unique(std::move(out));
}

std::vector<Graph::TermId> Graph::subjects(TermId p, TermId o) const {
  std::vector<TermId> out;
  if (p.is_any() || o.is_any()) return out;
  out.reserve(8);  // grown once for most lists, not four times
  dataset_.scan(TermId::any(), p, o, TermId::any(), [&](const rdf::Quad& q, uint32_t) {
    out.push_back(q.subject);
    return true;
  });
  return sorted_unique(std::move(out));
}

std::vector<Graph::TermId> Graph::instances(TermId type) const {
  return subjects(rdf_type_, type);
}

std::optional<Graph::TermId> Graph::object(TermId s, TermId p) const {
  // The usual single value without building and sorting the list.
  bool several = false;
  const TermId one = single_object(s, p, several);
  if (several) return objects(s, p).front();
  if (one.is_any()) return std::nullopt;
  return one;
}

bool Graph::has_type(TermId s, TermId type) const {
  return !type.is_any() && !rdf_type_.is_any() &&
         dataset_.count(s, rdf_type_, type, TermId::any(), 1) > 0;
}

bool Graph::defined(TermId s) const {
  return !s.is_any() && dataset_.count(s, TermId::any(), TermId::any(), TermId::any(), 1) > 0;
}

bool Graph::first_statement(uint32_t i) const {
  const rdf::Quad& q = dataset_.quads()[i];
  uint32_t first = i;
  dataset_.scan(q.subject, q.predicate, q.object, TermId::any(), [&](const rdf::Quad&, uint32_t j) {
    first = j;  // matches come in load order: the first one is the first statement
    return false;
  });
  return first == i;
}

SourceLoc Graph::where(TermId s) const {
  SourceLoc loc;
  if (s.is_any()) return loc;
  dataset_.scan(s, TermId::any(), TermId::any(), TermId::any(), [&](const rdf::Quad&, uint32_t i) {
    if (!dataset_.location(i).known() || !first_statement(i)) return true;
    loc = dataset_.location(i);
    return false;
  });
  return loc;
}

SourceLoc Graph::where(TermId s, TermId p, TermId o) const {
  SourceLoc loc;
  if (!s.is_any() && !p.is_any()) {
    dataset_.scan(s, p, o, TermId::any(), [&](const rdf::Quad&, uint32_t i) {
      if (!dataset_.location(i).known() || !first_statement(i)) return true;
      loc = dataset_.location(i);
      return false;
    });
  }
  return loc.known() ? loc : where(s);
}

std::vector<Graph::TermId> Graph::list(TermId head) const {
  std::vector<TermId> out;
  for (int guard = 0; guard < 10000 && !head.is_any() && head != rdf_nil_; ++guard) {
    auto first = object(head, rdf_first_);
    if (!first) break;
    out.push_back(*first);
    auto rest = object(head, rdf_rest_);
    if (!rest) break;
    head = *rest;
  }
  return out;
}

std::optional<double> Graph::number(TermId lit) const {
  if (lit.is_any() || !terms()[lit].is_literal()) return std::nullopt;
  const rdf::Term& t = terms()[lit];
  auto v = rdf::xsd::number(t.value, terms()[t.datatype].value);
  if (!v || !std::isfinite(*v)) return std::nullopt;
  return v;
}

std::optional<double> Graph::number(TermId s, TermId p) const {
  auto o = object(s, p);
  return o ? number(*o) : std::nullopt;
}

std::vector<Graph::TermId> Graph::graphs_of(TermId subject) const {
  std::vector<TermId> graphs;
  if (subject.is_any()) return graphs;
  dataset_.scan(subject, TermId::any(), TermId::any(), TermId::any(),
                [&](const rdf::Quad& q, uint32_t) {
                  if (std::find(graphs.begin(), graphs.end(), q.graph) == graphs.end())
                    graphs.push_back(q.graph);
                  return true;
                });
  return graphs;
}

rdf::Dataset Graph::graphs_describing(TermId subject) const {
  rdf::Dataset out;
  const std::vector<TermId> graphs = graphs_of(subject);
  // In load order across the graphs, as a filter over all quads would give.
  std::vector<uint32_t> picked;
  for (TermId g : graphs) {
    dataset_.scan(TermId::any(), TermId::any(), TermId::any(), g,
                  [&](const rdf::Quad&, uint32_t i) {
                    picked.push_back(i);
                    return true;
                  });
  }
  if (graphs.size() > 1) std::sort(picked.begin(), picked.end());
  std::unordered_map<uint32_t, TermId> mapped;
  auto map = [&](TermId t) {
    auto [it, fresh] = mapped.try_emplace(t.index);
    if (fresh) it->second = out.terms().import(terms(), t);
    return it->second;
  };
  for (uint32_t i : picked) {
    const rdf::Quad& q = dataset_.quads()[i];
    out.add({map(q.subject), map(q.predicate), map(q.object), TermId::default_graph()},
            dataset_.location(i));
  }
  return out;
}

}  // namespace mospec::ir
