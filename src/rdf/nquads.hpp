// N-Triples / N-Quads reading and writing with exact escaping (RDF 1.1).
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
void read_nquads(std::string_view text, Dataset& into, uint32_t file_id = 0,
                 std::string_view file_name = "<input>");

enum class Format { NQuads, NTriples };
// Writes every quad, one per line, lines sorted (deterministic output).
// With NTriples the graph component is dropped (callers pass a flattened union).
void write_nquads(const Dataset& data, std::ostream& out, Format format = Format::NQuads);
std::string to_nquads(const Dataset& data, Format format = Format::NQuads);

}  // namespace mospec::rdf
