// JSON-LD 1.1 Deserialize JSON-LD to RDF (section 8.1, with Node Map Generation
// 7.2 and Object to RDF Conversion 8.1.2 / List to RDF 8.1.3).
#pragma once

#include <memory_resource>

#include "json/json.hpp"
#include "jsonld/options.hpp"
#include "rdf/dataset.hpp"

namespace mospec::jsonld {

// Adds the quads of an expanded document to `out`. Blank nodes get labels fresh in
// `out` (so two documents never share one). Each quad records the source location
// of the node object it came from (the place its "@id" is written).
// Honours options.produce_generalized_rdf and options.rdf_direction.
// The node map's tables are drawn from `scratch` (the heap by default); the
// loader passes the arena the expanded document is in, which it drops whole.
void to_rdf(const json::Value& expanded, rdf::Dataset& out, const Options& options,
            std::pmr::memory_resource* scratch = std::pmr::new_delete_resource());

// Convenience: expand + to_rdf.
void load_into(const json::Value& document, rdf::Dataset& out, const Options& options);

}  // namespace mospec::jsonld
