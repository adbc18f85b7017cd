// `mospec sim`: run the simulated robot headless and log it.
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/faults.hpp"
#include "cli/numbers.hpp"
#include "cli/world_arms.hpp"
#include "description/base_rdf.hpp"
#include "description/robot_model.hpp"
#include "sim/config.hpp"
#include "sim/drivers.hpp"
#include "sim/log.hpp"
#include "sim/run.hpp"
#include "sim/world.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace mospec::cli {
Action add_sim_command(CLI::App& app) {
  struct Flags {
    std::string world;
    double duration = 5.0;
    std::string base;
    std::string log;
    std::optional<std::uint64_t> seed;
    std::string controller = "gravity";
    int log_every = 1;
    bool mount = false;
    std::vector<std::string> faults;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand("sim", kSimSummary);
  cmd->add_option("world", flags->world, "World file (JSON)")->type_name("WORLD");
  cmd->add_option("--duration", flags->duration,
                  "Simulated time [s], in (0, 86400] and at most 10^7 control ticks")
      ->check(finite_number(0.0, 86400.0, true, "s"))
      ->capture_default_str();
  cmd->add_option("--base", flags->base, "Base model (overrides the world file)")
      ->check(CLI::IsMember({"wheeled", "planar", "fixed"}));
  cmd->add_option("--log", flags->log, "CSV log file ('-' = standard output)")
      ->type_name("FILE.csv");
  cmd->add_option("--log-every", flags->log_every, "Log every N-th control tick")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--seed", flags->seed,
                  "Seed of the initial perturbations, 0..2^53 (overrides the file)")
      ->check(integer_in(0, kMaxSeed));
  cmd->add_option("--controller", flags->controller, "Arm controller")
      ->check(CLI::IsMember({"zero", "gravity"}))
      ->capture_default_str();
  cmd->add_flag("--mount", flags->mount, "Activate SC2's end-effector mounts to the table");
  cmd->add_option("--fault", flags->faults, kFaultHelp)->type_name("SPEC");

  return [flags]() {
    sim::WorldConfig config =
        flags->world.empty() ? sim::default_world() : sim::load_world_config(flags->world);
    if (!flags->base.empty()) config.base = *sim::parse_base_fidelity(flags->base);
    if (flags->seed) config.seed = *flags->seed;
    if (flags->mount) config.mount.active = true;
    config.drives =
        description::load_base(config.base_model.model, config.base_model.configuration);
    std::vector<runtime::Chain> chains = arm_chains(config, nullptr);
    sim::actuation_from_chains(config, chains);
    sim::World world(config, std::move(chains));
    for (const std::string& f : flags->faults) add_fault(world.faults(), f);
    std::vector<runtime::Pose> X_PB;
    for (const sim::ArmSetup& a : config.arms) X_PB.push_back(a.X_PB);
    sim::GravityCompensation gravity(world.arms(), X_PB);
    const bool compensate = flags->controller == "gravity";
    sim::CsvLog log(world);
    const bool logging = !flags->log.empty();

    const std::uint64_t ticks =
        sim::tick_count(flags->duration, config.control_period,
                        logging ? static_cast<std::uint64_t>(flags->log_every) : 0);
    robot::MeasuredState state = world.make_state();
    robot::Command command = world.make_command();
    const auto start = std::chrono::steady_clock::now();
    for (std::uint64_t k = 0; k < ticks; ++k) {
      world.read(state);
      if (compensate) gravity.compute(state, command);
      world.write(command);
      if (logging && k % static_cast<std::uint64_t>(flags->log_every) == 0) log.record(world);
      world.step();
    }
    if (logging) log.record(world);  // the final state
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (logging) write_output(flags->log, log.text());

    std::cerr << "mospec: simulated " << world.time() << " s (" << ticks << " ticks, "
              << sim::to_string(config.base) << " base, " << flags->controller << " controller) in "
              << wall << " s";
    if (wall > 0) std::cerr << " (" << std::round(world.time() / wall) << "x real time)";
    std::cerr << '\n';
    const bool clamped = sim::report_clamps(std::cerr, world.limiter().records());
    if (world.instabilities() > 0) {
      std::cerr << "mospec: error: MuJoCo reported " << world.instabilities()
                << " instability or capacity warning(s); the log is not trustworthy\n";
      return kExitFindings;
    }
    return clamped ? kExitFindings : kExitOk;
  };
}

}  // namespace mospec::cli
