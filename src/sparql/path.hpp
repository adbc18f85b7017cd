// Property paths (SPARQL 1.1 section 9), shared by the SPARQL engine and by
// SHACL's sh:path: one representation, one evaluator.
#pragma once

#include <memory>
#include <vector>

#include "rdf/dataset.hpp"
#include "sparql/limits.hpp"

namespace mospec::sparql {

struct Path;
using PathPtr = std::shared_ptr<const Path>;

struct Path {
  enum class Kind : uint8_t {
    Predicate,    // iri
    Inverse,      // ^items[0]
    Sequence,     // items[0] / items[1] / ...
    Alternative,  // items[0] | items[1] | ...
    ZeroOrMore,   // items[0]*
    OneOrMore,    // items[0]+
    ZeroOrOne,    // items[0]?
    NegatedSet,   // !(iri | ^iri ...): `predicate` unused; `negated` / `negated_inverse`
  };
  Kind kind = Kind::Predicate;
  rdf::TermId predicate;  // Kind::Predicate
  std::vector<PathPtr> items;
  std::vector<rdf::TermId> negated, negated_inverse;  // Kind::NegatedSet

  static PathPtr iri(rdf::TermId p);
  static PathPtr make(Kind k, std::vector<PathPtr> items);
};

// The buffers path evaluation reuses: visited sets (stamp arrays indexed by
// term id) and node lists. A caller evaluating many paths (an evaluator, a
// validator) owns one and passes it to every call, so that a call allocates
// nothing once it has warmed up. One per evaluating object; not thread-safe.
class PathWorkspace {
 public:
  PathWorkspace();
  ~PathWorkspace();
  PathWorkspace(const PathWorkspace&) = delete;
  PathWorkspace& operator=(const PathWorkspace&) = delete;

  struct Buffers;  // path.cpp
  Buffers& buffers() { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

// Every node reachable from `start` along `path` in `graph` (TermId::any() = the
// union of all graphs). Results are distinct, in first-reached order
// (deterministic). Zero-length paths include `start` itself, as SPARQL and SHACL
// define it. `out` is cleared first.
//
// Work is counted against `budget` (one step per triple followed and per node
// reached; nested `*` paths can take quadratic time in the data); without
// one, the call gets its own Budget with the default Limits. Past a limit the
// call throws mospec::Error "sparql-limit" (limits.hpp). Buffers come from
// `workspace`; without one, the call makes its own.
void evaluate_path(const rdf::Dataset& data, const Path& path, rdf::TermId start,
                   std::vector<rdf::TermId>& out, rdf::TermId graph = rdf::TermId::any(),
                   Budget* budget = nullptr, PathWorkspace* workspace = nullptr);

// Every node from which `end` is reachable along `path` (the inverse direction).
void evaluate_path_inverse(const rdf::Dataset& data, const Path& path, rdf::TermId end,
                           std::vector<rdf::TermId>& out, rdf::TermId graph = rdf::TermId::any(),
                           Budget* budget = nullptr, PathWorkspace* workspace = nullptr);

}  // namespace mospec::sparql
