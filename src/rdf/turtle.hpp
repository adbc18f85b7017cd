// Turtle and TriG reading through serd.
//
// Locations: serd 0.30 reports no position with a statement, so each quad is
// located where serd's read cursor was when it delivered the statement: just
// past the statement's object (the line is exact for single-line statements
// and names the object's line otherwise). Errors carry serd's own cursor.
//
// Known serd 0.30 limitation: in Turtle, serd renames labels of the form
// _:b<digit>... to _:B<digit>... (its own anonymous nodes are b1, b2, ...) and
// rejects a document that also uses a _:B<digit>... label ("found both `b' and
// `B' blank IDs"). Such documents are valid Turtle but are reported as errors.
#pragma once

#include <string_view>

#include "rdf/dataset.hpp"

namespace mospec::rdf {

// Reads Turtle (or TriG) text. `base_iri` resolves relative IRIs (RFC 3986, see
// resolve_iri); @base / BASE directives change it as they appear. A relative
// IRI with no base to resolve it against is an error. Blank nodes get a prefix
// fresh to this document. Syntax errors throw mospec::Error (code "syntax")
// with file:line:col; quads read before the error stay in `into`. serd reads
// nested blank nodes `[ ... ]` and collections `( ... )` by recursion, so a
// document nesting them deeper than 512 levels is refused (code "syntax", located
// at the bracket that goes too deep) before serd reads any of it.
void read_turtle(std::string_view text, std::string_view base_iri, Dataset& into,
                 uint32_t file_id = 0, std::string_view file_name = "<input>");
void read_trig(std::string_view text, std::string_view base_iri, Dataset& into,
               uint32_t file_id = 0, std::string_view file_name = "<input>");

}  // namespace mospec::rdf
