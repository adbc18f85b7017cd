// The SPARQL syntax tree produced by the parser (stage 1 of 3): the query as
// written, with prefixed names and relative IRIs already resolved and every
// node carrying its 1-based position in the query text. Syntactic sugar is
// kept (property lists, blank-node property lists, collections, paths); the
// algebra builder expands it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sparql/query.hpp"

namespace mospec::sparql::ast {

struct Pos {
  uint32_t line = 0, column = 0;
};

// A term in a pattern or an expression.
struct Term {
  enum class Kind : uint8_t { Var, Iri, Blank, Literal, Nil };
  Kind kind = Kind::Iri;
  std::string value;     // var name, IRI, blank label ("" for [] / generated), lexical form
  std::string datatype;  // literals: datatype IRI ("" = xsd:string or rdf:langString)
  std::string language;  // literals: language tag
  Pos pos;
};

struct Path {
  enum class Kind : uint8_t {
    Var,  // a variable as the verb (only at the top of a triple)
    Iri,
    Inverse,
    Sequence,
    Alternative,
    ZeroOrMore,
    OneOrMore,
    ZeroOrOne,
    Negated,  // items are Iri or Inverse(Iri)
  };
  Kind kind = Kind::Iri;
  std::string value;  // Var name / IRI
  std::vector<Path> items;
  Pos pos;
};

struct Node;  // a subject or object: a term, [ ... ] or ( ... )
struct PropertyObjects {
  Path verb;
  std::vector<Node> objects;
};
struct Node {
  enum class Kind : uint8_t { Term, BlankPropertyList, Collection };
  Kind kind = Kind::Term;
  Term term;
  std::vector<PropertyObjects> properties;  // BlankPropertyList
  std::vector<Node> members;                // Collection
  Pos pos;
};
// One TriplesSameSubjectPath: subject followed by its property list.
struct Triples {
  Node subject;
  std::vector<PropertyObjects> properties;
};

struct Group;

struct Expr {
  enum class Kind : uint8_t {
    Term,  // term (Var, Iri, Literal)
    Or,    // args[0] || args[1]
    And,
    Not,      // !args[0]
    Compare,  // name is "=", "!=", "<", ">", "<=", ">="
    In,       // args[0] IN (args[1..])
    NotIn,
    Arith,   // name is "+", "-", "*", "/"
    Negate,  // -args[0]
    Plus,    // +args[0]
    Call,    // built-in function `name` (upper case) or function IRI (is_iri)
    Exists,  // pattern
    NotExists,
    Aggregate,  // name (upper case) over args[0]; only GROUP_CONCAT is parsed
  };
  Kind kind = Kind::Term;
  Term term;
  std::string name;
  bool is_iri = false;
  std::vector<Expr> args;
  std::shared_ptr<Group> pattern;  // Exists / NotExists
  bool distinct = false;           // Aggregate: over distinct values
  std::string separator = " ";     // Aggregate GROUP_CONCAT (18.5.1.7: a space by default)
  Pos pos;
};

struct Query;

struct Element {
  enum class Kind : uint8_t { Triples, Group, Union, Optional, Filter, Bind, SubSelect };
  Kind kind = Kind::Triples;
  std::vector<Triples> triples;  // Triples (one TriplesBlock)
  std::vector<Group> groups;     // Group: 1, Union: 2+, Optional: 1
  Expr expr;                     // Filter / Bind
  Term var;                      // Bind target
  std::shared_ptr<Query> sub;    // SubSelect: the nested SELECT
  Pos pos;
};

struct Group {
  std::vector<Element> elements;
  Pos pos;  // of '{'
};

struct Projection {
  Term var;
  bool has_expr = false;
  Expr expr;
};

struct OrderKey {
  Expr expr;
  bool descending = false;
};

struct Query {
  QueryForm form = QueryForm::Select;
  bool distinct = false;  // DISTINCT or REDUCED
  bool star = false;
  std::vector<Projection> projection;
  Group where;
  std::vector<Term> group_by;  // GROUP BY variables
  Pos group_pos;               // of GROUP, when there is one
  std::vector<OrderKey> order;
  int64_t limit = -1;
  int64_t offset = 0;
  std::string base;  // for IRI() at evaluation
};

// Parses the text (stage 1). Throws QueryError "sparql-syntax" or
// "unsupported-sparql".
Query parse(std::string_view text, const PrefixMap& prefixes, std::string_view base_iri);

// "line L, column C: " + message, as a QueryError.
[[noreturn]] void fail(std::string_view code, Pos pos, const std::string& message);

}  // namespace mospec::sparql::ast
