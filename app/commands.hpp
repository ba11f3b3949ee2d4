#pragma once
// Each subcommand adds itself to the app; its callback sets `exit_code`.

#include <CLI/CLI.hpp>

namespace ccbuild::cli {

void add_validate_command(CLI::App& app, int& exit_code);
void add_layers_command(CLI::App& app, int& exit_code);
void add_plan_layer_command(CLI::App& app, int& exit_code);
void add_sweep_command(CLI::App& app, int& exit_code);
void add_climb_command(CLI::App& app, int& exit_code);
void add_fit_command(CLI::App& app, int& exit_code);
void add_schedule_command(CLI::App& app, int& exit_code);
void add_diff_command(CLI::App& app, int& exit_code);
void add_report_command(CLI::App& app, int& exit_code);
void add_export_command(CLI::App& app, int& exit_code);
void add_import_command(CLI::App& app, int& exit_code);
void add_dry_run_command(CLI::App& app, int& exit_code);
void add_study_command(CLI::App& app, int& exit_code);

}  // namespace ccbuild::cli
