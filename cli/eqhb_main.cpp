// eqhb command line: solve a scene, list the solvers.
#include <CLI/CLI.hpp>
#include <iostream>

#include "eqhb/error.h"
#include "registry.h"
#include "solve_command.h"

int main(int argc, char** argv) {
  CLI::App app{"eqhb: periodic vibrations with dry friction and contact by equality-based harmonic balance"};
  app.require_subcommand(1);
  eqhb::cli::SolveArguments solve;
  eqhb::cli::addSolveCommand(app, solve);
  auto* solvers = app.add_subcommand("solvers", "List the registered solver backends");
  CLI11_PARSE(app, argc, argv);
  try {
    if (solvers->parsed()) {
      for (const auto& entry : eqhb::registeredSolvers())
        std::cout << entry.name << "\t" << entry.description << "\n";
      return 0;
    }
    return eqhb::cli::runSolve(solve);
  } catch (const eqhb::InputError& e) {
    std::cerr << "eqhb: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "eqhb: error: " << e.what() << "\n";
    return 2;
  }
}
