// eqhb command line: solve a scene, list the solvers.
#include <CLI/CLI.hpp>
#include <iostream>

#include "eqhb/error.h"
#include "eqhb/io_error.h"
#include "eqhb/preload/static_contact.h"
#include "eqhb/solvers/deadline.h"
#include "eqhb/backends/registry.h"
#include "eqhb/version.h"
#include "flag_names.h"
#include "generate_command.h"
#include "modes_command.h"
#include "shoot_command.h"
#include "solve_command.h"
#include "study_command.h"
#include "sweep_command.h"
#include "terminal/verbosity.h"
#include "time_commands.h"

int main(int argc, char** argv) {
  CLI::App app{"eqhb: periodic vibrations with dry friction and contact by equality-based harmonic balance"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("eqhb ") + EQHB_VERSION);
  // Global switches are also accepted after the subcommand.
  app.fallthrough();
  eqhb::cli::addVerbosityOptions(app);
  eqhb::cli::SolveArguments solve;
  eqhb::cli::addSolveCommand(app, solve);
  auto* solvers = app.add_subcommand("solvers", "List the registered solver backends");
  eqhb::cli::SolveArguments simulate_hb, compare_hb;
  eqhb::cli::TimeArguments simulate_time, compare_time;
  eqhb::cli::addSimulateCommand(app, simulate_hb, simulate_time);
  eqhb::cli::addCompareCommand(app, compare_hb, compare_time);
  eqhb::cli::SolveArguments sweep_hb;
  eqhb::cli::SweepArguments sweep;
  eqhb::cli::addSweepCommand(app, sweep_hb, sweep);
  eqhb::cli::GenerateArguments generate;
  eqhb::cli::addGenerateCommand(app, generate);
  eqhb::cli::ShootArguments shoot;
  eqhb::cli::addShootCommand(app, shoot);
  eqhb::cli::ModesArguments modes;
  eqhb::cli::addModesCommand(app, modes);
  eqhb::cli::SolveArguments study_hb;
  eqhb::cli::StudyArguments study;
  eqhb::cli::addStudyCommand(app, study_hb, study);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end parsing with code 0; any other parse error is bad input,
    // which exits 2 like every other input error (CLI11's own codes are 100+).
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    if (solvers->parsed()) {
      for (const auto& entry : eqhb::registeredSolvers())
        std::cout << entry.name << "\t" << entry.description << "\n";
      return 0;
    }
    if (app.got_subcommand("simulate")) return eqhb::cli::runSimulate(simulate_hb, simulate_time);
    if (app.got_subcommand("generate")) return eqhb::cli::runGenerate(generate);
    if (app.got_subcommand("sweep")) return eqhb::cli::runSweep(sweep_hb, sweep);
    if (app.got_subcommand("shoot")) return eqhb::cli::runShoot(shoot);
    if (app.got_subcommand("modes")) return eqhb::cli::runModes(modes);
    if (app.got_subcommand("study")) return eqhb::cli::runStudy(study_hb, study);
    if (app.got_subcommand("compare")) return eqhb::cli::runCompare(compare_hb, compare_time);
    return eqhb::cli::runSolve(solve);
  } catch (const eqhb::InputError& e) {
    std::cerr << "eqhb: error: " << eqhb::cli::withFlagNames(e.what()) << "\n";
    return 2;
  } catch (const eqhb::IoError& e) {  // a file could not be written: not the input's fault
    std::cerr << "eqhb: I/O error: " << e.what() << "\n";
    return 3;
  } catch (const eqhb::StaticSolveFailed& e) {
    // Not bad input either: a static state exists and was not found.
    std::cerr << "eqhb: did not converge: " << e.what() << "\n";
    return 1;
  } catch (const eqhb::TimeLimitReached& e) {
    // Not bad input: stopped by --time-limit, like a solve that ran out of time.
    std::cerr << "eqhb: stopped: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "eqhb: error: " << eqhb::cli::withFlagNames(e.what()) << "\n";
    return 2;
  }
}
