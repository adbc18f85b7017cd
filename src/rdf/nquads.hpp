// N-Triples / N-Quads reading and writing with exact escaping (RDF 1.1).
//
// Writing is canonical in the sense of RDF 1.1 canonical N-Triples, with two
// choices made explicit:
//  - In literals, '"', '\\', LF and CR are written as \" \\ \n \r; every other
//    control character (U+0000..U+001F, U+007F) as \uXXXX with upper-case hex,
//    so a written line never holds a raw control character. Everything else,
//    including non-ASCII text, is written as is. IRIs and blank-node labels are
//    written as is.
//  - Literals with datatype xsd:string are written without a datatype,
//    rdf:langString literals as "lex"@lang, and rdf:dirLangString literals (a
//    base direction, which RDF 1.1 cannot express) in RDF 1.2 syntax as
//    "lex"@lang--ltr / "lex"@lang--rtl. The reader accepts that syntax too.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>

#include "rdf/dataset.hpp"
#include "support/diagnostics.hpp"

namespace mospec::rdf {

// Parses N-Quads (N-Triples is a subset). Blank-node labels get a prefix unique
// to this call, so two documents read into one dataset never share a blank
// node. Throws mospec::Error (code "syntax") naming file:line:col on bad input.
// `file` is used for messages and for the locations recorded with each quad.
// Each quad is located at its subject. On error, quads of the lines before the
// bad one have already been added.
void read_nquads(std::string_view text, Dataset& into, uint32_t file_id = 0,
                 std::string_view file_name = "<input>");

struct NQuadsOptions {
  // Generalized RDF (as JSON-LD's produceGeneralizedRdf emits and its test
  // suite expects): subjects and predicates may be any IRI, blank node or
  // literal. Off, the RDF 1.1 grammar applies.
  bool generalized = false;
};
void read_nquads(std::string_view text, Dataset& into, const NQuadsOptions& options,
                 uint32_t file_id = 0, std::string_view file_name = "<input>");

enum class Format { NQuads, NTriples };
// Writes every quad, one per line, lines sorted bytewise (deterministic output).
// With NTriples the graph component is dropped (callers pass a flattened
// union; lines that become equal are written once).
void write_nquads(const Dataset& data, std::ostream& out, Format format = Format::NQuads);
std::string to_nquads(const Dataset& data, Format format = Format::NQuads);

}  // namespace mospec::rdf
