// ccbuild: plans, schedules and runs the construction of buildings by Contour Crafting.
//
// Exit codes always hold (as VROOM's main does it): 0 success, 1 the answer is "no",
// 2 bad input or usage (InputError, CLI11's parse errors), 3 anything else (a broken
// invariant, an unexpected exception, even a crash), each with a message.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <cstring>
#include <exception>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace {
using namespace ccbuild::cli;

// The closest of `names` to `word`, when it is a near miss.
std::string closest(const std::string& word, const std::vector<std::string>& names) {
  return ccbuild::nearest_word(word, names, std::max<std::size_t>(3, word.size() / 3 + 1));
}

// "did you mean" for what CLI11 did not take: flags against the options of the command
// in use, a first word against the commands.
std::string suggestion(const CLI::App& app, const std::string& message, int argc, char** argv) {
  const CLI::App* command = &app;
  for (const CLI::App* sub : app.get_subcommands()) command = sub;
  std::vector<std::string> commands;
  for (const CLI::App* sub : app.get_subcommands({})) commands.push_back(sub->get_name());
  if (command == &app) {
    if (argc < 2 || argv[1][0] == '-') return "";
    const std::string best = closest(argv[1], commands);
    if (!best.empty()) return "did you mean '" + best + "'?";
    std::string list;
    for (const auto& n : commands) list += (list.empty() ? "" : ", ") + n;
    return "the commands are: " + list;
  }
  const std::string marker = "not expected: ";
  const auto at = message.find(marker);
  if (at == std::string::npos) return "";
  std::istringstream words(message.substr(at + marker.size()));
  std::vector<std::string> names;
  for (const CLI::Option* o : command->get_options())
    for (const auto& n : o->get_lnames()) names.push_back("--" + n);
  for (std::string word; words >> word;) {
    if (word.size() < 2 || word[0] != '-') continue;
    const std::string best = closest(word.substr(0, word.find('=')), names);
    if (!best.empty()) return "did you mean '" + best + "'?";
  }
  return "";
}

void print_json_error(const std::string& kind, int exit_code,
                      const std::vector<ccbuild::Diagnostic>& diagnostics) {
  nlohmann::ordered_json out;
  out["error"]["kind"] = kind;
  out["error"]["exit_code"] = exit_code;
  out["error"]["diagnostics"] = nlohmann::ordered_json::array();
  for (const auto& d : diagnostics)
    out["error"]["diagnostics"].push_back(
        {{"file", d.file}, {"line", d.line}, {"field", d.field}, {"message", d.message}});
  std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

// The last line of defence: a crash or a terminate still ends with exit code 3 and a
// message, never a bare signal (signal handlers may only use async-signal-safe calls).
extern "C" void on_fatal_signal(int signal_number) {
  const char* text = "ccbuild: internal error: fatal signal (a bug in ccbuild; please report it)\n";
  if (signal_number == SIGSEGV)
    text = "ccbuild: internal error: segmentation fault (a bug in ccbuild; please report it)\n";
  if (signal_number == SIGABRT)
    text = "ccbuild: internal error: aborted (a bug in ccbuild; please report it)\n";
  const ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
  ::_exit(kExitInternal);
}

void install_last_resorts() {
  std::set_terminate([] {
    std::fputs("ccbuild: internal error: unhandled exception (a bug in ccbuild)\n", stderr);
    std::_Exit(kExitInternal);
  });
  // A separate stack, so that even a stack overflow reaches the handler.
  static char alternate_stack[64 * 1024];
  stack_t ss{};
  ss.ss_sp = alternate_stack;
  ss.ss_size = sizeof alternate_stack;
  ::sigaltstack(&ss, nullptr);
  struct sigaction action {};
  action.sa_handler = on_fatal_signal;
  action.sa_flags = SA_ONSTACK;
  sigemptyset(&action.sa_mask);
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::sigaction(s, &action, nullptr);
  // A file-size limit (ulimit -f) makes a write fail with EFBIG, reported with its path,
  // instead of killing the process half-way through its outputs.
  ::signal(SIGXFSZ, SIG_IGN);
}

}  // namespace

int main(int argc, char** argv) {
  install_last_resorts();
  CLI::App app(
      "ccbuild plans, schedules and runs the construction of buildings by a Contour Crafting "
      "machine.\n"
      "Lengths inside are metres; files may say `units: ft`.\n"
      "Exit codes: 0 success; 1 the run worked but the answer is no (e.g. no collision-free "
      "plan); 2 bad input or usage; 3 internal error.\n"
      "Run `ccbuild COMMAND --help` for a command's options and examples.",
      "ccbuild");
  app.set_version_flag("--version", std::string("ccbuild ") + ccbuild::schedule::kCcbuildVersion);
  app.require_subcommand(1, 1);
  app.fallthrough(false);
  app.failure_message(
      [](const CLI::App*, const CLI::Error& error) { return std::string(error.what()); });

  int exit_code = kExitOk;
  add_validate_command(app, exit_code);
  add_import_command(app, exit_code);
  add_layers_command(app, exit_code);
  add_plan_layer_command(app, exit_code);
  add_sweep_command(app, exit_code);
  add_fit_command(app, exit_code);
  add_climb_command(app, exit_code);
  add_schedule_command(app, exit_code);
  add_diff_command(app, exit_code);
  add_report_command(app, exit_code);
  add_export_command(app, exit_code);
  add_dry_run_command(app, exit_code);
  add_study_command(app, exit_code);

  bool json = false;
  for (int k = 1; k < argc; ++k)
    if (std::strcmp(argv[k], "--json") == 0) json = true;

  try {
    // A hidden switch that proves a broken invariant ends as exit code 3 with a message.
    if (const char* probe = std::getenv("CCBUILD_SELFTEST_INTERNAL_CHECK");
        probe && std::strcmp(probe, "1") == 0)
      CCBUILD_CHECK(false, "self-test of the internal-error path");
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) {  // --help, --version
      app.exit(error);
      return kExitOk;
    }
    // CLI11 quotes what it could not take: a value of megabytes is cut short.
    std::string message = ccbuild::echoed(error.what(), 400);
    const std::string hint = ccbuild::echoed(suggestion(app, error.what(), argc, argv), 400);
    std::cerr << "ccbuild: error: " << message << (hint.empty() ? "" : "; " + hint) << "\n"
              << "Run 'ccbuild --help' or 'ccbuild COMMAND --help' for usage.\n";
    if (json)
      print_json_error("usage", kExitBadInput,
                       {{"", 0, "", message + (hint.empty() ? "" : "; " + hint)}});
    return kExitBadInput;
  } catch (const ccbuild::InputError& error) {
    std::vector<ccbuild::Diagnostic> diagnostics = error.diagnostics();
    for (auto& d : diagnostics) {
      if (d.file.empty()) d.field = flag_for_field(d.field);
      std::cerr << "ccbuild: error: " << d.to_string() << "\n";
    }
    if (json) print_json_error("input", kExitBadInput, diagnostics);
    return kExitBadInput;
  } catch (const ccbuild::schedule::NoFit& error) {
    // An answer, not bad input: no member of the family climbs this building.
    const auto& fit = error.fit;
    if (json) {
      std::vector<ccbuild::Diagnostic> reasons;
      for (const auto& reason : fit.reasons) reasons.push_back({"", 0, "", reason});
      if (!fit.nearest_change.empty())
        reasons.push_back({"", 0, "nearest_change", fit.nearest_change});
      print_json_error("no-fit", kExitNo, reasons);
      return kExitNo;
    }
    std::cout << "no fit: no member of the machine family climbs the building ("
              << ccbuild::climb::to_string(fit.status.code()) << ")\n";
    for (const auto& reason : fit.reasons) std::cout << "  " << reason << "\n";
    if (!fit.nearest_change.empty())
      std::cout << "  nearest change: " << fit.nearest_change << "\n";
    return kExitNo;
  } catch (const ccbuild::InternalError& error) {
    std::cerr << "ccbuild: internal error: " << error.what() << " (a bug in ccbuild)\n";
    if (json) print_json_error("internal", kExitInternal, {{"", 0, "", error.what()}});
    return kExitInternal;
  } catch (const std::bad_alloc&) {
    std::cerr << "ccbuild: internal error: out of memory\n";
    return kExitInternal;
  } catch (const std::exception& error) {
    std::cerr << "ccbuild: internal error: " << error.what() << "\n";
    if (json) print_json_error("internal", kExitInternal, {{"", 0, "", error.what()}});
    return kExitInternal;
  }
  return exit_code;
}
