#include "ir/lower.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <unordered_map>

#include "ir/lowering.hpp"

namespace mospec::ir {

namespace {

std::string join_lines(const std::vector<Diagnostic>& ds) {
  std::string out;
  for (size_t i = 0; i < ds.size(); ++i) {
    if (i) out.push_back('\n');
    out.append(format(ds[i]));
  }
  return out;
}

}  // namespace

LowerError::LowerError(std::vector<Diagnostic> diagnostics)
    : Error("lowering-failed", join_lines(diagnostics)), diagnostics_(std::move(diagnostics)) {}

std::string content_hash(const std::string& text) {
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

namespace {

using lowering::State;

struct PassInfo {
  std::string_view name;
  void (*run)(State&);
  bool scheduled = false;  // runs on program.steps, in schedule order
};

// Lowering's passes, in order: what each lowers is in its name.
const PassInfo kPasses[] = {
    {"properties", &lowering::refuse_unread_properties},
    {"clocks", &lowering::lower_clocks},
    {"arm-solvers", &lowering::lower_arms},
    {"operators", &lowering::lower_operators},
    {"accumulated-wrenches", &lowering::lower_accumulated_wrenches},
    {"planar-angles", &lowering::lower_planar_angles},
    {"base", &lowering::lower_base},
    {"evaluators", &lowering::lower_evaluators},
    {"monitors", &lowering::lower_monitors},
    {"handlers", &lowering::lower_handlers},
    {"goals", &lowering::lower_goals},
    {"controllers", &lowering::lower_controllers},
    {"views", &lowering::lower_views},
    {"driver-directions", &lowering::check_driver_directions},
    {"motion-gates", &lowering::gate_arm_solves},
    {"producers", &lowering::check_inputs},
    {"schedule", &lowering::schedule, true},
    {"unlisted-controllers", &lowering::settle_unlisted_controllers, true},
    {"log", &lowering::build_log, true},
};

// Reports lowering's warnings, located as its errors are.
struct Warnings {
  const app::LoadedModel& model;
  DiagnosticSink& sink;
  void warn(SourceLoc loc, DiagnosticCode code, std::string message) const {
    sink.report(located(Severity::Warning, loc, model.files(), code, std::move(message)));
  }
};

// A controller whose output reaches no solver (no acceleration constraint or
// force of a solver's motion drivers depends on it, through any chain of
// operators, views and other controllers) runs every tick and moves nothing:
// the model asked for a control law that has no effect, which is said at the
// controller. Steps are in schedule order, so one backward pass finds every
// step whose output a solver reads, directly or not.
void warn_controllers_reaching_no_solver(const State& st, const Warnings& w) {
  const Program& program = st.program;
  const std::vector<char> effective = lowering::steps_reaching_a_solver(program);
  for (size_t s = 0; s < program.steps.size(); ++s) {
    const Step& step = program.steps[s];
    if (role(step) != StepRole::Controller || effective[s] || step.out.empty()) continue;
    if (st.unlisted_controllers.count(st.term(step.iri).index)) continue;  // a note says so
    w.warn(step.where, "controller-reaches-no-solver",
           "the controller '" + step.iri + "' drives '" +
               program.data[static_cast<size_t>(step.out.front())].iri +
               "', which reaches no solver: no acceleration constraint or force of a solver's "
               "motion drivers depends on it, so the controller runs every tick and moves "
               "nothing; name it in an acceleration constraint (or the wrench of a force) that "
               "a solver uses, or take it out of the `controllers` of the handlers that list "
               "it (it is then not used, and lowering notes that)");
  }
}

}  // namespace

Program lower(const app::LoadedModel& model, const LowerOptions& options) {
  State st(model, options);
  for (const app::ModelFile& f : model.model_files()) {
    if (f.is_app) {
      st.program.app = f.iri;
      break;
    }
  }
  for (const PassInfo& pass : kPasses) {
    pass.run(st);
    if (!st.errors.empty()) {
      // Later passes would only report what follows from these problems,
      // except that every missing producer is worth knowing at once.
      if (pass.name == "producers" || pass.scheduled) break;
      continue;
    }
    // Until "schedule" orders them, the steps so far are in st.steps, in
    // declaration order: lend them to the program for the check.
    const bool ordered = pass.scheduled;
    if (!ordered) std::swap(st.program.steps, st.steps);
    auto problems =
        check(st.program, &model.files(), ordered ? Stage::Scheduled : Stage::Unscheduled);
    if (options.after_pass) options.after_pass(pass.name, st.program);
    if (!ordered) std::swap(st.program.steps, st.steps);
    if (!problems.empty()) {
      for (Diagnostic& d : problems)
        d.message = "after lowering pass '" + std::string(pass.name) + "': " + d.message;
      throw VerifyError(std::move(problems));
    }
  }
  if (!st.errors.empty()) throw LowerError(std::move(st.errors));
  if (options.warnings != nullptr) {
    warn_controllers_reaching_no_solver(st, Warnings{model, *options.warnings});
    for (Diagnostic& n : st.notes) options.warnings->report(std::move(n));
  }
  return std::move(st.program);
}

std::span<const std::string_view> lowering_passes() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> out;
    for (const PassInfo& p : kPasses) out.push_back(p.name);
    return out;
  }();
  return names;
}

}  // namespace mospec::ir
