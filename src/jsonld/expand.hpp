// JSON-LD 1.1 Expansion (JSON-LD 1.1 Processing Algorithms and API, section 5.1),
// including context processing (section 4.1) and IRI expansion (section 4.2).
#pragma once

#include "json/json.hpp"
#include "jsonld/options.hpp"

namespace mospec::jsonld {

// The expand() API method: expands `input` (already parsed) using `options`
// (expand_context applied first, then the document's own contexts). The result is
// always an array (the spec's final step). Output values keep the source location
// of the JSON value they came from: a node object carries the location of the
// input object, its "@id" string that of the input @id string, and output keys
// (json::Object::key_location) that of the input key.
// Throws mospec::Error whose code() is the spec's error code, e.g.
// "invalid context entry", located where possible.
// With options.diagnostics set, what JSON-LD drops or reinterprets silently is
// reported as warnings (never changing the result): "dropped-key" (a key that
// expands to no IRI), "undefined-type" (an @type value that is no term, compact
// or absolute IRI and is resolved against the base) and "dropped-id" (an @id
// that expands to nothing).
// The result's strings, arrays and objects live in `output` (the heap by
// default): an arena the caller keeps until the result is gone makes the
// expanded tree one bump per value to build and free to drop.
json::Value expand(const json::Value& input, const Options& options,
                   json::Resource* output = std::pmr::get_default_resource());

}  // namespace mospec::jsonld
