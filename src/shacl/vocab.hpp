// IRIs of the SHACL, RDF, RDFS and XSD terms the validator reads or writes.
#pragma once

#include <string_view>

namespace mospec::shacl::vocab {

#define MOSPEC_SH(name) inline constexpr std::string_view name = "http://www.w3.org/ns/shacl#" #name

inline constexpr std::string_view kSh = "http://www.w3.org/ns/shacl#";
inline constexpr std::string_view kRdf = "http://www.w3.org/1999/02/22-rdf-syntax-ns#";
inline constexpr std::string_view kRdfs = "http://www.w3.org/2000/01/rdf-schema#";
inline constexpr std::string_view kXsd = "http://www.w3.org/2001/XMLSchema#";

inline constexpr std::string_view rdf_type = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type";
inline constexpr std::string_view rdf_first = "http://www.w3.org/1999/02/22-rdf-syntax-ns#first";
inline constexpr std::string_view rdf_rest = "http://www.w3.org/1999/02/22-rdf-syntax-ns#rest";
inline constexpr std::string_view rdf_nil = "http://www.w3.org/1999/02/22-rdf-syntax-ns#nil";
inline constexpr std::string_view rdfs_class = "http://www.w3.org/2000/01/rdf-schema#Class";
inline constexpr std::string_view rdfs_subclass_of =
    "http://www.w3.org/2000/01/rdf-schema#subClassOf";
inline constexpr std::string_view owl_imports = "http://www.w3.org/2002/07/owl#imports";
inline constexpr std::string_view xsd_boolean = "http://www.w3.org/2001/XMLSchema#boolean";
inline constexpr std::string_view xsd_integer = "http://www.w3.org/2001/XMLSchema#integer";

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

// Constraint parameters (C++ keywords get an sh_ prefix).
inline constexpr std::string_view sh_class = "http://www.w3.org/ns/shacl#class";
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
inline constexpr std::string_view sh_not = "http://www.w3.org/ns/shacl#not";
inline constexpr std::string_view sh_and = "http://www.w3.org/ns/shacl#and";
inline constexpr std::string_view sh_or = "http://www.w3.org/ns/shacl#or";
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
inline constexpr std::string_view sh_in = "http://www.w3.org/ns/shacl#in";
MOSPEC_SH(sparql);
MOSPEC_SH(select);
MOSPEC_SH(prefixes);
MOSPEC_SH(declare);
MOSPEC_SH(prefix);
MOSPEC_SH(SPARQLConstraint);
inline constexpr std::string_view sh_namespace = "http://www.w3.org/ns/shacl#namespace";

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

#undef MOSPEC_SH

}  // namespace mospec::shacl::vocab
