// Turtle and TriG reading through serd.
#pragma once

#include <string_view>

#include "rdf/dataset.hpp"

namespace mospec::rdf {

// Reads Turtle (or TriG) text. `base_iri` resolves relative IRIs. Blank nodes get
// a prefix fresh to this document. Syntax errors throw mospec::Error (code
// "syntax") with file:line:col.
void read_turtle(std::string_view text, std::string_view base_iri, Dataset& into,
                 uint32_t file_id = 0, std::string_view file_name = "<input>");
void read_trig(std::string_view text, std::string_view base_iri, Dataset& into,
               uint32_t file_id = 0, std::string_view file_name = "<input>");

}  // namespace mospec::rdf
