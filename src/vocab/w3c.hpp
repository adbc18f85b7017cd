// IRIs of the W3C vocabularies mospec reads or writes: RDF, RDFS, XSD, OWL,
// SHACL and the i18n datatypes of JSON-LD 1.1. The one place they are spelled
// (the ctest `vocab_home` fails when a namespace IRI appears elsewhere in src/).
//
// Each vocabulary is a namespace: `ns` is its namespace IRI, every other
// constant a full term IRI named by its local name (C++ keywords get a
// trailing underscore: sh::class_, sh::and_ ...). The MOSPEC_VOCAB_* macros are
// the namespace IRIs as string literals, for tables that concatenate them.
#pragma once

#include <string_view>

#define MOSPEC_VOCAB_RDF "http://www.w3.org/1999/02/22-rdf-syntax-ns#"
#define MOSPEC_VOCAB_RDFS "http://www.w3.org/2000/01/rdf-schema#"
#define MOSPEC_VOCAB_XSD "http://www.w3.org/2001/XMLSchema#"
#define MOSPEC_VOCAB_OWL "http://www.w3.org/2002/07/owl#"
#define MOSPEC_VOCAB_SH "http://www.w3.org/ns/shacl#"
#define MOSPEC_VOCAB_I18N "https://www.w3.org/ns/i18n#"

namespace mospec::vocab {

namespace rdf {
inline constexpr std::string_view ns = MOSPEC_VOCAB_RDF;
inline constexpr std::string_view type = MOSPEC_VOCAB_RDF "type";
inline constexpr std::string_view first = MOSPEC_VOCAB_RDF "first";
inline constexpr std::string_view rest = MOSPEC_VOCAB_RDF "rest";
inline constexpr std::string_view nil = MOSPEC_VOCAB_RDF "nil";
inline constexpr std::string_view langString = MOSPEC_VOCAB_RDF "langString";
inline constexpr std::string_view dirLangString = MOSPEC_VOCAB_RDF "dirLangString";
inline constexpr std::string_view JSON = MOSPEC_VOCAB_RDF "JSON";
}  // namespace rdf

namespace rdfs {
inline constexpr std::string_view ns = MOSPEC_VOCAB_RDFS;
inline constexpr std::string_view Class = MOSPEC_VOCAB_RDFS "Class";
inline constexpr std::string_view subClassOf = MOSPEC_VOCAB_RDFS "subClassOf";
}  // namespace rdfs

namespace xsd {
inline constexpr std::string_view ns = MOSPEC_VOCAB_XSD;
inline constexpr std::string_view string = MOSPEC_VOCAB_XSD "string";
inline constexpr std::string_view boolean = MOSPEC_VOCAB_XSD "boolean";
inline constexpr std::string_view integer = MOSPEC_VOCAB_XSD "integer";
inline constexpr std::string_view decimal = MOSPEC_VOCAB_XSD "decimal";
inline constexpr std::string_view float_ = MOSPEC_VOCAB_XSD "float";
inline constexpr std::string_view double_ = MOSPEC_VOCAB_XSD "double";
}  // namespace xsd

namespace owl {
inline constexpr std::string_view ns = MOSPEC_VOCAB_OWL;
inline constexpr std::string_view imports = MOSPEC_VOCAB_OWL "imports";
}  // namespace owl

namespace i18n {
inline constexpr std::string_view ns = MOSPEC_VOCAB_I18N;
}  // namespace i18n

// SHACL (what the validator reads and what its reports write).
namespace sh {
#define MOSPEC_SH(name) inline constexpr std::string_view name = MOSPEC_VOCAB_SH #name
#define MOSPEC_SH_KW(name) inline constexpr std::string_view name##_ = MOSPEC_VOCAB_SH #name

inline constexpr std::string_view ns = MOSPEC_VOCAB_SH;

MOSPEC_SH(NodeShape);
MOSPEC_SH(PropertyShape);
MOSPEC_SH(ValidationReport);
MOSPEC_SH(ValidationResult);
MOSPEC_SH(conforms);
MOSPEC_SH(result);
MOSPEC_SH(focusNode);
MOSPEC_SH(resultPath);
MOSPEC_SH(value);
MOSPEC_SH(sourceShape);
MOSPEC_SH(sourceConstraint);
MOSPEC_SH(sourceConstraintComponent);
MOSPEC_SH(resultSeverity);
MOSPEC_SH(resultMessage);
MOSPEC_SH(Violation);
MOSPEC_SH(Warning);
MOSPEC_SH(Info);

MOSPEC_SH(targetNode);
MOSPEC_SH(targetClass);
MOSPEC_SH(targetSubjectsOf);
MOSPEC_SH(targetObjectsOf);
MOSPEC_SH(path);
MOSPEC_SH(alternativePath);
MOSPEC_SH(inversePath);
MOSPEC_SH(zeroOrMorePath);
MOSPEC_SH(oneOrMorePath);
MOSPEC_SH(zeroOrOnePath);
MOSPEC_SH(deactivated);
MOSPEC_SH(severity);
MOSPEC_SH(message);

MOSPEC_SH(BlankNode);
MOSPEC_SH(IRI);
MOSPEC_SH(Literal);
MOSPEC_SH(BlankNodeOrIRI);
MOSPEC_SH(BlankNodeOrLiteral);
MOSPEC_SH(IRIOrLiteral);

// Constraint parameters.
MOSPEC_SH_KW(class);
MOSPEC_SH(datatype);
MOSPEC_SH(nodeKind);
MOSPEC_SH(minCount);
MOSPEC_SH(maxCount);
MOSPEC_SH(minExclusive);
MOSPEC_SH(minInclusive);
MOSPEC_SH(maxExclusive);
MOSPEC_SH(maxInclusive);
MOSPEC_SH(minLength);
MOSPEC_SH(maxLength);
MOSPEC_SH(pattern);
MOSPEC_SH(flags);
MOSPEC_SH(languageIn);
MOSPEC_SH(uniqueLang);
MOSPEC_SH(equals);
MOSPEC_SH(disjoint);
MOSPEC_SH(lessThan);
MOSPEC_SH(lessThanOrEquals);
MOSPEC_SH_KW(not );
MOSPEC_SH_KW(and);
MOSPEC_SH_KW(or);
MOSPEC_SH(xone);
MOSPEC_SH(node);
MOSPEC_SH(property);
MOSPEC_SH(qualifiedValueShape);
MOSPEC_SH(qualifiedMinCount);
MOSPEC_SH(qualifiedMaxCount);
MOSPEC_SH(qualifiedValueShapesDisjoint);
MOSPEC_SH(closed);
MOSPEC_SH(ignoredProperties);
MOSPEC_SH(hasValue);
MOSPEC_SH_KW(in);
MOSPEC_SH(sparql);
MOSPEC_SH(select);
MOSPEC_SH(prefixes);
MOSPEC_SH(declare);
MOSPEC_SH(prefix);
MOSPEC_SH(SPARQLConstraint);
MOSPEC_SH_KW(namespace);

// SPARQL-based constraint components (SHACL 6).
MOSPEC_SH(ConstraintComponent);
MOSPEC_SH(parameter);
MOSPEC_SH(optional);
MOSPEC_SH(validator);
MOSPEC_SH(nodeValidator);
MOSPEC_SH(propertyValidator);
MOSPEC_SH(ask);
MOSPEC_SH(labelTemplate);

// Non-validating properties (SHACL 2.3.2) and annotations mospec accepts and
// does not need.
MOSPEC_SH(name);
MOSPEC_SH(description);
MOSPEC_SH(order);
MOSPEC_SH(group);
MOSPEC_SH(defaultValue);

#undef MOSPEC_SH_KW
#undef MOSPEC_SH
}  // namespace sh

}  // namespace mospec::vocab
