#include "verdict/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "robot/limits.hpp"

namespace mospec::verdict {

std::string console_number(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", x);
  return b;
}

namespace {

using Json = nlohmann::ordered_json;

std::string local_name(std::string_view iri) {
  const size_t k = iri.find_last_of("#/");
  return std::string(k == std::string_view::npos ? iri : iri.substr(k + 1));
}

// The IRI of what a synthetic datum belongs to ("<constraint>#satisfied").
std::string owner_iri(const std::string& iri) {
  return iri.substr(0, iri.find('#'));
}

const char* tolerance_source(ir::Step::Tolerance t) {
  switch (t) {
    case ir::Step::Tolerance::Stated:
      return "stated";
    case ir::Step::Tolerance::Default:
      return "default";
    case ir::Step::Tolerance::None:
      break;
  }
  return "none";
}

Json number_or_null(double x) {
  return std::isfinite(x) ? Json(x) : Json(nullptr);
}

// A motion's `.ended` code when a violated `while` aborted it
// (runtime::steps::MotionEnd::WhileViolated; sim::RunEvent::code).
constexpr int kWhileViolated = 2;

// The world's arm `a` by name (sim::RunResult::arms).
std::string arm_name(const sim::RunResult& r, size_t a) {
  return a < r.arms.size() ? r.arms[a] : "arm" + std::to_string(a);
}

}  // namespace

VerdictPlan plan_verdict(const ir::Program& program) {
  using ir::role;
  using ir::StepRole;
  VerdictPlan plan;
  // Log columns by datum (Value columns of a whole datum) and by name.
  std::map<int, size_t> column_of_data;
  std::map<std::string, size_t> column_of_name;
  for (size_t i = 0; i < program.log.size(); ++i) {
    const ir::LogColumn& c = program.log[i];
    column_of_name.emplace(c.name, i);
    if (c.component < 0 && c.kind == robot::LogColumnKind::Value) column_of_data.emplace(c.data, i);
  }
  std::map<int, const ir::Step*> producer;
  for (const ir::Step& s : program.steps) {
    for (int d : s.out) producer.emplace(d, &s);
  }
  const auto column = [&](const std::string& name) -> std::ptrdiff_t {
    const auto it = column_of_name.find(name);
    return it == column_of_name.end() ? -1 : static_cast<std::ptrdiff_t>(it->second);
  };
  // A guard: the satisfied flag of a constraint's evaluation.
  const auto guard = [&](int flag) -> std::optional<VerdictPlan::Guard> {
    const auto p = producer.find(flag);
    const auto c = column_of_data.find(flag);
    if (p == producer.end() || role(*p->second) != StepRole::Constraint ||
        c == column_of_data.end())
      return std::nullopt;
    const ir::Step& evaluate = *p->second;
    VerdictPlan::Guard g;
    g.constraint = owner_iri(program.data[static_cast<size_t>(flag)].iri);
    g.name = local_name(g.constraint);
    g.satisfied = c->second;
    const auto q = producer.find(evaluate.in[0]);
    g.timeout = evaluate.constraint.kind == runtime::ConstraintKind::GreaterThan &&
                q != producer.end() && role(*q->second) == StepRole::Clock;
    return g;
  };
  // The data read by controllers whose outputs reach a solver (through any
  // chain of steps; steps are in schedule order, so one backward pass finds
  // them): a controller reaching none acts on nothing (lowering warns,
  // controller-reaches-no-solver).
  std::set<int> read_by_controllers;
  {
    std::vector<char> reaches(program.data.size(), 0);
    for (size_t k = program.steps.size(); k-- > 0;) {
      const ir::Step& s = program.steps[k];
      bool live = role(s) == StepRole::Solver;
      for (int o : s.out) live = live || reaches[static_cast<size_t>(o)];
      if (!live) continue;
      for (int i : s.in) reaches[static_cast<size_t>(i)] = 1;
      if (role(s) == StepRole::Controller) read_by_controllers.insert(s.in.begin(), s.in.end());
    }
  }
  std::set<int> guard_flags, goal_flags;
  for (const ir::Step& s : program.steps) {
    switch (role(s)) {
      case StepRole::Motion: {
        VerdictPlan::Motion m;
        m.iri = s.iri;
        m.name = local_name(s.iri);
        const std::ptrdiff_t running = column(m.name + ".running");
        const std::ptrdiff_t ended = column(m.name + ".ended");
        if (running < 0 || ended < 0) break;
        m.running = static_cast<size_t>(running);
        m.ended = static_cast<size_t>(ended);
        const auto n_when = static_cast<size_t>(s.n_when);
        const auto n_while = static_cast<size_t>(s.n_while);
        m.has_when = n_when > 0;
        for (size_t k = 0; k < s.in.size(); ++k) {
          if (k < n_when || k >= n_when + n_while) guard_flags.insert(s.in[k]);
          if (k < n_when) continue;
          if (auto g = guard(s.in[k])) (k < n_when + n_while ? m.whiles : m.untils).push_back(*g);
        }
        for (size_t k = 0; k < s.goals.size(); ++k) {
          const auto p = producer.find(s.goals[k]);
          if (p == producer.end() || role(*p->second) != StepRole::Constraint) continue;
          const ir::Step& evaluate = *p->second;
          VerdictPlan::Goal g;
          g.constraint = owner_iri(program.data[static_cast<size_t>(s.goals[k])].iri);
          g.name = local_name(g.constraint);
          g.relation = std::string(ir::relation_name(evaluate.constraint.kind));
          g.unit = program.data[static_cast<size_t>(evaluate.in[0])].unit;
          g.spec = evaluate.constraint;
          g.tolerance_source = tolerance_source(evaluate.tolerance_source);
          g.is_while = k < static_cast<size_t>(s.n_goal_whiles);
          g.acted_on = evaluate.out.size() > 1 && read_by_controllers.count(evaluate.out[1]) > 0;
          // Read only by controllers that reach no solver: not enforced.
          if (!g.is_while && !g.acted_on) continue;
          const std::ptrdiff_t satisfied = column(g.name + ".satisfied");
          if (satisfied < 0) continue;
          g.satisfied = static_cast<size_t>(satisfied);
          g.value = column(g.name + ".value");
          g.error = column(g.name + ".error");
          goal_flags.insert(s.goals[k]);
          m.goals.push_back(std::move(g));
        }
        plan.motions.push_back(std::move(m));
        break;
      }
      case StepRole::Solver: {
        if (s.out.empty()) break;  // the base's: no degraded flag
        const std::string name = local_name(s.iri);
        if (const std::ptrdiff_t d = column(name + ".degraded"); d >= 0)
          plan.solvers.push_back({name, static_cast<size_t>(d)});
        break;
      }
      default:
        break;
    }
  }
  for (const ir::Step& s : program.steps) {
    if (role(s) != StepRole::Constraint) continue;
    VerdictPlan::Constraint c;
    c.iri = owner_iri(program.data[static_cast<size_t>(s.out[0])].iri);
    c.name = local_name(c.iri);
    c.relation = std::string(ir::relation_name(s.constraint.kind));
    const std::ptrdiff_t satisfied = column(c.name + ".satisfied");
    if (satisfied < 0) continue;
    c.satisfied = static_cast<size_t>(satisfied);
    c.value = column(c.name + ".value");
    if (s.constraint.kind != runtime::ConstraintKind::Assignment)
      c.error = column(c.name + ".error");
    c.guard = guard_flags.count(s.out[0]) > 0;
    c.goal = goal_flags.count(s.out[0]) > 0;
    c.tolerance = s.constraint.tolerance;
    c.tolerance_source = tolerance_source(s.tolerance_source);
    c.judged = s.constraint.kind != runtime::ConstraintKind::Equality || c.tolerance > 0.0;
    plan.constraints.push_back(std::move(c));
  }
  // The end effector's forces, traced back through their producers to the
  // logged values they are made of.
  for (const ir::ArmSolver& solver : program.arms) {
    if (solver.port < 0) continue;
    if (static_cast<size_t>(solver.port) >= plan.arms.size()) plan.arms.resize(solver.port + 1);
    VerdictPlan::Arm& arm = plan.arms[static_cast<size_t>(solver.port)];
    const int tip = solver.chain.size() - 1;
    for (const ir::CartesianForce& f : solver.cartesian_forces) {
      if (f.segment != tip) continue;
      std::set<size_t> found;
      std::set<int> seen;
      std::vector<int> todo{f.wrench};
      while (!todo.empty()) {
        const int d = todo.back();
        todo.pop_back();
        if (!seen.insert(d).second) continue;
        if (const auto c = column_of_data.find(d); c != column_of_data.end() && d != f.wrench) {
          found.insert(c->second);
          continue;
        }
        const auto p = producer.find(d);
        if (p == producer.end()) continue;
        if (role(*p->second) != StepRole::Computation) continue;
        for (int in : p->second->in) todo.push_back(in);
      }
      (found.empty() ? arm.unobserved : arm.forces).push_back(f.iri);
      arm.columns.insert(arm.columns.end(), found.begin(), found.end());
    }
    std::sort(arm.columns.begin(), arm.columns.end());
    arm.columns.erase(std::unique(arm.columns.begin(), arm.columns.end()), arm.columns.end());
  }
  return plan;
}

void watch_for_verdict(const VerdictPlan& plan, sim::RunOptions& options) {
  std::set<size_t> watch(options.watch.begin(), options.watch.end());
  for (const VerdictPlan::Motion& m : plan.motions) {
    watch.insert(m.running);
    for (const VerdictPlan::Guard& g : m.whiles) watch.insert(g.satisfied);
    for (const VerdictPlan::Guard& g : m.untils) watch.insert(g.satisfied);
  }
  options.watch.assign(watch.begin(), watch.end());
  options.snapshots.clear();
  options.held.clear();
  for (const VerdictPlan::Motion& m : plan.motions) {
    if (m.goals.empty()) continue;
    sim::RunOptions::Snapshot snapshot;
    snapshot.at = m.ended;
    for (const VerdictPlan::Goal& g : m.goals) {
      snapshot.columns.push_back(g.satisfied);
      for (const std::ptrdiff_t c : {g.value, g.error})
        if (c >= 0) snapshot.columns.push_back(static_cast<size_t>(c));
      options.held.push_back({g.satisfied, m.running});
    }
    options.snapshots.push_back(std::move(snapshot));
  }
  options.pushing.resize(std::max(options.pushing.size(), plan.arms.size()));
  for (size_t a = 0; a < plan.arms.size(); ++a) options.pushing[a] = plan.arms[a].columns;
}

namespace {

// A watched column's value after tick `tick` (0 before its first change), from
// RunResult::changes.
double watched_value(const sim::RunResult& r, size_t column, std::uint64_t tick) {
  double v = 0.0;
  for (const sim::RunChange& c : r.changes) {
    if (c.tick > tick) break;
    if (c.column == column) v = c.value;
  }
  return v;
}

// What a goal wants, as the console says it: "= 0.4926", "<= 0.4",
// "in [0.1, 0.2]".
std::string wanted(const VerdictPlan::Goal& g) {
  switch (g.spec.kind) {
    case runtime::ConstraintKind::Equality:
    case runtime::ConstraintKind::Assignment:
      return "= " + console_number(g.spec.reference);
    case runtime::ConstraintKind::LessThan:
      return "<= " + console_number(g.spec.threshold);
    case runtime::ConstraintKind::GreaterThan:
      return ">= " + console_number(g.spec.threshold);
    case runtime::ConstraintKind::Bilateral:
      return "in [" + console_number(g.spec.lower) + ", " + console_number(g.spec.upper) + "]";
  }
  return "?";
}

Json reference_json(const VerdictPlan::Goal& g) {
  switch (g.spec.kind) {
    case runtime::ConstraintKind::LessThan:
    case runtime::ConstraintKind::GreaterThan:
      return g.spec.threshold;
    case runtime::ConstraintKind::Bilateral:
      return Json::array({g.spec.lower, g.spec.upper});
    default:
      return g.spec.reference;
  }
}

// Where a goal's tolerance comes from, as the console says it.
std::string tolerance_text(const VerdictPlan::Goal& g) {
  if (g.tolerance_source == "none")
    return "no tolerance: the model states none and " + g.unit +
           " has no default; state its `tolerance`";
  return "tolerance " + console_number(g.spec.tolerance) + " " + g.unit + ", " +
         (g.tolerance_source == "stated" ? "stated" : "the default for " + g.unit);
}

}  // namespace

Verdict judge(const VerdictPlan& plan, const sim::RunResult& r) {
  Verdict v;
  Json& j = v.json;
  size_t pending_goals = 0;                  // not met by a motion still running at the end
  std::vector<std::string> pending_motions;  // those motions
  std::ostringstream text;
  std::ostringstream details;
  const auto last = [&](size_t column) {
    return column + 1 < r.last_row.size() ? r.last_row[column + 1] : std::nan("");
  };
  const std::uint64_t last_tick = r.ticks == 0 ? 0 : r.ticks - 1;
  // Changes are complete up to the tick of the last one kept.
  const auto known_at = [&](std::uint64_t tick) {
    return r.changes_dropped == 0 || (!r.changes.empty() && tick < r.changes.back().tick);
  };

  // The motion timeline.
  Json motions = Json::array();
  for (const VerdictPlan::Motion& m : plan.motions) {
    std::optional<std::uint64_t> start, end;
    std::optional<double> start_time, end_time;
    int code = 0;
    for (const sim::RunChange& c : r.changes) {
      if (c.column == m.running + 1 && c.value != 0.0) {
        start = c.tick;
        start_time = c.time;
        break;
      }
    }
    for (const sim::RunEvent& e : r.events) {
      if (e.column != m.ended + 1) continue;
      end = e.tick;
      end_time = e.time;
      code = e.code;
      break;
    }
    // A motion whose `until` holds in the tick it starts never shows running.
    if (end && !start) {
      start = end;
      start_time = end_time;
    }
    Json x;
    x["motion"] = m.iri;
    x["name"] = m.name;
    x["started_tick"] = start ? Json(*start) : Json(nullptr);
    x["started_time"] = start_time ? Json(*start_time) : Json(nullptr);
    x["ended_tick"] = end ? Json(*end) : Json(nullptr);
    x["ended_time"] = end_time ? Json(*end_time) : Json(nullptr);
    std::string ended_by, line = "  motion " + m.name + ": ";
    // The guards that held (an until) or did not (a while) in the end tick.
    Json guards = Json::array();
    std::vector<std::string> named;
    const auto which = [&](const std::vector<VerdictPlan::Guard>& list, bool held) {
      if (!end || !known_at(*end)) return;
      for (const VerdictPlan::Guard& g : list) {
        if ((watched_value(r, g.satisfied + 1, *end) != 0.0) != held) continue;
        Json gj;
        gj["constraint"] = g.constraint;
        gj["timeout"] = g.timeout;
        guards.push_back(std::move(gj));
        named.push_back(g.name + (g.timeout ? " (a timeout)" : ""));
      }
    };
    const auto joined = [&] {
      std::string s;
      for (size_t i = 0; i < named.size(); ++i) s += (i ? ", " : "") + named[i];
      return s.empty() ? std::string("(not recorded)") : s;
    };
    if (!start) {
      ended_by = "never-started";
      line += std::string("never started") + (m.has_when ? " (its `when` never held)" : "");
    } else {
      line += "ticks " + std::to_string(*start) + " to ";
      if (!end) {
        ended_by = "running";
        line += std::to_string(last_tick) + " (" + console_number(*start_time) + " s to " +
                console_number(r.simulated) + " s), still running when the run ended";
      } else {
        line += std::to_string(*end) + " (" + console_number(*start_time) + " s to " +
                console_number(*end_time) + " s), ";
        if (code == kWhileViolated) {
          ended_by = "while-violated";
          which(m.whiles, false);
          line += "ABORTED: its `while` " + joined() + " was violated";
          v.why.push_back("the motion '" + m.name + "' was aborted at tick " +
                          std::to_string(*end) + ": its `while` " + joined() + " was violated");
        } else {
          ended_by = "until";
          which(m.untils, true);
          line += "ended by its `until` " + joined();
        }
      }
    }
    x["ended_by"] = ended_by;
    if (ended_by == "until" || ended_by == "while-violated") x["guards"] = std::move(guards);
    details << line << '\n';
    motions.push_back(std::move(x));
  }
  j["motions"] = std::move(motions);
  if (r.changes_dropped > 0) j["watched_changes_not_listed"] = r.changes_dropped;

  // Every event (the summary's "events" lists them).
  j["events"] = r.events.size();
  {
    details << "  events: " << r.events.size() + r.events_dropped;
    constexpr size_t kShown = 8;
    for (size_t i = 0; i < r.events.size() && i < kShown; ++i) {
      const sim::RunEvent& e = r.events[i];
      const std::string& column = e.column < r.columns.size() ? r.columns[e.column] : "?";
      const bool motion = column.ends_with(".ended");
      const char* what = e.code == 1   ? (motion ? "until" : "rising")
                         : e.code == 2 ? (motion ? "while-violated" : "falling")
                                       : "both";
      details << (i ? "; " : ": ") << column << ' ' << what << " at tick " << e.tick;
    }
    if (r.events.size() + r.events_dropped > kShown)
      details << "; ... (the summary's `events` lists them)";
    details << '\n';
  }

  // Each motion's goals: judged when it ended (at the run's end while it
  // runs), and how its `while` goals held while it ran.
  Json goals = Json::array();
  {
    size_t snapshot = 0, held = 0;
    for (const VerdictPlan::Motion& m : plan.motions) {
      if (m.goals.empty()) continue;
      const sim::Snapshot* at = snapshot < r.snapshots.size() ? &r.snapshots[snapshot] : nullptr;
      ++snapshot;
      bool started = false;
      for (const sim::RunChange& c : r.changes) started = started || c.column == m.running + 1;
      const bool ended = at && at->taken;
      started = started || ended;
      std::string line = "  goals of " + m.name;
      if (!started) {
        line += ": not judged, the motion never started";
      } else if (ended) {
        line += " when it ended (tick " + std::to_string(at->tick) + ")";
      } else {
        line += " at the run's end (tick " + std::to_string(last_tick) +
                "; still running, judged when it ends)";
      }
      size_t met = 0, column = 0;
      std::vector<std::string> unmet, held_after, lapsed, never;
      for (const VerdictPlan::Goal& g : m.goals) {
        // Its values where it is judged: the snapshot's columns in their order.
        const auto value_at = [&](std::ptrdiff_t c) -> double {
          if (c < 0) return std::nan("");
          if (ended) return column < at->values.size() ? at->values[column++] : std::nan("");
          return last(static_cast<size_t>(c));
        };
        const double sat = value_at(static_cast<std::ptrdiff_t>(g.satisfied));
        const double value = value_at(g.value), error = value_at(g.error);
        const bool holds = sat != 0.0 && !std::isnan(sat);
        const sim::HeldRecord h = held < r.held.size() ? r.held[held] : sim::HeldRecord{};
        ++held;
        Json x;
        x["motion"] = m.iri;
        x["constraint"] = g.constraint;
        x["name"] = g.name;
        x["relation"] = g.relation;
        x["while"] = g.is_while;
        x["acted_on"] = g.acted_on;
        x["judged_at"] = !started ? Json(nullptr) : Json(ended ? "motion-end" : "run-end");
        x["judged"] = ended;
        x["tick"] = !started ? Json(nullptr) : Json(ended ? at->tick : last_tick);
        x["value"] = started ? number_or_null(value) : Json(nullptr);
        x["reference"] = reference_json(g);
        x["error"] = started ? number_or_null(error) : Json(nullptr);
        x["tolerance"] = g.spec.tolerance;
        x["tolerance_source"] = g.tolerance_source;
        x["unit"] = g.unit;
        x["met"] = started ? Json(holds) : Json(nullptr);
        x["running_ticks"] = h.during_ticks;
        x["held_ticks"] = h.held_ticks;
        x["first_held_tick"] = h.ever_held ? Json(h.first_held_tick) : Json(nullptr);
        x["lapses"] = h.lapses;
        x["lapsed_ticks"] = h.lapsed_ticks;
        x["first_lapse_tick"] = h.lapses ? Json(h.first_lapse_tick) : Json(nullptr);
        goals.push_back(std::move(x));
        if (!started) continue;
        if (holds) {
          ++met;
        } else {
          unmet.push_back(g.name + " = " + console_number(value) + " " + g.unit + " (wants " +
                          wanted(g) + ", error " + console_number(error) + "; " +
                          tolerance_text(g) + ")");
        }
        if (!g.is_while || h.during_ticks == 0) continue;
        const std::string who = g.name + (g.acted_on ? "" : " (no controller acts on it)");
        if (!h.ever_held) {
          never.push_back(who + " in " + std::to_string(h.during_ticks) + " ticks");
        } else if (h.lapses > 0) {
          lapsed.push_back(who + " " + std::to_string(h.lapses) + " time" +
                           (h.lapses == 1 ? "" : "s") + " from tick " +
                           std::to_string(h.first_lapse_tick) + " (" +
                           std::to_string(h.lapsed_ticks) + " ticks in all)");
        } else if (h.held_ticks < h.during_ticks) {
          held_after.push_back(who + " from tick " + std::to_string(h.first_held_tick));
        }
      }
      if (started) {
        line += ": " + std::to_string(met) + " of " + std::to_string(m.goals.size()) + " met";
        const char* what = ended ? "; NOT MET: " : "; not met yet: ";
        for (size_t i = 0; i < unmet.size(); ++i) line += (i ? "; " : what) + unmet[i];
        // A motion still running has not reached its end: its goals are due
        // then, and a run cut short of it does not fail on them.
        if (!ended && !unmet.empty()) {
          pending_goals += unmet.size();
          pending_motions.push_back(m.name);
        }
        if (ended && !unmet.empty()) {
          std::string why = "the motion '" + m.name + "' did not meet " +
                            std::to_string(unmet.size()) + " of its goals";
          for (size_t i = 0; i < unmet.size(); ++i)
            why += (i ? ", " : ": ") + unmet[i].substr(0, unmet[i].find(' '));
          v.why.push_back(why);
        }
      }
      details << line << '\n';
      size_t whiles = 0;
      for (const VerdictPlan::Goal& g : m.goals) whiles += g.is_while ? 1 : 0;
      if (whiles == 0 || !started) continue;
      const size_t throughout = whiles - held_after.size() - lapsed.size() - never.size();
      details << "  whiles of " << m.name << " while it ran: " << throughout << " of " << whiles
              << " held throughout";
      const auto list = [&](const char* what, const std::vector<std::string>& items) {
        for (size_t i = 0; i < items.size(); ++i) details << (i ? ", " : what) << items[i];
      };
      list("; held once reached: ", held_after);
      list("; LEFT after holding: ", lapsed);
      list("; never held: ", never);
      details << '\n';
    }
  }
  j["goals"] = std::move(goals);

  // Each constraint at the end.
  Json constraints = Json::array();
  size_t counted = 0, met = 0;
  std::vector<std::string> unmet, tracked;
  for (const VerdictPlan::Constraint& c : plan.constraints) {
    const double sat = last(c.satisfied);
    const bool holds = sat != 0.0 && !std::isnan(sat);
    Json x;
    x["constraint"] = c.iri;
    x["name"] = c.name;
    x["relation"] = c.relation;
    x["guard"] = c.guard;
    x["final_value"] =
        c.value >= 0 ? number_or_null(last(static_cast<size_t>(c.value))) : Json(nullptr);
    const double error = c.error >= 0 ? last(static_cast<size_t>(c.error)) : std::nan("");
    x["final_error"] = c.error >= 0 ? number_or_null(error) : Json(nullptr);
    x["satisfied"] = holds;
    x["goal"] = c.goal;
    x["tolerance"] = c.judged ? Json(c.tolerance) : Json(nullptr);
    x["tolerance_source"] = c.tolerance_source;
    x["judged"] = c.judged;
    constraints.push_back(std::move(x));
    if (c.guard || c.goal) continue;
    if (!c.judged) {
      tracked.push_back(c.name + " " + console_number(error));
      continue;
    }
    ++counted;
    if (holds) {
      ++met;
    } else {
      unmet.push_back(c.name + (c.error >= 0 ? " (error " + console_number(error) + ")" : ""));
    }
  }
  j["constraints"] = std::move(constraints);
  details << "  other constraints at the end (goals and guards aside): " << met << " of " << counted
          << " met";
  if (!unmet.empty()) {
    details << "; not met:";
    for (size_t i = 0; i < unmet.size(); ++i) details << (i ? ", " : " ") << unmet[i];
  }
  details << '\n';
  if (!tracked.empty()) {
    details << "  equalities without a tolerance (final error, not judged):";
    for (size_t i = 0; i < tracked.size(); ++i) details << (i ? ", " : " ") << tracked[i];
    details << '\n';
  }

  // Peak torque ratio per arm.
  Json peak;
  details << "  peak torque ratio |tau|/limit:";
  for (size_t a = 0; a < r.peak_torque_ratio.size(); ++a) {
    Json x;
    x["ratio"] = r.peak_torque_ratio[a];
    x["tick"] = r.peak_torque_tick[a];
    peak[arm_name(r, a)] = std::move(x);
    details << (a ? ", " : " ") << arm_name(r, a) << " arm "
            << console_number(r.peak_torque_ratio[a]) << " (tick " << r.peak_torque_tick[a] << ")";
  }
  details << '\n';
  j["peak_torque_ratio"] = std::move(peak);

  // Limit breaches: what the robot interface clamped, joints beyond their limits.
  Json breaches = Json::array();
  std::vector<std::string> breach_lines, clamped;
  std::uint64_t first_clamp = 0;
  for (const robot::ClampRecord& c : r.clamps) {
    if (c.ticks == 0) continue;
    Json x;
    x["limit"] = c.quantity;
    x["ticks"] = c.ticks;
    x["first_tick"] = c.first_tick;
    x["max_requested"] = number_or_null(c.max_requested);
    x["limit_value"] = c.limit;
    x["unit"] = c.unit;
    breaches.push_back(std::move(x));
    if (clamped.empty() || c.first_tick < first_clamp) first_clamp = c.first_tick;
    clamped.push_back(c.quantity);
  }
  if (!clamped.empty()) {
    constexpr size_t kNamed = 3;
    std::string line = "commands clamped from tick " + std::to_string(first_clamp) + " (";
    for (size_t i = 0; i < clamped.size() && i < kNamed; ++i) line += (i ? ", " : "") + clamped[i];
    if (clamped.size() > kNamed)
      line += " and " + std::to_string(clamped.size() - kNamed) + " more";
    breach_lines.push_back(line + ")");
  }
  if (r.joint_limit.ticks > 0) {
    const std::string name = arm_name(r, static_cast<size_t>(r.joint_limit.arm)) + "_arm.q[" +
                             std::to_string(r.joint_limit.joint) + "]";
    Json x;
    x["limit"] = "joint position";
    x["ticks"] = r.joint_limit.ticks;
    x["first_tick"] = r.joint_limit.first_tick;
    x["furthest"] = name;
    x["max_excess"] = r.joint_limit.max_excess;
    x["unit"] = "rad";
    breaches.push_back(std::move(x));
    breach_lines.push_back("a joint beyond its limits from tick " +
                           std::to_string(r.joint_limit.first_tick) + " (" +
                           std::to_string(r.joint_limit.ticks) + " ticks; furthest " + name + ", " +
                           console_number(r.joint_limit.max_excess) + " rad beyond)");
  }
  j["limit_breaches"] = std::move(breaches);
  details << "  limits:";
  if (breach_lines.empty()) details << " none breached";
  for (size_t i = 0; i < breach_lines.size(); ++i)
    details << (i ? "; " : " BREACHED: ") << breach_lines[i];
  details << '\n';
  if (!breach_lines.empty()) {
    std::string why = "a limit was breached:";
    for (size_t i = 0; i < breach_lines.size(); ++i)
      why += (i ? "; " : " ") + breach_lines[i].substr(0, breach_lines[i].find(" ("));
    v.why.push_back(why);
  }

  // Non-finite commands.
  {
    Json x;
    x["ticks"] = r.non_finite_ticks;
    x["first_tick"] = r.non_finite_ticks ? Json(r.first_non_finite_tick) : Json(nullptr);
    j["non_finite_commands"] = std::move(x);
    details << "  non-finite commands: ";
    if (r.non_finite_ticks == 0) {
      details << "none\n";
    } else {
      details << "in " << r.non_finite_ticks << " ticks from tick " << r.first_non_finite_tick
              << '\n';
      v.why.push_back("a command was not finite");
    }
  }

  // Degraded solves.
  {
    Json x = Json::object();
    std::string line;
    for (const VerdictPlan::Solver& s : plan.solvers) {
      const std::uint64_t ticks =
          s.degraded + 1 < r.columns.size() && s.degraded < r.flag_ticks.size()
              ? r.flag_ticks[s.degraded]
              : 0;
      x[s.name] = ticks;
      if (ticks > 0)
        line += (line.empty() ? " " : ", ") + s.name + " in " + std::to_string(ticks) + " ticks";
    }
    j["degraded_solves"] = std::move(x);
    details << "  degraded solves:" << (line.empty() ? " none" : line) << '\n';
  }

  // Contact lost while a force was commanded.
  {
    Json x;
    details << "  contact:";
    const VerdictPlan::Arm none;
    for (size_t a = 0; a < r.contact.size(); ++a) {
      const VerdictPlan::Arm& arm = a < plan.arms.size() ? plan.arms[a] : none;
      const sim::ContactRecord& c = r.contact[a];
      Json y;
      y["forces"] = arm.forces;
      if (!arm.unobserved.empty()) y["unobserved_forces"] = arm.unobserved;
      y["commanded_ticks"] = c.commanded_ticks;
      y["touching_ticks"] = c.touching_ticks;
      y["losses"] = c.losses;
      y["lost_ticks"] = c.lost_ticks;
      y["first_loss_tick"] = c.losses ? Json(c.first_loss_tick) : Json(nullptr);
      y["first_loss_time"] = c.losses ? Json(c.first_loss_time) : Json(nullptr);
      y["longest_loss_ticks"] = c.longest_loss;
      x[arm_name(r, a)] = std::move(y);
      details << (a ? "; " : " ") << arm_name(r, a) << " arm ";
      if (arm.forces.empty()) {
        details << (arm.unobserved.empty() ? "pushed nothing" : "pushes, not observed");
      } else if (c.commanded_ticks == 0) {
        details << "commanded no force";
      } else if (c.losses == 0) {
        details << (c.touching_ticks ? "kept it" : "never touched") << " while pushing ("
                << c.commanded_ticks << " ticks)";
      } else {
        details << "lost it " << c.losses << " time" << (c.losses == 1 ? "" : "s")
                << " while pushing (first at tick " << c.first_loss_tick << ", " << c.lost_ticks
                << " ticks in all, longest " << c.longest_loss << ")";
      }
    }
    details << '\n';
    j["contact"] = std::move(x);
  }

  if (r.instabilities > 0) {
    j["instabilities"] = r.instabilities;
    v.why.push_back("MuJoCo reported instabilities");
  }
  v.failed = !v.why.empty();
  j["status"] = v.failed ? "failed" : "ok";
  j["goals_not_met_yet"] = pending_goals;
  j["exit_status"] = v.failed ? 1 : 0;
  j["why"] = v.why;
  // The status first, in the object and on the console.
  Json ordered;
  ordered["status"] = j["status"];
  ordered["exit_status"] = j["exit_status"];
  ordered["why"] = j["why"];
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() != "status" && it.key() != "exit_status" && it.key() != "why")
      ordered[it.key()] = it.value();
  }
  j = std::move(ordered);
  text << "mospec: verdict: ";
  if (!v.failed && pending_goals > 0) {
    // "ok" means every goal is met: a run cut short of a motion's end has
    // not judged the goals that motion has not met yet.
    text << "ok so far: " << pending_goals << " goal(s) not met yet, as ";
    for (size_t i = 0; i < pending_motions.size(); ++i)
      text << (i ? ", " : "") << pending_motions[i];
    text << (pending_motions.size() == 1 ? " was" : " were")
         << " still running when the run ended (run longer to judge them)\n";
  } else if (!v.failed) {
    text << "ok\n";
  } else {
    text << "FAILED: ";
    for (size_t i = 0; i < v.why.size(); ++i) text << (i ? "; " : "") << v.why[i];
    text << '\n';
  }
  v.text = text.str() + details.str();
  return v;
}

// Each arm solve's `.degraded` column (ir::lowering::build_log) and the ticks
// it was raised, in log order.
std::vector<std::pair<std::string, std::uint64_t>> degraded_solves(const sim::RunResult& r) {
  constexpr std::string_view kSuffix = ".degraded";
  std::vector<std::pair<std::string, std::uint64_t>> out;
  // r.columns[0] is "t"; the controller's columns follow, as flag_ticks is indexed.
  for (size_t i = 0; i < r.flag_ticks.size() && i + 1 < r.columns.size(); ++i) {
    const std::string& name = r.columns[i + 1];
    if (name.size() > kSuffix.size() && name.ends_with(kSuffix))
      out.emplace_back(name.substr(0, name.size() - kSuffix.size()), r.flag_ticks[i]);
  }
  return out;
}

}  // namespace mospec::verdict
