// The diagnostic catalogue: every code mospec reports, with its default
// severity, the stage that reports it and what it means (docs/diagnostics.md is
// this table rendered; tests/support/diagnostic_codes_test.cpp checks that each
// entry has a test that triggers it).
//
// A code is a DiagnosticCode, built from a string literal at compile time: a
// literal that is not in the table does not compile, so a misspelt code cannot
// ship. A code only known at run time (one stage passing on another's) is
// looked up, and a miss is a bug in mospec, not in the input (std::logic_error,
// exit 3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <iterator>
#include <string>
#include <string_view>
#include <type_traits>

namespace mospec {

enum class Severity : uint8_t { Note, Warning, Error };

struct CodeEntry {
  std::string_view code;
  Severity severity;  // the severity it is reported with (a few are escalated or relaxed by flags)
  std::string_view stage;
  std::string_view meaning;
  // No input reaches it: a failed invariant or the machine failing under mospec.
  // Its test checks that its emission site exists, not that input triggers it.
  bool internal = false;
};

// Grouped by stage, in pipeline order; the JSON-LD codes are the spec's own
// error codes (https://www.w3.org/TR/json-ld11-api/#jsonlderrorcode), spelled
// as the spec spells them so the conformance tests can compare them.
inline constexpr CodeEntry kDiagnosticCodes[] = {
    // Shared by every stage.
    {"io", Severity::Error, "any", "a file cannot be read or written"},
    {"usage", Severity::Error, "any", "the command line asks for something that cannot be done"},
    {"internal", Severity::Error, "any", "a library mospec relies on failed (OpenSSL's SHA-256)",
     true},

    {"invalid json", Severity::Error, "json", "the text is not well-formed JSON"},

    {"syntax", Severity::Error, "rdf", "an N-Quads or Turtle document is not well-formed"},
    {"invalid-term", Severity::Error, "rdf", "a quad names a term id its dataset does not hold"},

    {"sparql-syntax", Severity::Error, "sparql", "a SPARQL query is not well-formed"},
    {"unsupported-sparql", Severity::Error, "sparql",
     "a SPARQL query uses a feature mospec's engine does not implement"},
    {"sparql-limit", Severity::Error, "sparql",
     "a SPARQL query exceeded its time or step budget (--sparql-seconds, --sparql-steps)"},

    {"colliding keywords", Severity::Error, "json-ld", "two keys expand to the same keyword"},
    {"conflicting indexes", Severity::Error, "json-ld", "one node has two different @index values"},
    {"context overflow", Severity::Error, "json-ld",
     "contexts include each other too deeply (JSON-LD 1.1)"},
    {"recursive context inclusion", Severity::Error, "json-ld",
     "a context includes itself (JSON-LD 1.0 processing mode)"},
    {"cyclic IRI mapping", Severity::Error, "json-ld", "a term's IRI is defined through itself"},
    {"invalid @id value", Severity::Error, "json-ld", "an @id is not a string"},
    {"invalid @import value", Severity::Error, "json-ld", "an @import is not a string"},
    {"invalid @included value", Severity::Error, "json-ld", "an @included holds no node objects"},
    {"invalid @index value", Severity::Error, "json-ld", "an @index is not a string"},
    {"invalid @nest value", Severity::Error, "json-ld",
     "an @nest is not a string or names a keyword"},
    {"invalid @prefix value", Severity::Error, "json-ld", "an @prefix is not true or false"},
    {"invalid @propagate value", Severity::Error, "json-ld", "an @propagate is not true or false"},
    {"invalid @protected value", Severity::Error, "json-ld", "an @protected is not true or false"},
    {"invalid @reverse value", Severity::Error, "json-ld", "an @reverse is not an object"},
    {"invalid @version value", Severity::Error, "json-ld", "an @version is not the number 1.1"},
    {"invalid IRI mapping", Severity::Error, "json-ld",
     "a term maps to something that is not an IRI"},
    {"invalid base IRI", Severity::Error, "json-ld", "an @base is not an IRI"},
    {"invalid base direction", Severity::Error, "json-ld", "an @direction is not ltr, rtl or null"},
    {"invalid container mapping", Severity::Error, "json-ld", "an @container has an invalid value"},
    {"invalid context entry", Severity::Error, "json-ld", "a context has a key it may not have"},
    {"invalid context nullification", Severity::Error, "json-ld",
     "a context is nulled where protected terms forbid it"},
    {"invalid default language", Severity::Error, "json-ld",
     "an @language is not a string or null"},
    {"invalid keyword alias", Severity::Error, "json-ld", "a term aliases @context"},
    {"invalid language map value", Severity::Error, "json-ld",
     "a language map holds something that is not a string"},
    {"invalid language mapping", Severity::Error, "json-ld",
     "a term's @language is not a string or null"},
    {"invalid language-tagged string", Severity::Error, "json-ld",
     "a language-tagged string has a malformed tag"},
    {"invalid language-tagged value", Severity::Error, "json-ld",
     "a value with @language is not a string"},
    {"invalid local context", Severity::Error, "json-ld",
     "a context is not an object, an IRI or an array of them"},
    {"invalid remote context", Severity::Error, "json-ld",
     "a loaded context has no @context object"},
    {"invalid reverse property", Severity::Error, "json-ld",
     "a reverse term definition is invalid"},
    {"invalid reverse property map", Severity::Error, "json-ld",
     "an @reverse map holds a keyword or a value object"},
    {"invalid reverse property value", Severity::Error, "json-ld",
     "a reverse property's value is a literal or a list"},
    {"invalid scoped context", Severity::Error, "json-ld", "a term's scoped context is invalid"},
    {"invalid set or list object", Severity::Error, "json-ld",
     "an @set or @list object has other keys"},
    {"invalid term definition", Severity::Error, "json-ld", "a term definition is malformed"},
    {"invalid type mapping", Severity::Error, "json-ld",
     "a term's @type is not an IRI, @id, @vocab, @json or @none"},
    {"invalid type value", Severity::Error, "json-ld", "an @type is not a string or strings"},
    {"invalid typed value", Severity::Error, "json-ld", "a typed value's @type is not an IRI"},
    {"invalid value object", Severity::Error, "json-ld",
     "an @value object has keys it may not have"},
    {"invalid value object value", Severity::Error, "json-ld", "an @value is not a scalar"},
    {"invalid vocab mapping", Severity::Error, "json-ld", "an @vocab is not an IRI or null"},
    {"keyword redefinition", Severity::Error, "json-ld", "a context defines a keyword as a term"},
    {"loading document failed", Severity::Error, "json-ld", "a document cannot be loaded"},
    {"loading remote context failed", Severity::Error, "json-ld", "a context cannot be loaded"},
    {"processing mode conflict", Severity::Error, "json-ld",
     "a JSON-LD 1.1 context is processed in 1.0 mode"},
    {"protected term redefinition", Severity::Error, "json-ld", "a protected term is redefined"},
    {"dropped-key", Severity::Warning, "json-ld",
     "a key maps to no IRI, so its value is dropped from the model"},
    {"dropped-id", Severity::Warning, "json-ld", "an @id is not an IRI, so the node is unnamed"},
    {"malformed-id", Severity::Warning, "json-ld", "an @id looks like a mistyped IRI"},
    {"undefined-type", Severity::Warning, "json-ld",
     "an @type maps to no IRI of a vocabulary the model loads"},
    {"keyword-like-term", Severity::Warning, "json-ld",
     "a term has the form of a keyword and is ignored"},

    {"invalid iri-map", Severity::Error, "load", "an app's iri-map entry is malformed"},
    {"invalid-drop", Severity::Error, "load", "an app drops a node it cannot drop"},
    {"dropped", Severity::Note, "load", "what an app's drop removed from the model"},

    {"invalid-limits", Severity::Error, "robot", "a robot limit is not a finite number > 0"},
    {"too-many-faults", Severity::Error, "robot", "more faults are injected than can be held"},
    {"unknown-sensor", Severity::Error, "robot", "a fault names a sensor the robot does not have"},

    {"invalid-kelo", Severity::Error, "runtime", "a KELO base's numbers are unusable"},
    {"size-mismatch", Severity::Error, "runtime",
     "the ACHD solver is given vectors of the wrong size"},
    {"non-finite", Severity::Error, "runtime", "the ACHD solver is given NaN or infinite entries"},

    {"invalid-robot-model", Severity::Error, "description",
     "a robot description is not a kinematic chain mospec can use"},
    {"invalid-urdf", Severity::Error, "description", "a URDF file cannot be imported"},
    {"invalid-base", Severity::Error, "description",
     "a base problem of no known kind (the fallback of an exhaustive switch)", true},

    {"shacl-ill-formed", Severity::Error, "shacl", "a shapes graph is not well-formed SHACL"},
    {"unsupported-shacl", Severity::Error, "shacl",
     "a shapes graph uses a SHACL feature mospec does not implement"},
    {"shacl-too-deep", Severity::Error, "shacl", "shapes nest deeper than mospec follows"},
    {"shacl-recursion", Severity::Error, "shacl", "a shape refers to itself"},
    {"shacl-failure", Severity::Error, "shacl", "a SHACL-SPARQL constraint failed to run"},

    {"unshaped-terms", Severity::Error, "validation",
     "the list of terms no shape covers is malformed"},
    {"unshaped-term", Severity::Warning, "validation",
     "a term of mospec's metamodels that the model uses is constrained by no shape (--strict)"},
    {"shape-unused", Severity::Warning, "validation",
     "a shape's targets select no node of the model (--strict)"},

    {"lowering-failed", Severity::Error, "lowering", "lowering found errors (listed with it)"},
    {"ambiguous-controller", Severity::Error, "lowering",
     "a controller could drive more than one quantity"},
    {"arm-driven-twice", Severity::Error, "lowering", "two solvers drive one arm"},
    {"base-configuration-mismatch", Severity::Error, "lowering",
     "the base's configuration disagrees with the world's base"},
    {"base-unit", Severity::Error, "lowering", "a base's number has the wrong unit"},
    {"controller-reaches-no-solver", Severity::Warning, "lowering",
     "a controller's output reaches no solver"},
    {"cycle", Severity::Error, "lowering", "steps depend on each other in a cycle"},
    {"degenerate-base", Severity::Error, "lowering", "a base's wheel geometry is degenerate"},
    {"driven-twice", Severity::Error, "lowering", "one quantity has two drivers"},
    {"evaluated-twice", Severity::Error, "lowering", "one constraint has two evaluators"},
    {"infeasible-motion", Severity::Error, "lowering",
     "a motion's constraints cannot all hold at once"},
    {"invalid-controller", Severity::Error, "lowering",
     "a controller's parameters are unusable (a gain or limit out of range)"},
    {"mount-mismatch", Severity::Error, "lowering",
     "an arm is mounted at two places (two statements, or the model and the world)"},
    {"invalid-axis", Severity::Error, "lowering", "an axis is not a unit vector"},
    {"invalid-monitor", Severity::Error, "lowering",
     "a monitor's threshold, edge or inputs are unusable"},
    {"invalid-constraint", Severity::Error, "lowering", "a constraint's bounds are unusable"},
    {"frame-mismatch", Severity::Error, "lowering",
     "two poses, twists or wrenches are combined in different frames"},
    {"invalid-chain", Severity::Error, "lowering", "a kinematic chain cannot be used"},
    {"invalid-evaluator", Severity::Error, "lowering", "a constraint evaluator is unusable"},
    {"invalid-guard", Severity::Error, "lowering", "a motion's guard is unusable"},
    {"invalid-inertia", Severity::Error, "lowering", "an inertia is not physical"},
    {"invalid-number", Severity::Error, "lowering", "a number is not finite or out of range"},
    {"invalid-pose", Severity::Error, "lowering", "a pose is not a rigid transform"},
    {"invalid-timeout", Severity::Error, "lowering", "a timeout is not a finite duration > 0"},
    {"invalid-view", Severity::Error, "lowering", "a view of a quantity is unusable"},
    {"missing-base-number", Severity::Error, "lowering", "a base lacks a number it needs"},
    {"missing-property", Severity::Error, "lowering", "a node lacks a property it needs"},
    {"missing-tolerance", Severity::Error, "lowering",
     "an equality guard or monitor states no tolerance"},
    {"not-a-constant", Severity::Error, "lowering", "a value that must be constant is produced"},
    {"produced-constant", Severity::Error, "lowering", "a constant is also produced by a step"},
    {"produced-twice", Severity::Error, "lowering", "two steps produce one quantity"},
    {"several-values", Severity::Error, "lowering", "a property that takes one value has several"},
    {"subspace-mismatch", Severity::Error, "lowering",
     "a force and its constraint span different subspaces"},
    {"too-many-bases", Severity::Error, "lowering", "an app has more than one mobile base"},
    {"too-many-guards", Severity::Error, "lowering", "a motion has more guards than are supported"},
    {"type-mismatch", Severity::Error, "lowering", "a value has the wrong type"},
    {"unbound-chain", Severity::Error, "lowering", "a solver's chain is bound to no robot arm"},
    {"undefined-configuration", Severity::Error, "lowering",
     "a base names a configuration the model does not define"},
    {"undefined-constraint", Severity::Error, "lowering",
     "a node names a constraint the model does not define"},
    {"undefined-quantity", Severity::Error, "lowering",
     "a node names a quantity the model does not define"},
    {"unevaluated-constraint", Severity::Error, "lowering", "a constraint has no evaluator"},
    {"unhandled", Severity::Error, "lowering",
     "a controller or motion is listed by no constraint handler"},
    {"unknown-joint", Severity::Error, "lowering", "a joint is not one of the chain's"},
    {"unknown-link", Severity::Error, "lowering", "a link is not one of the chain's"},
    {"unordered-directions", Severity::Error, "lowering",
     "a solver's driver directions have no order"},
    {"unprioritised-driver", Severity::Error, "lowering", "a solver's driver has no priority"},
    {"unproduced-quantity", Severity::Error, "lowering",
     "a quantity is read but nothing produces it"},
    {"unstated-idle", Severity::Error, "lowering", "an arm does not say what it does when idle"},
    {"unsupported-attachment", Severity::Error, "lowering",
     "a force or constraint is attached where the solver cannot take it"},
    {"unsupported-constraint", Severity::Error, "lowering", "a constraint kind is not supported"},
    {"unsupported-drive-count", Severity::Error, "lowering",
     "a base has a number of drives mospec does not support"},
    {"unsupported-idle", Severity::Error, "lowering", "an arm's idle behaviour is not supported"},
    {"unsupported-inertia", Severity::Error, "lowering",
     "an impedance controller states an apparent inertia"},
    {"unsupported-one-sided", Severity::Error, "lowering",
     "a one-sided constraint where only two-sided ones are supported"},
    {"unsupported-output", Severity::Error, "lowering",
     "a solver output mospec cannot compute is asked for"},
    {"unsupported-priority", Severity::Error, "lowering",
     "a priority scheme the solver does not support"},
    {"unsupported-property", Severity::Error, "lowering",
     "a property mospec does not honour is stated"},
    {"unsupported-root", Severity::Error, "lowering", "a chain's root is not supported"},
    {"unsupported-solver", Severity::Error, "lowering", "a solver kind is not supported"},
    {"unused-controller", Severity::Note, "lowering", "a controller is never activated"},
    {"wrong-unit", Severity::Error, "lowering", "a quantity has the wrong unit"},

    {"ir-invalid", Severity::Error, "ir", "a program does not verify"},

    {"codegen", Severity::Error, "codegen",
     "a program cannot be written as C++ (an embedded template fails, or a placement does not "
     "survive the generated chain)",
     true},
    {"codegen-name-collision", Severity::Error, "codegen",
     "two names of a program map to one C++ identifier"},
    {"codegen-template", Severity::Error, "codegen", "a code template is malformed"},
    {"build", Severity::Error, "codegen",
     "building a generated controller failed (the compiler, CMake or a library is missing or "
     "broken, or mospec generated code that does not compile)",
     true},
    {"load", Severity::Error, "codegen", "a built controller cannot be loaded"},
    {"unsafe-cache", Severity::Error, "codegen", "the build cache is not private to the user"},
    {"unsafe-path", Severity::Error, "codegen", "a path cannot be written safely into CMake"},

    {"invalid-world", Severity::Error, "simulation", "a world file is unusable"},
    {"invalid-duration", Severity::Error, "simulation", "a run's duration is unusable"},
    {"invalid-run-options", Severity::Error, "simulation", "a run's options do not fit the world"},
    {"robot-mismatch", Severity::Error, "simulation",
     "a controller was made for another robot than the world's"},
    {"mujoco", Severity::Error, "simulation",
     "the generated MuJoCo model lacks an object mospec made", true},
    {"video", Severity::Error, "simulation", "a video cannot be rendered or encoded"},

    {"loop-sign", Severity::Error, "run",
     "a controller's gain has the sign that makes its error grow"},
    {"unstable-loop", Severity::Error, "run", "a controller's closed loop is unstable at the tick"},
    {"fixed-tip", Severity::Note, "import-urdf",
     "a URDF's tip link is fixed to the last moving link"},
    {"new", Severity::Error, "new", "mospec new cannot make the asked-for app"},
    {"trials", Severity::Error, "trials", "a trials run or its results are unusable"},
    {"csv", Severity::Error, "plot", "a run log is not the CSV mospec writes"},
    {"missing-column", Severity::Error, "plot", "a run log lacks a column the plot needs"},
    {"not-found", Severity::Error, "plot", "gnuplot is not installed", true},
    {"plot", Severity::Error, "plot", "gnuplot failed on the script mospec wrote", true},
    {"report", Severity::Error, "report", "a run cannot be reported"},
};

class DiagnosticCode;
namespace detail {
// Not constexpr: reaching it while a literal code is checked at compile time
// makes the DiagnosticCode's constructor fail to compile.
void diagnostic_code_not_in_catalogue();
}  // namespace detail

// One entry of kDiagnosticCodes, named by its code.
class DiagnosticCode {
 public:
  // The empty code of a default-made Diagnostic (no entry).
  constexpr DiagnosticCode() = default;
  consteval DiagnosticCode(const char* code) : DiagnosticCode(std::string_view(code)) {}
  consteval DiagnosticCode(std::string_view code) : index_(index_of(code)) {
    if (index_ == kNone) detail::diagnostic_code_not_in_catalogue();
  }
  // A code carried at run time (passed on from another diagnostic); a code
  // the catalogue lacks throws std::logic_error (a bug in mospec), and an
  // empty one is no code.
  DiagnosticCode(const std::string& code);
  static DiagnosticCode checked(std::string_view code);
  // nullptr for a code the catalogue lacks.
  static const CodeEntry* find(std::string_view code);

  bool empty() const { return index_ == kNone; }
  std::string_view name() const { return empty() ? std::string_view() : entry().code; }
  const CodeEntry& entry() const { return kDiagnosticCodes[index_]; }
  operator std::string_view() const { return name(); }
  operator std::string() const { return std::string(name()); }
  friend bool operator==(const DiagnosticCode& a, const DiagnosticCode& b) {
    return a.index_ == b.index_;
  }
  // Against a spelling (a literal, a std::string): exact matches, so they are
  // chosen before converting the spelling to a code.
  template <class T>
  requires(std::is_convertible_v<const T&, std::string_view> &&
           !std::is_same_v<T, DiagnosticCode>) friend bool
  operator==(const DiagnosticCode& a, const T& b) {
    return a.name() == std::string_view(b);
  }

 private:
  static constexpr uint16_t kNone = UINT16_MAX;
  static constexpr uint16_t index_of(std::string_view code) {
    for (size_t i = 0; i < std::size(kDiagnosticCodes); ++i) {
      if (kDiagnosticCodes[i].code == code) return static_cast<uint16_t>(i);
    }
    return kNone;
  }
  uint16_t index_ = kNone;
};

std::ostream& operator<<(std::ostream&, const DiagnosticCode&);

}  // namespace mospec
