// Lowering passes. Producers, the schedule (a topological order from sensor reads to actuator
// writes) and the log.
#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>

#include "ir/lowering.hpp"

namespace mospec::ir::lowering {

void check_inputs(State& st) {
  for (const Step& s : st.steps) {
    for (int d : s.in) {
      if (st.produced(d)) continue;
      const Data& dd = st.program.data[static_cast<size_t>(d)];
      // An inertia is a constant or refused where it is read (fill_inertia).
      if (dd.type == DataType::Inertia) continue;
      std::string msg = "nothing produces '";
      msg.append(dd.iri).append("', which '").append(s.iri).append("' needs");
      st.error(dd.where.known() ? dd.where : s.where, "unproduced-quantity", msg);
      st.producer.emplace(d, -1);  // report once
    }
  }
}

void schedule(State& st) {
  const size_t n = st.steps.size();
  // The edges producer -> reader, grouped by producer (offsets into `next`),
  // each group in the order of its readers.
  std::vector<size_t> from;  // per edge: the producing step
  std::vector<size_t> to;    // per edge: the reading step
  std::vector<int> waiting(n, 0);
  for (size_t i = 0; i < n; ++i) {
    for (int d : st.steps[i].in) {
      auto it = st.producer.find(d);
      if (it == st.producer.end() || it->second < 0) continue;
      from.push_back(static_cast<size_t>(it->second));
      to.push_back(i);
      ++waiting[i];
    }
  }
  std::vector<size_t> offset(n + 1, 0);
  for (size_t p : from) ++offset[p + 1];
  for (size_t i = 0; i < n; ++i) offset[i + 1] += offset[i];
  std::vector<size_t> next(from.size());
  {
    std::vector<size_t> fill(offset.begin(), offset.end() - 1);
    for (size_t e = 0; e < from.size(); ++e) next[fill[from[e]]++] = to[e];
  }
  // Kahn's algorithm, always taking the earliest-declared ready step: the
  // order is a function of the model only.
  std::priority_queue<size_t, std::vector<size_t>, std::greater<>> ready;
  for (size_t i = 0; i < n; ++i) {
    if (waiting[i] == 0) ready.push(i);
  }
  std::vector<size_t> order;
  order.reserve(n);
  while (!ready.empty()) {
    const size_t i = ready.top();
    ready.pop();
    order.push_back(i);
    for (size_t k = offset[i]; k < offset[i + 1]; ++k) {
      if (--waiting[next[k]] == 0) ready.push(next[k]);
    }
  }
  if (order.size() != n) {
    for (size_t i = 0; i < n; ++i) {
      if (waiting[i] > 0) {
        st.error(st.steps[i].where, "cycle",
                 "'" + st.steps[i].iri + "' (" + std::string(kind_name(st.steps[i])) +
                     ") is on a dependency cycle: each quantity on it needs another one of them in "
                     "the same tick");
      }
    }
    return;
  }
  // Moved: from here on only program.steps is read.
  st.program.steps.reserve(n);
  for (size_t i : order) st.program.steps.push_back(std::move(st.steps[i]));
}

// Each step's columns, as its kind logs them (StepKindInfo::log).
void build_log(State& st) {
  for (const Step& s : st.program.steps) {
    if (const LogHook log = info(s.kind).log) log(st.program, s, st.program.log);
  }
}

}  // namespace mospec::ir::lowering

namespace mospec::ir::lowering {

std::vector<char> steps_reaching_a_solver(const Program& program) {
  std::vector<char> reaches(program.data.size(), 0);  // a solver depends on the datum
  std::vector<char> effective(program.steps.size(), 0);
  for (size_t s = program.steps.size(); s-- > 0;) {
    const Step& step = program.steps[s];
    bool live = role(step) == StepRole::Solver;
    for (int o : step.out) live = live || reaches[static_cast<size_t>(o)];
    if (!live) continue;
    effective[s] = 1;
    for (int i : step.in) reaches[static_cast<size_t>(i)] = 1;
  }
  return effective;
}

// A controller no handler lists has no motion that says when it acts. If a
// solver reads what it drives, it would act whatever the task does: refused.
// Otherwise it is a definition the app does not use (a scenario that leaves a
// shared file's controller out of its handlers): it is switched off for good,
// by a constant "active" flag, and a note says so.
void settle_unlisted_controllers(State& st) {
  if (st.unlisted_controllers.empty()) return;
  const std::vector<char> reaching = steps_reaching_a_solver(st.program);
  int never = -1;
  for (size_t i = 0; i < st.program.steps.size(); ++i) {
    Step& s = st.program.steps[i];
    if (role(s) != StepRole::Controller || s.out.empty()) continue;
    if (!st.unlisted_controllers.count(st.term(s.iri).index)) continue;
    const std::string drives = st.program.data[static_cast<size_t>(s.out.front())].iri;
    if (reaching[i]) {
      st.error(s.where, "unhandled",
               "no constraint handler lists the controller '" + s.iri +
                   "', so no motion says when it acts, yet a solver reads what it drives ('" +
                   drives +
                   "'); list it in the `controllers` of the handler of each motion it serves");
      continue;
    }
    if (never < 0) {
      never = st.synthetic(st.program.app + "#never", "never", DataType::Flag, SourceLoc{});
      st.program.data[static_cast<size_t>(never)].value = {0.0};
    }
    s.in.push_back(never);
    st.note(s.where, "unused-controller",
            "the controller '" + s.iri + "' is not used: no constraint handler lists it and no " +
                "solver reads what it drives ('" + drives + "'), so it never acts");
  }
}

}  // namespace mospec::ir::lowering
