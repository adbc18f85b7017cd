// SHACL Core validation of a data graph against a compiled shapes model.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "rdf/dataset.hpp"
#include "shacl/report.hpp"
#include "shacl/shapes.hpp"
#include "sparql/limits.hpp"
#include "support/diagnostics.hpp"

namespace mospec::shacl {

struct ValidateOptions {
  // Where a data node (a term of the data graph's table) is written, for the
  // report's order and the text output (nullopt: not located). Unset: the
  // location of the first triple that has the node as subject (else as object).
  std::function<std::optional<SourceLoc>(rdf::TermId)> locate;
  // Bounds on the SPARQL work of the whole validation: every SPARQL
  // constraint's query and every sh:path evaluation, for every shape and focus
  // node, share one time and step budget (rows are bounded per SELECT).
  sparql::Limits sparql_limits;
  // The budget to charge instead (nullptr: one of sparql_limits for this
  // call), when a command validates more than once.
  sparql::Budget* sparql_budget = nullptr;
};

// Validates `data` (every graph of it, as one graph) against every shape with
// targets. `data` may be shapes.graph() itself. Returns a sorted report.
//
// Recursion: a shape that reaches itself for the same focus node (through
// sh:node, sh:property, sh:and, ...) throws mospec::Error "shacl-recursion"
// naming the shape cycle and the focus node.
//
// Work: SPARQL constraints and paths that together exceed the budget throw mospec::Error
// "sparql-limit", located at the constraint (or the shape) and naming it and the focus node.
Report validate(const Shapes& shapes, const rdf::Dataset& data,
                const ValidateOptions& options = {});

// For each shape (indexed as shapes.shapes()): how many focus nodes its
// targets select in `data` (0 for shapes without targets). Deactivated shapes
// are counted too. `mospec validate --strict` reports shapes with targets that
// select nothing.
std::vector<size_t> count_focus_nodes(const Shapes& shapes, const rdf::Dataset& data);

}  // namespace mospec::shacl
