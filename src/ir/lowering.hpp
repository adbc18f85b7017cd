// Lowering's explicit state and its passes (internal to src/ir; the public
// entry point is lower.hpp).
//
// Each pass is a free function over one State: it reads the model through
// State's graph accessors and adds data and steps through State's builders.
// lower.cpp runs them in order (kPasses) and checks the program after each.
// A State is the only thing passes share: the program under construction and
// the few cross-pass tables below, each documented with who writes it and who
// reads it.
#pragma once

#include <map>
#include <memory_resource>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "ir/graph.hpp"
#include "ir/ir.hpp"
#include "ir/lower.hpp"
#include "ir/operators.hpp"
#include "support/arena.hpp"
#include "vocab/metamodels.hpp"
#include "vocab/w3c.hpp"

namespace mospec::ir::lowering {

using rdf::TermId;

// mospec::vocab::metamodel_term(domain, local), built in one allocation (the
// passes spell their vocabulary terms this way, hundreds of times a lowering).
inline std::string vocab(std::string_view domain, std::string_view local) {
  const std::string_view mm = mospec::vocab::kMetamodels;
  std::string s;
  s.reserve(mm.size() + domain.size() + 1 + local.size());
  s.append(mm).append(domain).append("#").append(local);
  return s;
}
inline const std::string kXsd(mospec::vocab::xsd::ns);
inline const std::string kQudt(mospec::vocab::qudt::ns);

// What follows the last '#' or '/' (a plain loop: find_last_of calls memchr
// once per character).
inline std::string_view local_view(std::string_view iri) {
  for (size_t k = iri.size(); k > 0; --k) {
    if (iri[k - 1] == '#' || iri[k - 1] == '/') return iri.substr(k);
  }
  return iri;
}
inline std::string local_name(std::string_view iri) {
  return std::string(local_view(iri));
}

// "a " or "an ", as messages put it before `word`.
inline std::string article(std::string_view word) {
  return std::string_view("aeiouAEIOU").find(word.empty() ? 'x' : word[0]) == std::string_view::npos
             ? "a "
             : "an ";
}

// ASCII letters and digits are kept (as std::isalnum does in the "C" locale
// mospec runs in), anything else becomes '_'.
inline std::string identifier(std::string_view s) {
  const auto alnum = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
  };
  const bool digit_first = !s.empty() && s[0] >= '0' && s[0] <= '9';
  const size_t prefix = s.empty() || digit_first ? 2 : 0;
  std::string out(prefix + s.size(), '_');
  if (prefix) out[0] = 'q';
  for (size_t i = 0; i < s.size(); ++i) {
    if (alnum(s[i])) out[prefix + i] = s[i];
  }
  return out;
}

struct State {
  State(const app::LoadedModel& loaded, const LowerOptions& lower_options)
      : model(loaded), graph(loaded.dataset()), options(lower_options) {
    // Room for a model of sc1's size (about 150 data and 160 steps), so that
    // growing these rarely moves every datum, step or name.
    program.data.reserve(256);
    steps.reserve(256);
    data_names.reserve(256);
    step_names.reserve(256);
  }

  // --- graph access (ir/graph.hpp) ---------------------------------------
  TermId term(const std::string& iri) const { return graph.term(iri); }
  static bool absent(TermId t) { return t.is_any(); }
  std::string str(TermId t) const { return std::string(graph.str(t)); }
  std::vector<TermId> objects(TermId s, const std::string& p) const {
    return graph.objects(s, term(p));
  }
  // The one value of a single-valued property. A second value (e.g. a
  // quantity given a value by two files) is never resolved by picking one:
  // it is a located error naming both (several_values).
  std::optional<TermId> object(TermId s, const std::string& p) const { return object(s, term(p)); }
  void several_values(TermId s, const std::string& p, const std::vector<TermId>& values) const;
  // For a reference to `e` that nothing defines: "; did you mean '<nearest>'?"
  // naming the defined entity of the same namespace nearest in spelling, or "".
  std::string did_you_mean(TermId e) const;
  bool has_type(TermId s, const std::string& type) const { return graph.has_type(s, term(type)); }
  std::vector<TermId> instances(const std::string& type) const {
    return graph.instances(term(type));
  }
  bool defined(TermId s) const { return graph.defined(s); }
  SourceLoc where(TermId s) const { return graph.where(s); }
  SourceLoc where(TermId s, const std::string& p, TermId o) const {
    return graph.where(s, term(p), o);
  }
  // Whether `q` is the time some clock gives (mospec/time).
  bool is_clock_time(TermId q) const {
    for (TermId c : graph.subjects(term(vocab("mospec/time", "time")), q)) {
      if (has_type(c, vocab("mospec/time", "Clock"))) return true;
    }
    return false;
  }
  std::vector<TermId> list(TermId head) const { return graph.list(head); }
  std::optional<double> number(TermId lit) const { return graph.number(lit); }
  // The literal as messages quote it: "+1e400"^^xsd:double.
  std::string literal_text(TermId lit) const {
    const rdf::Term& t = graph.terms()[lit];
    std::string dt(graph.terms()[t.datatype].value);
    if (dt.starts_with(kXsd)) dt.replace(0, kXsd.size(), "xsd:");
    std::string out = "\"";
    out.append(t.value).append("\"^^").append(dt);
    return out;
  }
  std::optional<double> number(TermId s, const std::string& p) const {
    auto o = object(s, p);
    return o ? graph.number(*o) : std::nullopt;
  }

  // The graphs of the file that describes a chain (read in place by
  // description::describe_chain): other files' poses between the robot's
  // frames (task quantities) are not part of its structure.
  std::vector<TermId> chain_graphs(const std::string& chain_iri) const {
    return graph.graphs_of(term(chain_iri));
  }

  // --- diagnostics --------------------------------------------------------
  void error(SourceLoc loc, DiagnosticCode code, std::string message) const {
    errors.push_back(located(Severity::Error, loc, model.files(), code, std::move(message)));
  }
  // "file:line:col" of an entity, for a message that names a second place.
  std::string place(SourceLoc loc) const {
    if (!loc.known()) return "an unknown place";
    return format_place(model.files().path(loc.file), loc.line, loc.column);
  }
  std::string place(TermId e) const { return place(where(e)); }
  void error(TermId at, DiagnosticCode code, std::string message) const {
    error(where(at), code, std::move(message));
  }
  // What lowering left out of the program, and why: reported with the
  // warnings (LowerOptions::warnings), never counted as one.
  void note(SourceLoc loc, DiagnosticCode code, std::string message) const {
    notes.push_back(located(Severity::Note, loc, model.files(), code, std::move(message)));
  }

  // --- data ---------------------------------------------------------------
  // The vocabulary terms every datum is read through (type_of, datum,
  // fill_constant), looked up once per lowering instead of spelled and looked
  // up per datum; any() for a term the model never uses.
  struct DatumTerms {
    TermId pose, pose_coordinate, twist, twist_coordinate, wrench, wrench_coordinate,
        rigid_body_inertia, rigid_body_inertia_coordinate, direction_coordinate, position,
        position_coordinate, quantity, linear_distance;
    TermId of_body, about;  // a rigid-body inertia's body and reference point
    TermId has_quantity_kind, unit, value;
    TermId of, with_respect_to, reference_point, dyn_reference_point, as_seen_by, dyn_as_seen_by;
    TermId x, y, z, direction_cosine[3];
  };
  const DatumTerms& datum_terms() const;
  // object(s, p) for a property given by its id. Only a property with
  // several values is read as a sorted list (for the error and the first).
  std::optional<TermId> object(TermId s, TermId p) const {
    bool several = false;
    const TermId one = graph.single_object(s, p, several);
    if (several) return several_of(s, p);
    if (one.is_any()) return std::nullopt;
    return one;
  }
  // The first of a property's several values, reported (several_values).
  TermId several_of(TermId s, TermId p) const {
    const std::vector<TermId> all = graph.objects(s, p);
    several_values(s, str(p), all);
    return all.front();
  }
  std::optional<double> number(TermId s, TermId p) const {
    auto o = object(s, p);
    return o ? graph.number(*o) : std::nullopt;
  }
  std::optional<DataType> type_of(TermId e) const;
  int datum(TermId e, DataType expected, TermId referenced_by, const std::string& role);
  int synthetic(const std::string& iri, const std::string& name, DataType type, SourceLoc loc,
                const std::string& unit = {});
  // `base` as an identifier, made unique among `used` by a suffix _2, _3, ...
  using Names = std::pmr::unordered_set<std::pmr::string>;
  std::string unique_name(std::string_view base, Names& used) {
    std::string n = identifier(base);
    if (used.emplace(std::string_view(n)).second) return n;
    for (int k = 2;; ++k) {
      std::string candidate = n + "_" + std::to_string(k);
      if (used.emplace(std::string_view(candidate)).second) return candidate;
    }
  }
  void fill_inertia(Data& d, TermId e);

  // --- steps --------------------------------------------------------------
  // A step asked for by model entity `e`, named and located by it.
  Step step_for(StepKind kind, TermId e) const {
    Step s;
    s.kind = kind;
    s.iri = str(e);
    s.name = local_name(s.iri);
    s.where = where(e);
    return s;
  }
  int add_step(Step step) {
    step.name = unique_name(step.name, step_names);
    const int index = static_cast<int>(steps.size());
    for (int d : step.out) produce(d, index);
    steps.push_back(std::move(step));
    return index;
  }
  void produce(int d, int step) {
    if (!program.data[static_cast<size_t>(d)].value.empty()) {
      const Data& dd = program.data[static_cast<size_t>(d)];
      error(dd.where, "produced-constant",
            "'" + dd.iri + "' has a fixed value in the model, but '" + pending_iri +
                "' also writes it");
      return;
    }
    auto [it, fresh] = producer.emplace(d, step);
    if (!fresh) {
      const Data& dd = program.data[static_cast<size_t>(d)];
      std::string msg = "'";
      msg.append(dd.iri)
          .append("' is produced twice: by '")
          .append(steps[static_cast<size_t>(it->second)].iri)
          .append("' and by '")
          .append(pending_iri)
          .append("'");
      error(dd.where, "produced-twice", msg);
    }
  }
  bool produced(int d) const {
    return producer.count(d) || !program.data[static_cast<size_t>(d)].value.empty();
  }

  // The model, read-only.
  const app::LoadedModel& model;
  Graph graph;  // the model's flattened union, read in place
  const LowerOptions& options;

  // What every pass builds: the program's data (through datum/synthetic), its
  // steps in declaration order (add_step; "schedule" moves them into
  // program.steps), the problems found (error), and the names taken so far.
  Program program;
  std::vector<Step> steps;
  // Mutable: the graph accessors, const otherwise, report a property that has
  // several values where one is read (once per subject and property).
  mutable std::vector<Diagnostic> errors;
  mutable std::vector<Diagnostic> notes;
  mutable std::set<std::pair<uint32_t, std::string>> several_reported;
  mutable std::optional<DatumTerms> datum_terms_;  // datum_terms(), once looked up
  // The names and tables below live exactly as long as one lowering: their
  // nodes (hundreds of them, each otherwise a malloc and a free) come from
  // one arena, released at once when the State goes. Declared first, so it
  // outlives them.
  Arena arena{16 * 1024};
  Names data_names{&arena}, step_names{&arena};            // taken (unique_name)
  std::pmr::unordered_map<uint32_t, int> data_of{&arena};  // model entity (term index) -> its datum
  std::pmr::map<int, int> producer{&arena};                // datum -> the step that writes it
  std::string pending_iri;                                 // the entity being lowered, for messages

  // Tables one pass leaves for a later one (writer -> readers).
  // evaluators -> handlers: which Evaluate step checks a constraint.
  std::pmr::map<uint32_t, int> evaluator_of_constraint{&arena};
  // evaluators -> monitors, handlers: an evaluator's Evaluate step.
  std::pmr::map<uint32_t, int> evaluate_step_of_evaluator{&arena};
  // monitors -> handlers: a monitor's step.
  std::pmr::map<uint32_t, int> monitor_step_of_monitor{&arena};
  // handlers -> controllers: the flag that activates a controller.
  std::pmr::map<uint32_t, int> active_of_controller{&arena};
  // handlers -> unlisted-controllers: the controllers no handler lists, and
  // the handlers of the app (where the advice points).
  std::pmr::set<uint32_t> unlisted_controllers{&arena};
};

// --- the passes, in the order lower.cpp runs them ---------------------------
// lower_properties.cpp
void refuse_unread_properties(State& st);
// lower_arms.cpp
void lower_clocks(State& st);
void lower_arms(State& st);
void lower_arm(State& st, TermId solver);
void gate_arm_solves(State& st);
void check_driver_directions(State& st);
// lower_operators.cpp
void lower_operators(State& st);
void refuse_unknown_properties(State& st, TermId e, const OperatorKind& kind);
int axis_constant(State& st, TermId e, const OperatorKind& kind, const OperatorPort& port,
                  TermId axis);
void check_frames(State& st, TermId e, const OperatorKind& kind, const Step& s);
std::string frame_origin(const State& st, const std::string& frame);
void lower_accumulated_wrenches(State& st);
void lower_planar_angles(State& st);
// lower_base.cpp
void lower_base(State& st);
// lower_constraints.cpp
void lower_evaluators(State& st);
void lower_monitors(State& st);
void lower_handlers(State& st);
void lower_goals(State& st);
// lower_controllers.cpp
void lower_controllers(State& st);
// lower_views.cpp
void lower_views(State& st);
// lower_schedule.cpp
void check_inputs(State& st);
void schedule(State& st);
void build_log(State& st);
void settle_unlisted_controllers(State& st);

// Per step of a scheduled program: whether a solver (an arm's solve or the
// base's force distribution) reads its output, directly or through other
// steps. Steps are in schedule order, so one backward pass finds them all.
std::vector<char> steps_reaching_a_solver(const Program& program);

}  // namespace mospec::ir::lowering
