// RDF graph -> the mobile base's configuration: a CastorDriveBase of mospec's
// mobile-base vocabulary (metamodels/mospec/mobile-base.json; shapes in
// mobile-base.ttl) read into the runtime's KeloConfig (geometry and the
// weights of Eq. 2-3). Lowering reads a platform solver's `configuration`
// with read_base(); the simulator's base is built from the same reading
// (load_base() for a file, or the program's constants), so both see the
// same doubles.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rdf/dataset.hpp"
#include "runtime/kelo.hpp"

namespace mospec::description {

// One problem with a base description: what kind, the entity it is about (a
// term of the dataset read, for the caller to locate), and a message that
// names the entity and the fix. Lowering reports each kind under its own code
// (src/ir/lower_base.cpp); load_base() throws with to_string(kind).
enum class BaseProblemKind : unsigned char {
  Undefined,      // the base is defined by no statement, or is not a CastorDriveBase
                  // (a drive: not a CastorDrive)
  MissingNumber,  // a length, position or weight is absent or not a number
  Unit,           // a length or position is not in exactly one unit, M
  DriveCount,     // fewer than 2 or more than runtime::kMaxKeloDrives drives
  Degenerate,     // Eq. 2-3 are not well posed (runtime::KeloModel refuses the
                  // numbers: a length <= 0, a negative weight, fewer than two
                  // enabled drives at distinct pivots, ...)
};
// "undefined-configuration", "missing-base-number", "base-unit",
// "unsupported-drive-count", "degenerate-base".
std::string_view to_string(BaseProblemKind kind);

struct BaseProblem {
  BaseProblemKind kind;
  rdf::TermId entity;
  std::string message;
};

struct BaseReading {
  runtime::KeloConfig config;  // valid only when `problems` is empty
  std::vector<BaseProblem> problems;
};

// Reads the CastorDriveBase `base_iri` from `dataset` (every graph, as one set
// of triples). Reports every problem it finds; never throws.
BaseReading read_base(const rdf::Dataset& dataset, std::string_view base_iri);

// Loads `model_file` (IRI prefixes resolved through `maps`, prefix ->
// directory, before mospec's own metamodels) and reads the base `base_iri`.
// Throws mospec::Error with the first problem's code, naming the file.
runtime::KeloConfig load_base(const std::string& model_file, const std::string& base_iri,
                              const std::vector<std::pair<std::string, std::string>>& maps = {});

}  // namespace mospec::description
