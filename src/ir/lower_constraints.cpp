// Lowering passes. Constraints: evaluators, monitors, the constraint handlers (their
// controllers: lower_controllers.cpp).
#include <algorithm>
#include <cmath>
#include <map>
#include <memory_resource>
#include <set>

#include "ir/controllers.hpp"
#include "ir/lowering.hpp"

namespace mospec::ir::lowering {

namespace {

// mospec's extension for guards and monitors (metamodels/mospec/guards.json).
const std::string kGuards = "mospec/guards";
// A constraint's tolerance: the published cstr-ext:tolerance (the secorolab
// task/constraint-extension.json).
const std::string kTolerance = mospec::vocab::term(mospec::vocab::cstr_ext::ns, "tolerance");

// An Evaluate step of an equality constraint that states no tolerance: it
// holds only at the instants its quantity equals the reference exactly, which
// a guard or a monitor would almost never see. The constraint, or nothing.
std::optional<TermId> equality_without_tolerance(const State& st, const Step& evaluate) {
  if (evaluate.constraint.kind != runtime::ConstraintKind::Equality) return std::nullopt;
  const auto c = st.object(st.term(evaluate.iri), vocab("task/constraint-handler", "constraint"));
  // A retired mos-grd:tolerance is refused where it is stated
  // (refuse_unread_properties): its absence here is that error's consequence.
  if (!c || st.object(*c, kTolerance) || st.object(*c, vocab(kGuards, "tolerance")))
    return std::nullopt;
  return c;
}

}  // namespace

namespace {

// The vocabulary terms the evaluators are read through, looked up once.
struct EvaluatorTerms {
  TermId error_evaluator, assignment_evaluator, constraint_p, error_p, quantity_p, lower_p, upper_p,
      threshold_p, reference_p, tolerance_p, bilateral, greater_than, less_than, equality,
      qudt_value;
};
EvaluatorTerms evaluator_terms(const State& st) {
  const auto ch = [&](std::string_view local) {
    return st.term(vocab("task/constraint-handler", local));
  };
  const auto cs = [&](std::string_view local) { return st.term(vocab("task/constraint", local)); };
  return {ch("ErrorEvaluator"),
          ch("AssignmentEvaluator"),
          ch("constraint"),
          ch("error"),
          cs("quantity"),
          cs("lower-threshold"),
          cs("upper-threshold"),
          cs("threshold"),
          cs("reference-value"),
          st.term(kTolerance),
          cs("BilateralConstraint"),
          cs("GreaterThanConstraint"),
          cs("LessThanConstraint"),
          cs("EqualityConstraint"),
          st.term(kQudt + "value")};
}

// One evaluator being lowered: its constraint `c` on the quantity `q`, and the
// Evaluate step it becomes.
struct Evaluation {
  State& st;
  const EvaluatorTerms& t;
  TermId e, c, q;
  bool assignment = false;
  int quantity = -1;
  std::string unit;  // the quantity's
  Step s;
  runtime::ConstraintSpec spec;
  std::optional<int> reference_datum;

  bool is(TermId type) const { return st.graph.has_type(c, type); }
};

// A threshold/reference of the constraint: a constant with the quantity's
// unit; nullopt when absent or invalid (reported).
std::optional<double> read_constant(Evaluation& ev, const std::string& prop, TermId property) {
  State& st = ev.st;
  auto t = st.object(ev.c, property);
  if (!t) return std::nullopt;
  const int d = st.datum(*t, DataType::Scalar, ev.c, prop);
  const Data& dd = st.program.data[static_cast<size_t>(d)];
  if (dd.value.empty()) {
    const auto lit = st.object(*t, ev.t.qudt_value);
    if (lit && st.graph.terms()[*lit].is_literal()) {
      st.error(st.graph.where(*t, ev.t.qudt_value, *lit), "invalid-number",
               "the " + prop + " '" + dd.iri + "' of '" + st.str(ev.c) + "' has the value " +
                   st.literal_text(*lit) + ", which is not a finite number of its datatype");
    } else if (st.defined(*t)) {  // else undefined-quantity said it
      st.error(*t, "not-a-constant",
               "the " + prop + " '" + dd.iri + "' of '" + st.str(ev.c) + "' has no value");
    }
    return std::nullopt;
  }
  if (dd.unit != ev.unit) {
    st.error(
        *t, "wrong-unit",
        "the " + prop + " '" + dd.iri + "' is in '" + dd.unit + "' but the constrained quantity '" +
            st.program.data[static_cast<size_t>(ev.quantity)].iri + "' is in '" + ev.unit + "'");
  }
  return dd.value[0];
}

// The model's tolerance `tol` of the constraint (cstr-ext:tolerance): a bound
// on |error|. False when it is invalid (reported).
bool read_tolerance(Evaluation& ev, TermId tol) {
  const auto v = read_constant(ev, "tolerance", ev.t.tolerance_p);
  if (!v) return false;
  if (!(*v >= 0.0)) {
    ev.st.error(tol, "invalid-constraint",
                "the tolerance '" + ev.st.str(tol) + "' of '" + ev.st.str(ev.c) + "' is " +
                    exact_number(*v) + "; a tolerance is a bound on |error|, >= 0");
    return false;
  }
  ev.spec.tolerance = *v;
  ev.s.tolerance_source = Step::Tolerance::Stated;
  return true;
}

bool read_bilateral(Evaluation& ev) {
  State& st = ev.st;
  ev.spec.kind = runtime::ConstraintKind::Bilateral;
  auto lo = read_constant(ev, "lower-threshold", ev.t.lower_p),
       hi = read_constant(ev, "upper-threshold", ev.t.upper_p);
  if (!lo || !hi) {
    // An invalid threshold has been reported by read_constant(); only a
    // missing one is reported here.
    if (!st.object(ev.c, ev.t.lower_p) || !st.object(ev.c, ev.t.upper_p))
      st.error(
          ev.c, "missing-property",
          "the bilateral constraint '" + st.str(ev.c) + "' needs a lower and an upper threshold");
    return false;
  }
  ev.spec.lower = *lo;
  ev.spec.upper = *hi;
  if (!(ev.spec.lower < ev.spec.upper)) {
    st.error(ev.c, "invalid-constraint",
             "the bilateral constraint '" + st.str(ev.c) + "' needs lower < upper");
    return false;
  }
  return true;
}

bool read_inequality(Evaluation& ev) {
  State& st = ev.st;
  ev.spec.kind = ev.is(ev.t.greater_than) ? runtime::ConstraintKind::GreaterThan
                                          : runtime::ConstraintKind::LessThan;
  auto t = read_constant(ev, "threshold", ev.t.threshold_p);
  if (!t) {
    if (!st.object(ev.c, ev.t.threshold_p))
      st.error(ev.c, "missing-property", "the constraint '" + st.str(ev.c) + "' needs a threshold");
    return false;
  }
  ev.spec.threshold = *t;
  // The model's tolerance: satisfied while beyond the threshold by no
  // more than it (a one-sided row releases within it: mark_one_sided).
  if (auto tol = st.object(ev.c, ev.t.tolerance_p)) {
    if (!read_tolerance(ev, *tol)) return false;
  }
  // A timeout: a threshold on a clock's time, which starts at 0 and only
  // grows. A threshold <= 0 s is decided before the first tick (a
  // greater-than constraint holds at once, a less-than never does).
  if (!(ev.spec.threshold > 0.0) && st.is_clock_time(ev.q)) {
    const TermId th = *st.object(ev.c, ev.t.threshold_p);
    const auto lit = st.object(th, ev.t.qudt_value);
    st.error(lit ? st.graph.where(th, ev.t.qudt_value, *lit) : st.where(th), "invalid-timeout",
             "the timeout '" + st.str(th) + "' of '" + st.str(ev.c) + "' is " +
                 exact_number(ev.spec.threshold) + " s; a threshold on the clock's time '" +
                 st.str(ev.q) + "' must be > 0 s");
    return false;
  }
  return true;
}

bool read_equality(Evaluation& ev) {
  State& st = ev.st;
  ev.spec.kind =
      ev.assignment ? runtime::ConstraintKind::Assignment : runtime::ConstraintKind::Equality;
  auto r = read_constant(ev, "reference-value", ev.t.reference_p);
  if (!r) {
    if (!st.object(ev.c, ev.t.reference_p))
      st.error(ev.c, "missing-property",
               "the equality constraint '" + st.str(ev.c) + "' needs a reference-value");
    return false;
  }
  ev.spec.reference = *r;
  if (auto t = st.object(ev.c, ev.t.reference_p)) ev.reference_datum = st.data_of.at(t->index);
  // The model's tolerance (cstr-ext:tolerance): satisfied while |error| <= it.
  auto tol = st.object(ev.c, ev.t.tolerance_p);
  if (!tol) return true;
  if (ev.assignment) {
    st.error(st.graph.where(ev.c, ev.t.tolerance_p, *tol), "unsupported-property",
             "the equality constraint '" + st.str(ev.c) +
                 "' states `tolerance`, but the "
                 "assignment evaluator '" +
                 st.str(ev.e) +
                 "' imposes its reference-value and "
                 "never checks it, so the tolerance would be ignored; remove `tolerance`");
    return false;
  }
  return read_tolerance(ev, *tol);
}

// The constraint's kind and bounds into ev.spec; false when refused (reported).
bool read_constraint(Evaluation& ev) {
  bool read = false;
  if (ev.is(ev.t.bilateral)) {
    read = read_bilateral(ev);
  } else if (ev.is(ev.t.greater_than) || ev.is(ev.t.less_than)) {
    read = read_inequality(ev);
  } else if (ev.is(ev.t.equality)) {
    read = read_equality(ev);
  } else {
    ev.st.error(ev.c, "unsupported-constraint",
                "'" + ev.st.str(ev.c) +
                    "' is not an equality, bilateral, greater-than or less-than constraint");
    return false;
  }
  if (!read) return false;
  if (ev.assignment && ev.spec.kind != runtime::ConstraintKind::Assignment) {
    ev.st.error(ev.e, "invalid-evaluator",
                "the assignment evaluator '" + ev.st.str(ev.e) + "' needs an equality constraint");
    return false;
  }
  return true;
}

// The Evaluate step: the constraint's satisfied flag, and its error (or, for
// an assignment, the quantity it writes).
void add_evaluate_step(Evaluation& ev) {
  State& st = ev.st;
  Step& s = ev.s;
  s.constraint = ev.spec;
  const int satisfied =
      st.synthetic(st.str(ev.c) + "#satisfied", local_name(st.str(ev.c)) + "_satisfied",
                   DataType::Flag, st.where(ev.c));
  if (ev.spec.kind == runtime::ConstraintKind::Bilateral) {
    s.lower_bound = st.data_of.at(st.object(ev.c, ev.t.lower_p)->index);
    s.upper_bound = st.data_of.at(st.object(ev.c, ev.t.upper_p)->index);
  }
  if (ev.assignment) {
    // The quantity is what the evaluator writes: the reference value.
    s.in = {*ev.reference_datum};
    s.out = {satisfied, ev.quantity};
  } else {
    int err = -1;
    if (auto eo = st.object(ev.e, ev.t.error_p)) {
      err = st.datum(*eo, DataType::Scalar, ev.e, "error");
      s.has_error_output = true;
    } else {
      err = st.synthetic(st.str(ev.e) + "#error", local_name(st.str(ev.e)) + "_error",
                         DataType::Scalar, st.where(ev.e), ev.unit);
    }
    s.in = {ev.quantity};
    s.out = {satisfied, err};
  }
  const int index = st.add_step(std::move(s));
  if (st.evaluator_of_constraint.count(ev.c.index)) {
    st.error(ev.e, "evaluated-twice", "the constraint '" + st.str(ev.c) + "' has two evaluators");
  }
  st.evaluator_of_constraint[ev.c.index] = index;
  st.evaluate_step_of_evaluator[ev.e.index] = index;
}

void lower_evaluator(State& st, const EvaluatorTerms& t, TermId e) {
  st.pending_iri = st.str(e);
  auto c = st.object(e, t.constraint_p);
  if (!c) {
    st.error(e, "missing-property", "the evaluator '" + st.str(e) + "' names no constraint");
    return;
  }
  if (!st.defined(*c)) {
    st.error(st.graph.where(e, t.constraint_p, *c), "undefined-constraint",
             "the evaluator '" + st.str(e) + "' evaluates '" + st.str(*c) +
                 "', which no model file defines");
    return;
  }
  auto q = st.object(*c, t.quantity_p);
  if (!q) {
    st.error(*c, "missing-property", "the constraint '" + st.str(*c) + "' names no quantity");
    return;
  }
  const bool assignment = st.graph.has_type(e, t.assignment_evaluator);
  Step s = st.step_for(StepKind::Evaluate, e);
  const int quantity = st.datum(*q, DataType::Scalar, *c, "quantity");
  Evaluation ev{
      st,           t,          e,           *c,
      *q,           assignment, quantity,    st.program.data[static_cast<size_t>(quantity)].unit,
      std::move(s), {},         std::nullopt};
  if (read_constraint(ev)) add_evaluate_step(ev);
}

}  // namespace

void lower_evaluators(State& st) {
  const EvaluatorTerms t = evaluator_terms(st);
  // An evaluator that is also an assignment is lowered once, as an assignment
  // (its `error` is refused by lower_properties.cpp).
  std::vector<TermId> evals;
  for (TermId e : st.graph.instances(t.error_evaluator))
    if (!st.graph.has_type(e, t.assignment_evaluator)) evals.push_back(e);
  for (TermId a : st.graph.instances(t.assignment_evaluator)) evals.push_back(a);
  for (TermId e : evals) lower_evaluator(st, t, e);
}

void lower_monitors(State& st) {
  const std::string ch = "task/constraint-handler";
  for (const bool edge : {false, true}) {
    for (TermId m :
         st.instances(vocab(ch, edge ? "EdgeTriggeredMonitor" : "LevelTriggeredMonitor"))) {
      st.pending_iri = st.str(m);
      auto err = st.object(m, vocab(ch, "error"));
      auto out = st.object(m, vocab(ch, edge ? "event" : "flag"));
      if (!err || !out) {
        st.error(m, "missing-property",
                 std::string("the monitor '") + st.str(m) + "' needs `error` and `" +
                     (edge ? "event" : "flag") + "`");
        continue;
      }
      Step s;
      s.kind = edge ? StepKind::EdgeMonitor : StepKind::LevelMonitor;
      s.iri = st.str(m);
      s.name = local_name(s.iri);
      s.where = st.where(m);
      s.in = {st.datum(*err, DataType::Scalar, m, "error")};
      // The watched constraint's tolerance (via the evaluator producing the error).
      bool refused = false;
      for (const auto& [eval_term, step] : st.evaluate_step_of_evaluator) {
        const Step& ev = st.steps[static_cast<size_t>(step)];
        if (ev.out.size() < 2 || ev.out[1] != s.in[0]) continue;
        s.constraint = ev.constraint;
        if (const auto c = equality_without_tolerance(st, ev)) {
          st.error(st.where(m, vocab(ch, "error"), *err), "missing-tolerance",
                   "the monitor '" + st.str(m) +
                       "' watches the error of the equality constraint '" + st.str(*c) +
                       "', which states no tolerance: it would be satisfied only "
                       "while its quantity equals the reference exactly, so the monitor would "
                       "almost never " +
                       (edge ? "fire" : "raise its flag") +
                       "; state the constraint's `tolerance` (cstr-ext:tolerance, a quantity in "
                       "its unit: satisfied while |error| <= it)");
          refused = true;
        }
      }
      if (refused) continue;
      if (edge) {
        // The edges it reports (mos-grd:edge; rising when the model says none).
        if (auto e = st.object(m, vocab(kGuards, "edge"))) {
          const std::string edge_iri = st.str(*e);
          if (edge_iri == vocab(kGuards, "rising")) {
            s.edges = runtime::Edges::Rising;
          } else if (edge_iri == vocab(kGuards, "falling")) {
            s.edges = runtime::Edges::Falling;
          } else if (edge_iri == vocab(kGuards, "both")) {
            s.edges = runtime::Edges::Both;
          } else {
            st.error(st.where(m, vocab(kGuards, "edge"), *e), "invalid-monitor",
                     "the edge-triggered monitor '" + st.str(m) + "' reports the edge '" +
                         edge_iri +
                         "'; an edge is rising, falling or both (mos-grd:rising, "
                         "mos-grd:falling, mos-grd:both)");
            continue;
          }
        }
      }
      const int d = st.synthetic(st.str(*out), local_name(st.str(*out)),
                                 edge ? DataType::Event : DataType::Flag, st.where(*out));
      st.data_of[out->index] = d;
      s.out = {d};
      s.state = st.program.states[static_cast<int>(StateKind::Monitor)]++;
      st.monitor_step_of_monitor[m.index] = static_cast<int>(st.steps.size());
      st.add_step(std::move(s));
    }
  }
}

namespace {

// A pre- or post-condition that cannot do what its place says: an equality
// without a tolerance (held only at an instant), a less-than on the clock's
// time as a post-condition (it holds from the start), a constraint that is
// both a pre- and a post-condition (the motion would end as it starts).
void check_guard(State& st, TermId motion, const std::string& prop, TermId c,
                 const Step& evaluate) {
  const std::string mot = "task/motion-specification";
  const std::string where =
      "the motion '" + st.str(motion) + "' lists '" + st.str(c) + "' in `" + prop + "`";
  const SourceLoc at = st.where(motion, vocab(mot, prop), c);
  if (equality_without_tolerance(st, evaluate)) {
    st.error(at, "missing-tolerance",
             where +
                 "; an equality without a tolerance holds only while its quantity equals the "
                 "reference exactly, so the " +
                 (prop == "when" ? "motion would almost never start" : "motion would not end") +
                 "; state the constraint's `tolerance` (cstr-ext:tolerance, a quantity in its "
                 "unit: satisfied while |error| <= it), or guard with a BilateralConstraint or a "
                 "greater-/less-than constraint");
    return;
  }
  const auto q = st.object(c, vocab("task/constraint", "quantity"));
  if (prop == "until" && evaluate.constraint.kind == runtime::ConstraintKind::LessThan && q &&
      st.is_clock_time(*q)) {
    st.error(at, "invalid-guard",
             where + "; a less-than constraint on the clock's time '" + st.str(*q) +
                 "' holds from the first tick (the time starts at 0), so the motion would end as "
                 "it starts; a timeout is a GreaterThanConstraint (time > threshold)");
    return;
  }
  if (prop == "until") {
    for (TermId w : st.objects(motion, vocab(mot, "when"))) {
      if (w != c) continue;
      st.error(at, "invalid-guard",
               where +
                   " and in `when`: the motion would start and end in the same tick and "
                   "never run; a post-condition is what ends the motion, not what starts it");
    }
  }
}

// The quantities each motion acts on (motion term -> data): those the
// assignments of its handlers impose, and those of the constraints whose
// errors its handlers' controllers read.
// (Its maps and sets come from the lowering's arena, as lower_handlers'.)
std::pmr::map<uint32_t, std::pmr::set<int>> acted_on(State& st) {
  const std::string ch = "task/constraint-handler";
  // An error signal -> the quantity its evaluator's constraint constrains.
  std::pmr::map<int, int> quantity_of_error{&st.arena};
  for (const auto& [evaluator, step] : st.evaluate_step_of_evaluator) {
    const Step& ev = st.steps[static_cast<size_t>(step)];
    if (ev.constraint.kind != runtime::ConstraintKind::Assignment && ev.out.size() > 1)
      quantity_of_error[ev.out[1]] = ev.in[0];
  }
  std::pmr::map<uint32_t, std::pmr::set<int>> acted{&st.arena};
  for (TermId h : st.instances(vocab(ch, "ConstraintHandler"))) {
    const auto m = st.graph.object(h, st.term(vocab(ch, "motion")));
    if (!m) continue;
    std::pmr::set<int>& quantities = acted[m->index];
    for (TermId e : st.objects(h, vocab(ch, "evaluators"))) {
      const auto it = st.evaluate_step_of_evaluator.find(e.index);
      if (it == st.evaluate_step_of_evaluator.end()) continue;
      const Step& ev = st.steps[static_cast<size_t>(it->second)];
      if (ev.constraint.kind == runtime::ConstraintKind::Assignment) quantities.insert(ev.out[1]);
    }
    for (TermId k : st.objects(h, vocab(ch, "controllers"))) {
      st.graph.each_statement(k, [&](const Graph::Statement& s) {
        const auto d = st.data_of.find(s.object.index);
        if (d == st.data_of.end()) return;
        if (const auto q = quantity_of_error.find(d->second); q != quantity_of_error.end())
          quantities.insert(q->second);
      });
    }
  }
  return acted;
}

// The values of its quantity a constraint allows: [lo, hi] (closed: a bound
// is met at equality within a tolerance of 0).
struct Feasible {
  double lo = -INFINITY, hi = INFINITY;
};

Feasible feasible(const runtime::ConstraintSpec& c) {
  switch (c.kind) {
    case runtime::ConstraintKind::Equality:
      return {c.reference - c.tolerance, c.reference + c.tolerance};
    case runtime::ConstraintKind::Assignment:
      return {c.reference, c.reference};
    case runtime::ConstraintKind::LessThan:
      return {-INFINITY, c.threshold};
    case runtime::ConstraintKind::GreaterThan:
      return {c.threshold, INFINITY};
    case runtime::ConstraintKind::Bilateral:
      return {c.lower, c.upper};
  }
  return {};
}

// As a message says what a constraint allows: "= 0.3", "= 0.3 +- 0.01", "<= 2".
std::string allowed(const runtime::ConstraintSpec& c, const std::string& unit) {
  const std::string u = unit.empty() ? "" : " " + unit;
  switch (c.kind) {
    case runtime::ConstraintKind::Equality:
      return "= " + exact_number(c.reference) +
             (c.tolerance > 0.0 ? " +- " + exact_number(c.tolerance) : std::string()) + u;
    case runtime::ConstraintKind::Assignment:
      return "set to " + exact_number(c.reference) + u;
    case runtime::ConstraintKind::LessThan:
      return "<= " + exact_number(c.threshold) + u;
    case runtime::ConstraintKind::GreaterThan:
      return ">= " + exact_number(c.threshold) + u;
    case runtime::ConstraintKind::Bilateral:
      return "in [" + exact_number(c.lower) + ", " + exact_number(c.upper) + "]" + u;
  }
  return "";
}

const std::string kCh = "task/constraint-handler";
const std::string kMot = "task/motion-specification";

// A `while` constraint of a motion, on the quantity it constrains.
struct PerCondition {
  int quantity;
  TermId constraint;
  runtime::ConstraintSpec spec;
};

// The quantities each motion acts on (acted_on).
using ActedOn = std::pmr::map<uint32_t, std::pmr::set<int>>;

// A `while` constraint of the motion m: false when it is refused (reported).
// One on a quantity the motion acts on is what the motion enforces (its goal:
// sc1's tube, outside at the start); any other is an invariant, checked every
// tick.
bool check_per_condition(State& st, TermId m, TermId c, const Step& evaluate,
                         const ActedOn& acted) {
  const bool assignment = evaluate.constraint.kind == runtime::ConstraintKind::Assignment;
  const int quantity = assignment ? evaluate.out[1] : evaluate.in[0];
  if (const auto a = acted.find(m.index); a != acted.end() && a->second.count(quantity))
    return false;
  if (!equality_without_tolerance(st, evaluate)) return true;
  st.error(st.where(m, vocab(kMot, "while"), c), "missing-tolerance",
           "the motion '" + st.str(m) + "' lists '" + st.str(c) +
               "' in `while`; no controller or assignment of the motion acts on its "
               "quantity, so it is checked every tick, and an equality without a "
               "tolerance holds only while its quantity equals the reference "
               "exactly: the motion would be aborted at once; state the "
               "constraint's `tolerance` (cstr-ext:tolerance, a quantity in its unit: "
               "satisfied while |error| <= it)");
  return false;
}

// The satisfied flags of the constraints the motion m lists in `prop` (when,
// while, until); the `while` ones also into per_condition, as listed.
std::vector<int> guard_flags(State& st, TermId m, const std::string& prop, const ActedOn& acted,
                             std::vector<PerCondition>& per_condition) {
  std::vector<int> flags;
  for (TermId c : st.objects(m, vocab(kMot, prop))) {
    auto it = st.evaluator_of_constraint.find(c.index);
    if (it == st.evaluator_of_constraint.end()) {
      // An evaluator that names it was refused: reported there already.
      if (!st.graph.subjects(st.term(vocab(kCh, "constraint")), c).empty()) continue;
      st.error(st.where(m, vocab(kMot, prop), c), "unevaluated-constraint",
               "the motion '" + st.str(m) + "' lists '" + st.str(c) + "' in `" + prop +
                   "`, but no evaluator evaluates it");
      continue;
    }
    const Step& evaluate = st.steps[static_cast<size_t>(it->second)];
    if (prop == "while") {
      const bool assigned = evaluate.constraint.kind == runtime::ConstraintKind::Assignment;
      per_condition.push_back(
          {assigned ? evaluate.out[1] : evaluate.in[0], c, evaluate.constraint});
      if (!check_per_condition(st, m, c, evaluate, acted)) continue;
    } else {
      check_guard(st, m, prop, c, evaluate);
    }
    flags.push_back(evaluate.out[0]);
  }
  return flags;
}

// What the motion requires while it runs, on one quantity: the
// per-conditions' allowed values must overlap (pairwise suffices: if
// every two intervals meet, all of them do), or no state satisfies the
// motion and one of them is ignored whichever way the run goes.
void check_feasible(State& st, TermId m, const std::vector<PerCondition>& per_condition) {
  for (size_t i = 0; i < per_condition.size(); ++i) {
    for (size_t j = i + 1; j < per_condition.size(); ++j) {
      const PerCondition &a = per_condition[i], &b = per_condition[j];
      if (a.quantity != b.quantity) continue;
      const Feasible fa = feasible(a.spec), fb = feasible(b.spec);
      if (std::max(fa.lo, fb.lo) <= std::min(fa.hi, fb.hi)) continue;
      const Data& q = st.program.data[static_cast<size_t>(a.quantity)];
      st.error(st.where(a.constraint), "infeasible-motion",
               "the motion '" + st.str(m) + "' requires, while it runs, both '" +
                   st.str(a.constraint) + "' ('" + q.iri + "' " + allowed(a.spec, q.unit) +
                   ") and '" + st.str(b.constraint) + "' (" + allowed(b.spec, q.unit) + ", " +
                   st.place(b.constraint) +
                   "), which no value satisfies at once; change one of them, or make them "
                   "guards of different motions");
      st.errors.push_back(located(Severity::Note, st.where(b.constraint), st.model.files(),
                                  "infeasible-motion",
                                  "the other constraint of the motion '" + st.str(m) + "' on '" +
                                      q.iri + "': '" + st.str(b.constraint) + "'"));
    }
  }
}

// The GuardedMotion step of the motion m; its running flag, or nullopt when
// refused (reported).
std::optional<int> lower_motion(State& st, TermId m, const ActedOn& acted) {
  Step s = st.step_for(StepKind::GuardedMotion, m);
  std::vector<PerCondition> per_condition;  // the motion's `while`, as listed
  const std::vector<int> when = guard_flags(st, m, "when", acted, per_condition);
  const std::vector<int> whiles = guard_flags(st, m, "while", acted, per_condition);
  check_feasible(st, m, per_condition);
  const std::vector<int> until = guard_flags(st, m, "until", acted, per_condition);
  s.in = when;
  s.in.insert(s.in.end(), whiles.begin(), whiles.end());
  s.in.insert(s.in.end(), until.begin(), until.end());
  s.n_when = static_cast<int>(when.size());
  s.n_while = static_cast<int>(whiles.size());
  if (when.size() > static_cast<size_t>(kMaxGuards) ||
      whiles.size() > static_cast<size_t>(kMaxGuards) ||
      until.size() > static_cast<size_t>(kMaxGuards)) {
    st.error(m, "too-many-guards",
             "the motion '" + st.str(m) + "' has more than 16 when, checked while or until guards");
    return std::nullopt;
  }
  const int active = st.synthetic(st.str(m) + "#running", local_name(st.str(m)) + "_running",
                                  DataType::Flag, st.where(m));
  // How it ended, in the tick it ends (runtime::steps::MotionEnd).
  const int ended = st.synthetic(st.str(m) + "#ended", local_name(st.str(m)) + "_ended",
                                 DataType::Event, st.where(m));
  s.out = {active, ended};
  s.state = st.program.states[static_cast<int>(StateKind::Motion)]++;
  st.add_step(std::move(s));
  return active;
}

// The running flags of the motions whose handlers list each controller,
// evaluator and monitor (in order of term, so the program is a function of
// the model). (Scratch maps and sets: from the lowering's arena.)
struct HandledBy {
  explicit HandledBy(State& st)
      : controller(&st.arena), evaluator(&st.arena), monitor(&st.arena), handled(&st.arena) {}
  using Flags = std::pmr::map<TermId, std::pmr::set<int>>;
  Flags controller, evaluator, monitor;
  std::pmr::set<uint32_t> handled;  // motions some handler names
};

// Listed by the handlers of several motions: active while any of them runs.
int any_of(State& st, TermId entity, const std::pmr::set<int>& flags) {
  if (flags.size() == 1) return *flags.begin();
  Step s = st.step_for(StepKind::AnyOf, entity);
  s.name += "_active";
  s.in.assign(flags.begin(), flags.end());
  const int d = st.synthetic(st.str(entity) + "#active", local_name(st.str(entity)) + "_active",
                             DataType::Flag, st.where(entity));
  s.out = {d};
  st.add_step(std::move(s));
  return d;
}

// Assignments write, and monitors report, only while their motion runs (or
// one of their motions); a monitor no handler lists watches the whole run.
void gate_by_motions(State& st, const HandledBy& by) {
  for (const auto& [c, flags] : by.controller)
    st.active_of_controller[c.index] = any_of(st, c, flags);
  for (const auto& [e, flags] : by.evaluator) {
    const auto it = st.evaluate_step_of_evaluator.find(e.index);
    if (it == st.evaluate_step_of_evaluator.end()) continue;
    if (st.steps[static_cast<size_t>(it->second)].constraint.kind !=
        runtime::ConstraintKind::Assignment)
      continue;
    const int active = any_of(st, e, flags);  // may grow st.steps
    st.steps[static_cast<size_t>(it->second)].in.push_back(active);
  }
  for (const auto& [mon, flags] : by.monitor) {
    const auto it = st.monitor_step_of_monitor.find(mon.index);
    if (it == st.monitor_step_of_monitor.end()) continue;
    const int active = any_of(st, mon, flags);  // may grow st.steps
    st.steps[static_cast<size_t>(it->second)].in.push_back(active);
  }
}

// A motion no handler handles: nothing evaluates its guards, and it never runs.
void check_unhandled(State& st, const HandledBy& by) {
  for (TermId m : st.instances(vocab(kMot, "GuardedMotion"))) {
    if (by.handled.count(m.index)) continue;
    st.error(m, "unhandled",
             "no constraint handler handles the motion '" + st.str(m) +
                 "', so nothing evaluates its guards and it would never run; add a "
                 "ConstraintHandler whose `motion` is it, listing its evaluators and controllers");
  }
}

// An assignment no handler lists would write whatever the task does:
// refused, as the motion it serves is unknown. A controller no handler lists
// is refused only if a solver reads what it drives
// (settle_unlisted_controllers, once the schedule shows that): one a scenario
// leaves out of its handlers, e.g. of a shared file, is not used.
void check_unlisted(State& st, const HandledBy& by) {
  for (TermId e : st.instances(vocab(kCh, "AssignmentEvaluator")))
    if (!by.evaluator.count(e))
      st.error(e, "unhandled",
               "no constraint handler lists the assignment evaluator '" + st.str(e) +
                   "', so no motion says when it acts; list it in the `evaluators` of the "
                   "handler of each motion it serves");
  for (const ControllerKind& kind : controller_kinds())
    for (TermId c : st.instances(kind.class_iri()))
      if (!by.controller.count(c)) st.unlisted_controllers.insert(c.index);
}

}  // namespace

void lower_handlers(State& st) {
  HandledBy by(st);
  std::pmr::map<uint32_t, int> active_of_motion{&st.arena};
  const ActedOn acted = acted_on(st);
  for (TermId h : st.instances(vocab(kCh, "ConstraintHandler"))) {
    st.pending_iri = st.str(h);
    auto m = st.object(h, vocab(kCh, "motion"));
    if (!m) {
      st.error(h, "missing-property",
               "the constraint handler '" + st.str(h) +
                   "' names no motion: its evaluators and controllers would run whatever the "
                   "task does; name the motion they serve (`motion`)");
      continue;
    }
    by.handled.insert(m->index);
    int active = -1;
    if (auto it = active_of_motion.find(m->index); it != active_of_motion.end()) {
      active = it->second;
    } else if (const std::optional<int> running = lower_motion(st, *m, acted)) {
      active = *running;
      active_of_motion[m->index] = active;
    } else {
      continue;
    }
    for (TermId c : st.objects(h, vocab(kCh, "controllers"))) by.controller[c].insert(active);
    for (TermId e : st.objects(h, vocab(kCh, "evaluators"))) by.evaluator[e].insert(active);
    for (TermId e : st.objects(h, vocab(kCh, "monitors"))) by.monitor[e].insert(active);
  }
  check_unhandled(st, by);
  gate_by_motions(st, by);
  check_unlisted(st, by);
}

// A motion's goals: the `while` constraints on the quantities it acts on
// (lower_handlers leaves them to the motion's controllers and assignments
// rather than checking them every tick), then the constraints whose errors
// its controllers read. Each gets a tolerance: the model's, or the default of
// its unit (default_tolerance()), also for the monitors watching its error;
// the verdict judges every goal against it when the motion ends, and a
// one-sided row releases its bound within it (mark_one_sided).
void lower_goals(State& st) {
  const std::string ch = "task/constraint-handler";
  const std::string mot = "task/motion-specification";
  const std::pmr::map<uint32_t, std::pmr::set<int>> acted = acted_on(st);
  std::pmr::map<int, int> evaluate_of_error{&st.arena};  // error datum -> its Evaluate step
  for (const auto& [evaluator, step] : st.evaluate_step_of_evaluator) {
    const Step& ev = st.steps[static_cast<size_t>(step)];
    if (ev.constraint.kind != runtime::ConstraintKind::Assignment && ev.out.size() > 1)
      evaluate_of_error[ev.out[1]] = step;
  }
  std::pmr::map<uint32_t, std::pmr::vector<TermId>> handlers_of{&st.arena};
  for (TermId h : st.instances(vocab(ch, "ConstraintHandler")))
    if (const auto m = st.graph.object(h, st.term(vocab(ch, "motion"))))
      handlers_of[m->index].push_back(h);
  std::pmr::set<int> defaulted{&st.arena};  // Evaluate steps given a default tolerance
  for (Step& motion : st.steps) {
    if (role(motion) != StepRole::Motion) continue;
    const TermId m = st.term(motion.iri);
    std::vector<int> goals;  // Evaluate steps
    const auto add = [&](int step) {
      if (std::find(goals.begin(), goals.end(), step) == goals.end()) goals.push_back(step);
    };
    const auto a = acted.find(m.index);
    for (TermId c : st.objects(m, vocab(mot, "while"))) {
      const auto it = st.evaluator_of_constraint.find(c.index);
      if (it == st.evaluator_of_constraint.end() || a == acted.end()) continue;
      const Step& ev = st.steps[static_cast<size_t>(it->second)];
      if (ev.constraint.kind == runtime::ConstraintKind::Assignment) continue;
      if (a->second.count(ev.in[0])) add(it->second);
    }
    const auto n_whiles = goals.size();
    if (const auto hs = handlers_of.find(m.index); hs != handlers_of.end()) {
      for (TermId h : hs->second) {
        for (TermId k : st.objects(h, vocab(ch, "controllers"))) {
          st.graph.each_statement(k, [&](const Graph::Statement& s) {
            const auto d = st.data_of.find(s.object.index);
            if (d == st.data_of.end()) return;
            if (const auto e = evaluate_of_error.find(d->second); e != evaluate_of_error.end())
              add(e->second);
          });
        }
      }
    }
    // The controllers' in the order of their steps (the map's order is the model's).
    std::sort(goals.begin() + static_cast<std::ptrdiff_t>(n_whiles), goals.end());
    motion.goals.clear();
    for (int g : goals) {
      Step& ev = st.steps[static_cast<size_t>(g)];
      motion.goals.push_back(ev.out[0]);
      if (ev.tolerance_source != Step::Tolerance::None) continue;
      const auto tolerance = default_tolerance(st.program.data[static_cast<size_t>(ev.in[0])].unit);
      if (!tolerance) continue;  // the verdict says there is none
      ev.constraint.tolerance = *tolerance;
      ev.tolerance_source = Step::Tolerance::Default;
      defaulted.insert(g);
    }
    motion.n_goal_whiles = static_cast<int>(n_whiles);
  }
  // The monitors watching a goal's error use its tolerance (lower_monitors
  // copied the constraint before it had one).
  for (int g : defaulted) {
    const Step& ev = st.steps[static_cast<size_t>(g)];
    for (Step& monitor : st.steps) {
      if (role(monitor) == StepRole::Monitor && !monitor.in.empty() && monitor.in[0] == ev.out[1])
        monitor.constraint = ev.constraint;
    }
  }
}

}  // namespace mospec::ir::lowering
