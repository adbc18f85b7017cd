#include "cli/log_info.hpp"

#include <cmath>
#include <set>

#include "ir/lowering.hpp"

namespace mospec::cli {

plot::LogInfo log_info(const ir::Program& program) {
  plot::LogInfo info;
  for (const ir::LogColumn& c : program.log) info.units[c.name] = c.unit;
  // The satisfied flags a motion waits for (its `when` and `until`; its
  // `while` are goals it holds).
  std::set<int> guards;
  for (const ir::Step& s : program.steps) {
    if (ir::role(s) != ir::StepRole::Motion) continue;
    const auto n_when = static_cast<size_t>(s.n_when), n_while = static_cast<size_t>(s.n_while);
    for (size_t k = 0; k < s.in.size(); ++k)
      if (k < n_when || k >= n_when + n_while) guards.insert(s.in[k]);
  }
  for (const ir::Step& s : program.steps) {
    if (ir::role(s) != ir::StepRole::Constraint || s.out.empty()) continue;
    const std::string& flag = program.data[static_cast<size_t>(s.out[0])].iri;
    const std::string name = ir::lowering::local_name(flag.substr(0, flag.find('#')));
    const runtime::ConstraintSpec& spec = s.constraint;
    plot::ConstraintInfo c;
    c.relation = ir::relation_name(spec.kind);
    switch (spec.kind) {
      case runtime::ConstraintKind::Equality:
      case runtime::ConstraintKind::Assignment:
        c.reference = spec.reference;
        break;
      case runtime::ConstraintKind::LessThan:
        c.upper = spec.threshold;
        break;
      case runtime::ConstraintKind::GreaterThan:
        c.lower = spec.threshold;
        break;
      case runtime::ConstraintKind::Bilateral:
        c.lower = spec.lower;
        c.upper = spec.upper;
        break;
    }
    if (spec.kind != runtime::ConstraintKind::Assignment) c.tolerance = spec.tolerance;
    c.guard = guards.count(s.out[0]) > 0;
    info.constraints[name] = std::move(c);
  }
  return info;
}

nlohmann::ordered_json log_info_json(const plot::LogInfo& info) {
  using Json = nlohmann::ordered_json;
  Json units = Json::object();
  for (const auto& [column, unit] : info.units) units[column] = unit;
  Json constraints = Json::object();
  for (const auto& [name, c] : info.constraints) {
    Json x;
    x["relation"] = c.relation;
    const auto put = [&](const char* key, const std::optional<double>& v) {
      if (v && std::isfinite(*v)) x[key] = *v;
    };
    put("reference", c.reference);
    put("lower", c.lower);
    put("upper", c.upper);
    put("tolerance", c.tolerance);
    if (c.guard) x["guard"] = true;
    constraints[name] = std::move(x);
  }
  Json j;
  j["units"] = std::move(units);
  j["constraints"] = std::move(constraints);
  return j;
}

}  // namespace mospec::cli
