// SPARQL 1.1 SELECT/ASK over an rdf::Dataset: the public API.
//
// Three stages, each in its own file:
//   parser.cpp    text -> AST with 1-based line:column positions (ast.hpp)
//   algebra.cpp   AST -> SPARQL algebra per SPARQL 1.1 section 18.2 (algebra.hpp)
//   evaluate.cpp  algebra -> solutions over a dataset (Evaluator below)
//
// A Query is parsed once and is immutable afterwards (share it freely, also
// across threads). An Evaluator is the per-dataset workspace: it resolves the
// query's constants against the dataset once per query, owns the side tables
// for terms computed by expressions, and keeps its buffers between calls, so
// evaluating the same query for thousands of focus nodes does not allocate in
// the steady state. One Evaluator per thread.
//
// Supported: PREFIX/BASE; SELECT (DISTINCT|REDUCED)? with variables,
// (expr AS ?v) or *; ASK; basic graph patterns with ; , a [] [ ... ] ( ... );
// every literal form; property paths (/ | ^ * + ? ! and groups); OPTIONAL,
// UNION, nested groups, FILTER (placed per 18.2.2.6), BIND; the operators
// = != < > <= >= && || ! + - * / IN, NOT IN, EXISTS, NOT EXISTS; the functions
// BOUND IF COALESCE ABS CEIL FLOOR ROUND isIRI isURI isBlank isLiteral
// isNumeric STR LANG DATATYPE IRI URI REGEX STRSTARTS STRENDS CONTAINS STRLEN
// UCASE LCASE (ASCII case mapping) CONCAT LANGMATCHES sameTerm and the XSD
// casts xsd:string/integer/decimal/double/float/boolean; ORDER BY, LIMIT,
// OFFSET; sub-SELECTs (with their own modifiers, evaluated bottom-up and
// joined with the enclosing group); GROUP BY variables and the aggregate
// GROUP_CONCAT (DISTINCT, SEPARATOR) as a whole SELECT expression, its strings
// sorted by code point (SPARQL leaves the order open).
// Everything else (MINUS, VALUES, SERVICE, GRAPH, FROM, other aggregates,
// GROUP BY expressions, HAVING, CONSTRUCT, DESCRIBE, updates, unknown functions) is rejected
// with a QueryError of code "unsupported-sparql" naming the construct and its
// position; syntax errors have code "sparql-syntax". Messages start with
// "line L, column C: " (positions inside the query text; columns count bytes).
//
// Default graph: the union of all graphs of the dataset (as a set of triples).
//
// Bounded work: the parser refuses queries nested deeper than 256 levels
// (sparql-syntax), and each evaluation runs under a Budget (a time budget and
// a step count, shared by every evaluation of a command, and a row count per
// SELECT; limits.hpp): past one it throws mospec::Error "sparql-limit".
//
// Deviations from the specification, on purpose:
//  - xsd:integer arithmetic is 64-bit; an overflow is an expression error.
//    xsd:decimal is computed in long double (not arbitrary precision).
//  - A dateTime without a timezone is compared as if it were UTC.
//  - '=' and '!=' between literals of two different known types (numeric,
//    string, language-tagged string, boolean, dateTime) are false/true rather
//    than a type error; only literals of unknown datatypes (or ill-typed ones)
//    raise the type error of RDFterm-equal. Language tags compare
//    case-insensitively.
//  - REGEX runs in RE2 (linear time) after translating XPath syntax and the
//    flags s, m, i, x, q (regex.hpp, shared with SHACL's sh:pattern). What RE2
//    cannot express (class subtraction, \p{Is..} blocks, back-references) is
//    rejected when the pattern is a constant (unsupported-sparql, or
//    sparql-syntax for an invalid pattern or flag) and an expression error
//    when it is computed.
//  - Property-path patterns other than sequences of plain/inverse IRIs yield
//    distinct bindings (alternatives do not duplicate a node reached twice).
#pragma once

#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rdf/dataset.hpp"
#include "sparql/limits.hpp"
#include "support/diagnostics.hpp"

namespace mospec::sparql {

namespace detail {
struct Plan;
class Engine;
}  // namespace detail

// prefix (without ':') -> namespace IRI. Extra prefixes given by the caller,
// e.g. from sh:prefixes; PREFIX declarations in the query text override them.
using PrefixMap = std::map<std::string, std::string, std::less<>>;

// A query error with its position inside the query text (line() == 0 when not
// tied to a position). The message already starts with "line L, column C: ".
class QueryError : public Error {
 public:
  QueryError(std::string code, uint32_t line, uint32_t column, const std::string& message);
  uint32_t line() const { return line_; }
  uint32_t column() const { return column_; }

 private:
  uint32_t line_, column_;
};

enum class QueryForm : uint8_t { Select, Ask };

class Query {
 public:
  QueryForm form() const;
  // The result variables in projection order (names without '?' or '$').
  // For SELECT * these are the visible in-scope variables in order of first
  // appearance.
  const std::vector<std::string>& variables() const;
  // True when the query text mentions the variable (anywhere).
  bool mentions(std::string_view name) const;
  // The translated algebra as an S-expression (group steps in evaluation
  // order, filters where they were placed), e.g.
  //   (select (?x) (group (join (bgp (?x <p> ?y) (filter (> ?y 1))))))
  std::string algebra() const;

  // Rejects (unsupported-sparql, with position) queries that SHACL's pre-binding
  // (SHACL 1.0 appendix "Pre-binding of Variables") cannot handle for the given
  // potentially pre-bound variables: `AS ?var` for one of them, or a sub-SELECT
  // that does not return one the query uses. MINUS, SERVICE and VALUES are
  // rejected by the parser for every query.
  void check_prebinding(std::span<const std::string_view> names) const;

  const detail::Plan& plan() const { return *plan_; }
  const std::shared_ptr<const detail::Plan>& shared_plan() const { return plan_; }
  explicit Query(std::shared_ptr<const detail::Plan> plan) : plan_(std::move(plan)) {}

 private:
  std::shared_ptr<const detail::Plan> plan_;
};

// Parses and translates a query. `base_iri` resolves relative IRIs when the
// query has no BASE (empty: relative IRIs are kept as written).
Query parse_query(std::string_view text, const PrefixMap& prefixes = {},
                  std::string_view base_iri = {});

// An initial binding ("pre-bound variable", e.g. this = the focus node). The
// value is a term id of the evaluator's dataset or one made by
// Evaluator::import.
struct Binding {
  std::string_view name;  // without '?' / '$'
  rdf::TermId value;
};

inline constexpr rdf::TermId kUnbound = rdf::TermId::any();

// Solutions as rows of term ids, one column per variable, kUnbound where a
// variable is unbound. Ids are data ids or evaluator-made ids (see Evaluator).
struct ResultSet {
  std::vector<std::string> variables;
  std::vector<rdf::TermId> cells;  // row-major, variables.size() per row
  size_t rows = 0;                 // kept apart: a row may have no columns

  size_t size() const { return rows; }
  std::span<const rdf::TermId> row(size_t i) const {
    return {cells.data() + i * variables.size(), variables.size()};
  }
  rdf::TermId at(size_t row, size_t column) const { return cells[row * variables.size() + column]; }
  // Column of a variable, or -1.
  int column(std::string_view name) const;
  void clear() {
    variables.clear();
    cells.clear();
    rows = 0;
  }
};

// Not thread-safe (one per thread). The dataset must not change while an
// evaluator uses it. Each query it evaluates stays alive in its cache of
// prepared queries (constants resolved, match counts for join ordering) until
// the evaluator is destroyed.
class Evaluator {
 public:
  explicit Evaluator(const rdf::Dataset& data);
  ~Evaluator();
  Evaluator(const Evaluator&) = delete;
  Evaluator& operator=(const Evaluator&) = delete;
  Evaluator(Evaluator&&) noexcept;
  Evaluator& operator=(Evaluator&&) noexcept;

  // Evaluates a SELECT query (an ASK query yields zero or one empty row).
  // Pre-bound variables follow SHACL's definition: every basic graph pattern
  // and property path of the query is joined with them, so they hold in every
  // sub-pattern (also inside EXISTS, OPTIONAL and UNION). A pre-bound variable
  // the query assigns with AS is rejected (check_prebinding). `out` is
  // overwritten.
  void select(const Query& query, std::span<const Binding> prebound, ResultSet& out);
  bool ask(const Query& query, std::span<const Binding> prebound = {});

  // Term ids: below kComputedBase they are ids of the dataset's TermTable.
  // Terms the dataset lacks (query constants, values computed by expressions,
  // imported terms) get ids from kComputedBase up. Every term has exactly one
  // id, so ids compare like terms. Computed ids stay valid until the next
  // select()/ask() call of this evaluator; imported and constant ids stay valid
  // for its lifetime.
  static constexpr uint32_t kComputedBase = 0x80000000u;
  // The term's table and its id there (for printing or importing elsewhere).
  std::pair<const rdf::TermTable*, rdf::TermId> locate(rdf::TermId id) const;
  const rdf::Term& term(rdf::TermId id) const;
  std::string to_ntriples(rdf::TermId id) const;
  // The id of a term of another table (e.g. the shapes graph) for pre-binding.
  rdf::TermId import(const rdf::TermTable& table, rdf::TermId id);

  const rdf::Dataset& data() const;

  // Bounds on each select()/ask() call (limits.hpp): past one, the call throws
  // mospec::Error with code "sparql-limit". Defaults: Limits{}.
  void set_limits(const Limits& limits);
  const Limits& limits() const;
  // Charges every later select()/ask() call to `budget` (which must outlive
  // them; nullptr: each call gets its own Budget of limits()), so that one
  // budget bounds all evaluations of a command. Its row limit still applies
  // to each SELECT on its own.
  void set_budget(Budget* budget);

 private:
  std::unique_ptr<detail::Engine> engine_;
};

}  // namespace mospec::sparql
