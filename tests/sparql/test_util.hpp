// Shared helpers for the SPARQL tests: a dataset from Turtle and results
// rendered as N-Triples text, one line per solution.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rdf/turtle.hpp"
#include "sparql/query.hpp"

namespace mospec::sparql::test {

inline const PrefixMap& prefixes() {
  static const PrefixMap p{
      {"ex", "http://example.org/"},
      {"rdf", "http://www.w3.org/1999/02/22-rdf-syntax-ns#"},
      {"xsd", "http://www.w3.org/2001/XMLSchema#"},
  };
  return p;
}

class Data {
 public:
  explicit Data(std::string_view turtle) {
    std::string text =
        "@prefix ex: <http://example.org/> .\n"
        "@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .\n"
        "@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .\n";
    text += turtle;
    rdf::read_turtle(text, "http://example.org/", data_);
    eval_ = std::make_unique<Evaluator>(data_);
  }

  rdf::Dataset& data() { return data_; }
  Evaluator& eval() { return *eval_; }
  rdf::TermId iri(std::string_view local) {
    return data_.terms().find_iri("http://example.org/" + std::string(local));
  }

  // Each solution as "v1 v2 ..." in projection order (UNDEF when unbound),
  // in result order.
  std::vector<std::string> run(std::string_view query, std::vector<Binding> prebound = {}) {
    Query q = parse_query(query, prefixes());
    ResultSet rs;
    eval_->select(q, prebound, rs);
    std::vector<std::string> out;
    for (size_t r = 0; r < rs.size(); ++r) {
      std::string line;
      for (size_t c = 0; c < rs.variables.size(); ++c) {
        if (c > 0) line += ' ';
        line += eval_->to_ntriples(rs.at(r, c));
      }
      out.push_back(line);
    }
    return out;
  }
  std::vector<std::string> sorted(std::string_view query, std::vector<Binding> prebound = {}) {
    auto out = run(query, std::move(prebound));
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  rdf::Dataset data_;
  std::unique_ptr<Evaluator> eval_;
};

using Rows = std::vector<std::string>;

// The QueryError thrown for `query` (fails the test when none is thrown).
inline QueryError error_of(std::string_view query) {
  try {
    parse_query(query, prefixes());
  } catch (const QueryError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for: " << query;
  return QueryError("", 0, 0, "no error");  // no code
}

}  // namespace mospec::sparql::test
