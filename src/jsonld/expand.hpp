// JSON-LD 1.1 Expansion (JSON-LD 1.1 Processing Algorithms and API, section 5.1),
// including context processing (section 4.1) and IRI expansion (section 4.2).
#pragma once

#include "jsonld/json.hpp"
#include "jsonld/options.hpp"

namespace mospec::jsonld {

// The expand() API method: expands `input` (already parsed) using `options`
// (expand_context applied first, then the document's own contexts). The result is
// always an array (the spec's final step). Output values keep the source location
// of the JSON value they came from; node objects carry the location of their
// "@id" (or of the object when there is none).
// Throws mospec::Error whose code() is the spec's error code, e.g.
// "invalid context entry", located where possible.
json::Value expand(const json::Value& input, const Options& options);

}  // namespace mospec::jsonld
