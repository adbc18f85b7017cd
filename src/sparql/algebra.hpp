// Stage 2: the SPARQL algebra of a query (SPARQL 1.1 section 18.2), as the
// evaluator consumes it. Built once per query by build_plan(); immutable.
//
// Variables are small integers (slots of a solution row). Constants are ids
// of the plan's own TermTable; the evaluator maps them to dataset ids once.
// Blank nodes of patterns and the intermediate nodes of sequence paths are
// hidden variables (never projected by SELECT *).
//
// A group graph pattern becomes one Group op: the left-deep chain of 18.2.2.6
// (Join / LeftJoin / Extend over the elements in order) with the group's
// filters attached as steps. The translation puts the conjunction of the
// filters on top of the chain; a filter is moved down to the earliest step
// after which every variable it mentions (also inside EXISTS) that the group
// can bind is certainly bound, which yields the same solutions sooner. Filters
// landing on a basic graph pattern are checked inside its join loop.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rdf/term.hpp"
#include "sparql/ast.hpp"
#include "sparql/path.hpp"
#include "sparql/regex.hpp"

namespace mospec::sparql::detail {

using Var = uint32_t;
inline constexpr uint32_t kNone = UINT32_MAX;

// A set of variables (a bitset sized to the query).
class VarSet {
 public:
  void insert(Var v) {
    if (v / 64 >= words_.size()) words_.resize(v / 64 + 1, 0);
    words_[v / 64] |= uint64_t{1} << (v % 64);
  }
  bool contains(Var v) const {
    return v / 64 < words_.size() && (words_[v / 64] >> (v % 64) & 1) != 0;
  }
  void insert_all(const VarSet& o) {
    if (o.words_.size() > words_.size()) words_.resize(o.words_.size(), 0);
    for (size_t i = 0; i < o.words_.size(); ++i) words_[i] |= o.words_[i];
  }
  void intersect(const VarSet& o) {
    for (size_t i = 0; i < words_.size(); ++i) words_[i] &= i < o.words_.size() ? o.words_[i] : 0;
  }
  bool subset_of(const VarSet& o) const {
    for (size_t i = 0; i < words_.size(); ++i)
      if ((words_[i] & ~(i < o.words_.size() ? o.words_[i] : 0)) != 0) return false;
    return true;
  }
  std::vector<Var> members() const {
    std::vector<Var> out;
    for (size_t i = 0; i < words_.size(); ++i)
      for (uint64_t w = words_[i]; w != 0; w &= w - 1)
        out.push_back(static_cast<Var>(i * 64 + static_cast<size_t>(__builtin_ctzll(w))));
    return out;
  }

 private:
  std::vector<uint64_t> words_;
};

// A position of a triple pattern: a variable or a constant (plan term id).
struct Slot {
  bool is_var = false;
  uint32_t value = 0;
};

struct PatternElem {
  Slot s, p, o;
  int32_t path = -1;  // >= 0: index into Plan::paths; p is unused
  ast::Pos pos;
};

enum class ExprOp : uint8_t {
  Const,  // value: plan term id
  Var,    // value: variable
  Or,
  And,
  Not,
  Eq,
  Ne,
  Lt,
  Gt,
  Le,
  Ge,
  In,
  NotIn,
  Add,
  Sub,
  Mul,
  Div,
  Neg,
  Plus,
  Exists,  // value: op index
  NotExists,
  Bound,  // args[0] is a Var expression
  If,
  Coalesce,
  Abs,
  Ceil,
  Floor,
  Round,
  IsIri,
  IsBlank,
  IsLiteral,
  IsNumeric,
  Str,
  Lang,
  Datatype,
  Iri,
  Regex,
  StrStarts,
  StrEnds,
  Contains,
  StrLen,
  Ucase,
  Lcase,
  Concat,
  LangMatches,
  SameTerm,
  CastString,
  CastInteger,
  CastDecimal,
  CastDouble,
  CastFloat,
  CastBoolean,
};

struct Expr {
  ExprOp op = ExprOp::Const;
  uint32_t value = 0;
  std::vector<uint32_t> args;  // indices into Plan::exprs
  int32_t regex = -1;          // Regex with constant pattern/flags: index into Plan::regexes
  ast::Pos pos;
};

enum class OpKind : uint8_t { Bgp, Group, Union, SubSelect };

struct Step {
  enum class Kind : uint8_t { Join, LeftJoin, Extend, Filter };
  Kind kind = Kind::Join;
  uint32_t child = kNone;  // Join / LeftJoin: op index
  uint32_t expr = kNone;   // LeftJoin condition (kNone: true), Extend value, Filter
  Var var = kNone;         // Extend
};

struct Op {
  OpKind kind = OpKind::Bgp;
  std::vector<PatternElem> elems;  // Bgp
  std::vector<uint32_t> filters;   // Bgp: filters to check inside the join loop
  std::vector<Step> steps;         // Group
  std::vector<uint32_t> children;  // Union
  uint32_t select = kNone;         // SubSelect: index into Plan::selects
  VarSet certain;                  // bound in every solution of the op
  VarSet mentioned;                // occur anywhere in the op (also in filters/EXISTS)
  // mentioned minus certain: bindings of these coming from outside must be
  // hidden while the op runs (the op is evaluated as a join, see evaluate.cpp).
  std::vector<Var> hide;
  std::vector<Var> vars;  // Bgp: the variables of its patterns
};

struct OrderKey {
  uint32_t expr;
  bool descending;
};

// GROUP BY and aggregates (18.2.4.1, 18.5): the solutions are grouped by
// the values of `keys` (all in one group when there are none); the group's one
// solution binds the keys and each aggregate's variable. Only GROUP_CONCAT, as
// a whole SELECT expression, is supported (evaluate.cpp says how it orders).
struct Aggregate {
  Var var = kNone;        // the (... AS ?var) it is bound to
  uint32_t expr = kNone;  // its argument
  bool distinct = false;
  std::string separator;
};
struct Grouping {
  bool active = false;  // GROUP BY or an aggregate
  std::vector<Var> keys;
  std::vector<Aggregate> aggregates;
};

// A nested SELECT (18.2.1: evaluated on its own, bottom-up; its solutions are
// then joined with the enclosing group). Its variables are slots of their
// own, hidden, except that pre-binding pins them by name like the outer ones.
struct Select {
  uint32_t root = kNone;
  std::vector<Var> result_vars;                           // inner slots, by column
  std::vector<Var> outer_vars;                            // the enclosing query's, by column
  std::vector<std::pair<Var, uint32_t>> projected_exprs;  // (inner var, expr)
  Grouping grouping;
  bool distinct = false;
  std::vector<OrderKey> order;
  int64_t limit = -1, offset = 0;
};

struct Plan {
  QueryForm form = QueryForm::Select;
  rdf::TermTable terms;                // constants of the query
  std::vector<std::string> var_names;  // by Var; hidden ones start with '_'
  std::vector<bool> hidden;
  std::vector<Op> ops;
  std::vector<Expr> exprs;
  std::vector<std::vector<Var>> expr_vars;  // by expr: every variable it mentions
  std::vector<PathPtr> paths;               // plan term ids
  std::vector<Regex> regexes;               // constant REGEX patterns, compiled once
  std::vector<Select> selects;              // sub-SELECTs, by SubSelect op
  uint32_t root = 0;

  std::vector<std::string> result_names;
  std::vector<Var> result_vars;                           // by column
  std::vector<std::pair<Var, uint32_t>> projected_exprs;  // (var, expr) computed after WHERE
  Grouping grouping;                                      // applied before projected_exprs
  bool distinct = false;
  std::vector<OrderKey> order;
  int64_t limit = -1, offset = 0;
  std::string base;

  // Variables assigned with AS (BIND or SELECT expressions), with positions,
  // for the pre-binding check.
  std::vector<std::pair<Var, ast::Pos>> assigned;
  // The names each sub-SELECT projects, with the position of its SELECT:
  // SHACL's pre-binding wants every pre-bound variable the query uses among them.
  std::vector<std::pair<std::vector<std::string>, ast::Pos>> subselect_names;

  Var find_var(std::string_view name) const {
    for (Var v = 0; v < var_names.size(); ++v)
      if (var_names[v] == name && !hidden[v]) return v;
    return kNone;
  }
  // Whether any slot has this name (also a sub-SELECT's own).
  bool names(std::string_view name) const {
    for (const std::string& n : var_names)
      if (n == name) return true;
    return false;
  }
};

// Stage 2 entry: translates the syntax tree. Throws QueryError for semantic
// errors (BIND of an in-scope variable, unknown functions, bad arity, bad
// constant regular expressions).
std::shared_ptr<Plan> build_plan(ast::Query&& query);

// The algebra as an S-expression, for tests and debugging (see Query::algebra).
std::string to_sse(const Plan& plan);

}  // namespace mospec::sparql::detail
