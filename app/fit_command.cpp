// ccbuild fit BUILDING --machine FAMILY.yaml -o fitted.yaml: the climbing machine of a
// family fitted to a building, written as a machine profile and its URDF.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/machine/climbing_family.hpp"
#include "ccbuild/report/climb_report.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct FitCommandOptions {
  std::string file;
  InputOptions input;
  std::string output;
  bool force = false;
  bool json = false;
  bool quiet = false;
};

void run_fit(const FitCommandOptions& o, int& exit_code) {
  InputOptions input = o.input;
  if (input.machine.empty())
    input.machine =
        (std::filesystem::path(CCBUILD_CONFIG_DIR) / "machines/cc-climber-family.yaml").string();
  const std::filesystem::path profile_path = o.output;
  const std::filesystem::path urdf_path =
      profile_path.parent_path() / (profile_path.stem().string() + ".urdf");
  // Both files claimed before the work, never over an input; the URDF's name is derived,
  // so a file there is replaced only when it is this profile's URDF from an earlier fit.
  const std::string urdf_mark =
      "<!-- ccbuild fit: the URDF of " + comment_text(profile_path.filename().string()) + " -->";
  OutputClaims claims({input.machine});
  claims.claim_file("-o", profile_path, o.force);
  claims.claim_derived("-o (its URDF)", urdf_path, profile_path, o.force, urdf_mark);
  schedule::ProjectOptions options = project_options(input);
  options.fitted_profile = profile_path;
  if (!o.quiet)
    options.progress = [](const std::string& what) { std::cerr << "fit: " << what << "\n"; };
  std::error_code ec;
  if (!std::filesystem::exists(o.file, ec)) throw InputError(o.file, 0, "", "file not found");
  const schedule::Project project = schedule::open_project(o.file, options);
  if (!project.fit)
    throw InputError(input.machine, 0, "",
                     "not a machine family (it has no `family:` section) but one machine: `ccbuild "
                     "fit` chooses a family's member for a building; give a family, such as "
                     "config/machines/cc-climber-family.yaml");
  for (const auto& input : project.files_read()) claims.add_input(input);
  const climb::FitResult& fit = *project.fit;
  // The mark after the XML declaration, which must come first.
  std::string urdf = fit.urdf_xml;
  const std::size_t declaration = urdf.rfind("?>", 64);
  urdf.insert(declaration == std::string::npos ? 0 : declaration + 3, urdf_mark + "\n");
  claims.write(urdf_path, urdf);
  claims.write(profile_path, fit.profile_yaml);
  claims.commit();
  exit_code = kExitOk;
  if (o.json) {
    std::cout << report::fit_json(project, fit, profile_path.string(), urdf_path.string())
                     .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
    return;
  }
  report::write_fit_text(std::cout, project, fit, input.machine);
  std::cout << "wrote " << profile_path.string() << " and " << urdf_path.string()
            << "; use it with --machine " << profile_path.string() << "\n";
}

}  // namespace

void add_fit_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<FitCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "fit",
      "Fit a climbing machine to a building: from a machine family (a profile with a "
      "`family:` section: platform size limits, how many units, where on the beams they may "
      "hang, the units' reach and stroke), choose the platform (its beams just outside the "
      "building's outermost walls on every storey) and the fewest units, mounted so that at "
      "every stage every unit's pin reaches solid wall (clear of wall ends and openings) and "
      "the platform stays statically stable by the profile's margin while printing and in "
      "every transfer. Writes the fitted profile and its URDF (for check_urdf, `climb` and "
      "`schedule`).\n"
      "`climb`, `schedule` and `validate` given a family fit it the same way on the fly.\n"
      "Exit code 1 when no member of the family climbs the building (the reason per stage and "
      "the nearest change that would fit are printed); 2 for bad input.\n"
      "Examples:\n"
      "  ccbuild fit config/buildings/house.yaml -o house-climber.yaml\n"
      "  ccbuild fit tower.yaml --machine config/machines/cc-climber-family.yaml -o tower.yaml "
      "--force\n"
      "  ccbuild climb config/buildings/house.yaml --machine house-climber.yaml");
  command->add_option("BUILDING", o->file, "Building file (or plan, IFC model)")->required();
  command
      ->add_option("-o,--output", o->output,
                   "The fitted profile to write (YAML); its URDF goes beside it, named after it "
                   "(fitted.yaml -> fitted.urdf)")
      ->required()
      ->check(output_path());
  command->add_flag("--force", o->force, "Overwrite existing output files (never an input)");
  command->add_flag("--json", o->json, "Print one JSON object (errors too)");
  command->add_flag("--quiet", o->quiet, "No progress on stderr");
  add_input_options(*command, o->input);
  command->callback([o, &exit_code] { run_fit(*o, exit_code); });
}

}  // namespace ccbuild::cli
