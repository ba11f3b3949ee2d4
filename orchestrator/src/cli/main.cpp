// ccbuild: plans, schedules and runs the construction of buildings by Contour Crafting.

#include <CLI/CLI.hpp>
#include <iostream>

#include "ccbuild/common/input_error.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  using namespace ccbuild::cli;
  CLI::App app(
      "ccbuild plans, schedules and runs the construction of buildings by a Contour Crafting "
      "machine.\n"
      "Lengths inside are metres; files may say `units: ft`.\n"
      "Exit codes: 0 success; 1 the run worked but the answer is no (e.g. infeasible); 2 bad input "
      "or usage; 3 internal error.\n"
      "Run `ccbuild COMMAND --help` for a command's options and examples.",
      "ccbuild");
  app.set_version_flag("--version", "ccbuild 0.1.0");
  app.require_subcommand(1, 1);
  app.fallthrough(false);

  int exit_code = kExitOk;
  add_validate_command(app, exit_code);
  add_layers_command(app, exit_code);
  add_plan_layer_command(app, exit_code);
  add_sweep_command(app, exit_code);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? kExitOk : kExitBadInput;
  } catch (const ccbuild::InputError& error) {
    for (const auto& d : error.diagnostics())
      std::cerr << "ccbuild: error: " << d.to_string() << "\n";
    return kExitBadInput;
  } catch (const std::exception& error) {
    std::cerr << "ccbuild: internal error: " << error.what() << "\n";
    return 3;
  }
  return exit_code;
}
