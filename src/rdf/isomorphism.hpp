// RDF dataset isomorphism (a bijection between blank nodes that maps one
// dataset onto the other). Literals compare exactly (lexical form, datatype,
// language, direction).
#pragma once

#include <string>

#include "rdf/dataset.hpp"

namespace mospec::rdf {

bool isomorphic(const Dataset& a, const Dataset& b);

// Human-readable explanation of the first differences (quads without a
// counterpart, blank nodes abstracted), for test failure messages.
std::string describe_difference(const Dataset& a, const Dataset& b, size_t max_lines = 20);

}  // namespace mospec::rdf
