// Issue 49's findings on outputs, dates and messages, each from an input generated here:
// every file a command writes (derived names included) claimed before anything is written,
// never a file the run reads or its schedule records, never a device, all or nothing for
// the whole run; one strict date and clock reader; a family's bad key is bad input whatever
// the fit finds; a weather file named where the site names it; echoed values cut short.

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
namespace fs = std::filesystem;
using testing::contains;

testing::CommandResult ccbuild_run(const std::string& args, int seconds = 120) {
  return testing::run_shell("timeout " + std::to_string(seconds) + " " + testing::ccbuild_binary() +
                            " " + args);
}

void expect_refused(const testing::CommandResult& r, const std::string& message,
                    const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err << r.out;
  EXPECT_TRUE(contains(r.err, message)) << what;
  EXPECT_FALSE(contains(r.err, "internal error")) << what;
}

/// Every regular file under `dir` with its bytes, to show that a refused run changed none
/// and made none.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[e.path().string()] = testing::slurp(e.path());
  return files;
}

/// A folder of copies: the cottage's plan, the bundled gantry (profile and URDF) and mix.
class Folder {
 public:
  explicit Folder(const std::string& name) : dir_(testing::scratch_dir("outputs", name)) {
    for (const auto& [from, to] : {std::pair{"tests/data/plans/cottage.yaml", "plan.yaml"},
                                   std::pair{"config/machines/cc-gantry.yaml", "cc-gantry.yaml"},
                                   std::pair{"config/machines/cc_gantry.urdf", "cc_gantry.urdf"},
                                   std::pair{"config/materials/standard-mix.yaml", "mix.yaml"}})
      fs::copy_file(testing::source_path(from), dir_ / to);
  }
  ~Folder() { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string inputs() const {
    return path("plan.yaml") + " --machine " + path("cc-gantry.yaml") + " --material " +
           path("mix.yaml");
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return path(name);
  }
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
};

TEST(OutputRule, ReportAndExportNeverReplaceAnInputTheScheduleRecords) {
  const Folder f("recorded");
  const std::string s = f.path("s.json");
  ASSERT_EQ(ccbuild_run("schedule " + f.inputs() + " --quiet --no-compare -o " + s).exit_code, 0);
  const auto before = snapshot(f.dir());
  // The plan, the machine's profile and its URDF: the schedule records each; --force or not.
  for (const std::string name : {"plan.yaml", "cc-gantry.yaml", "cc_gantry.urdf", "mix.yaml"}) {
    expect_refused(ccbuild_run("report " + s + " --force -o " + f.path(name)),
                   "output would overwrite an input file", "report onto " + name);
    expect_refused(ccbuild_run("export " + s + " --format csv --force -o " + f.path(name)),
                   "output would overwrite an input file", "export onto " + name);
  }
  EXPECT_EQ(snapshot(f.dir()), before);
}

TEST(OutputRule, ADeviceIsRefusedBeforeAnyNameIsDerivedFromIt) {
  const Folder f("devices");
  const auto fit = ccbuild_run("fit config/buildings/house.yaml -o /dev/null --quiet");
  expect_refused(fit, "-o: is a character device", "fit -o /dev/null");
  EXPECT_FALSE(fs::exists("/dev/null.urdf"));
  const auto import = ccbuild_run(
      "import " + testing::source_path("tests/data/ifc/house_ifc4.ifc").string() + " -o /dev/full");
  expect_refused(import, "--output: is a character device", "import -o /dev/full");
  EXPECT_FALSE(fs::exists("/dev/full.1.plan.yaml"));
  EXPECT_FALSE(fs::exists("/dev/full.plan.yaml"));
}

TEST(OutputRule, ADerivedNameReplacesOnlyWhatTheSameCommandWroteThere) {
  const Folder f("derived");
  // A machine named like the one fit would write: its URDF is someone else's file.
  const std::string profile = f.path("cc_gantry.yaml");
  f.write("cc_gantry.yaml", "precious profile\n");
  const auto before = snapshot(f.dir());
  const std::string fit =
      "fit config/buildings/house.yaml --machine config/machines/cc-climber-family.yaml --quiet ";
  const auto r = ccbuild_run(fit + "--force -o " + profile);
  expect_refused(r, "cc_gantry.urdf: -o (its URDF): exists, and is not the file ccbuild wrote",
                 "fit over another URDF");
  EXPECT_EQ(snapshot(f.dir()), before);
  // Its own output, fitted again with --force: replaced, both files.
  const std::string mine = f.path("fitted.yaml");
  ASSERT_EQ(ccbuild_run(fit + "-o " + mine).exit_code, 0);
  const auto again = ccbuild_run(fit + "--force -o " + mine);
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(contains(testing::slurp(f.path("fitted.urdf")),
                       "<!-- ccbuild fit: the URDF of fitted.yaml -->"));
  // Without --force, nothing is replaced.
  expect_refused(ccbuild_run(fit + "-o " + mine), "output file exists; pass --force",
                 "fit again without --force");
}

TEST(OutputRule, AScheduleWhoseReportCannotBeWrittenLeavesNoneOfItsOutputs) {
  const Folder f("all-or-none");
  const std::string s = f.path("s.json"), report = f.path("r.html"), csv = f.path("t.csv");
  ASSERT_EQ(ccbuild_run("schedule " + f.inputs() + " --quiet --no-compare -o " + s).exit_code, 0);
  const auto json_bytes = fs::file_size(s);
  ASSERT_EQ(ccbuild_run("report " + s + " -o " + report).exit_code, 0);
  const auto report_bytes = fs::file_size(report);
  ASSERT_GT(report_bytes, json_bytes + 8192) << "the report is expected larger than the JSON";
  fs::remove(s);
  fs::remove(report);
  // Room for the schedule and the export, not for the report: nothing at all is written.
  const auto blocks = (json_bytes + 4096) / 1024 + 1;
  const auto r = testing::run_shell("ulimit -f " + std::to_string(blocks) + " && timeout 120 " +
                                    testing::ccbuild_binary() + " schedule " + f.inputs() +
                                    " --quiet --no-compare -o " + s + " --report " + report +
                                    " --export " + csv);
  expect_refused(r, "cannot write output file: File too large", "the report too large");
  EXPECT_FALSE(fs::exists(s));
  EXPECT_FALSE(fs::exists(report));
  EXPECT_FALSE(fs::exists(csv));
  for (const auto& e : fs::directory_iterator(f.dir()))
    EXPECT_FALSE(contains(e.path().filename().string(), ".tmp.")) << "left behind";
}

TEST(OutputRule, ExportDatesStayWithinTheYearsADateMayName) {
  const Folder f("dates");
  const std::string s = f.path("s.json");
  ASSERT_EQ(ccbuild_run("schedule " + f.inputs() + " --quiet --no-compare -o " + s).exit_code, 0);
  for (const std::string start : {"9999-12-31T23:59", "2201-01-01T07:00", "2027-03-+1T07:00",
                                  "2027- 3- 1 07:00", "2027-03-01T+7:+0", "2027-02-29T07:00"})
    expect_refused(ccbuild_run("export " + s + " --format csv -o " + f.path("t.csv") +
                               " --start '" + start + "'"),
                   "--start: expected a local date and time from 1971 to 2200", start);
  // The last day a date may name, late: the schedule's end would pass it.
  expect_refused(ccbuild_run("export " + s + " --format csv -o " + f.path("t.csv") +
                             " --start '2200-12-31T23:00'"),
                 "ends after 2200-12-31", "a start whose end passes the last year");
  EXPECT_FALSE(fs::exists(f.path("t.csv")));
  const auto ok = ccbuild_run("export " + s + " --format csv -o " + f.path("t.csv") +
                              " --start '2200-12-01T07:00'");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(OutputRule, SiteDatesAndClocksAreReadStrictly) {
  const Folder f("site");
  const std::map<std::string, std::string> bad = {
      {"start: 2027-03-+1 07:00", "start"},
      {"start: 2027- 3- 1 07:00", "start"},
      {"working_hours: {mon-fri: +7:+0-17:00}", "working_hours"},
      {"holidays: [2027-3-8]", "holidays"},
  };
  for (const auto& [line, key] : bad) {
    std::string text =
        "start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n"
        "working_hours: {mon-fri: 07:00-17:00}\n";
    const std::string key_line = key + ":";
    const std::size_t at = text.find(key_line);
    if (at != std::string::npos)
      text.replace(at, text.find('\n', at) - at, line);
    else
      text += line + "\n";
    const std::string site = f.write("site.yaml", text);
    const auto r = ccbuild_run("validate " + f.inputs() + " --site " + site);
    expect_refused(r, "site.yaml:", line);
    EXPECT_TRUE(contains(r.err, key)) << line;
  }
}

TEST(OutputRule, AWeatherFileThatCannotBeReadIsNamedWhereTheSiteNamesIt) {
  const Folder f("weather");
  const std::string site = f.write("site.yaml",
                                   "start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n"
                                   "working_hours: {mon-fri: 07:00-17:00}\n"
                                   "weather: no-such-weather.csv\n");
  const auto missing = ccbuild_run("validate " + f.inputs() + " --site " + site);
  expect_refused(missing, "site.yaml:4: weather: the weather file", "missing");
  EXPECT_TRUE(contains(missing.err, "no-such-weather.csv' does not exist"));
  fs::create_directories(f.path("no-such-weather.csv"));
  expect_refused(ccbuild_run("validate " + f.inputs() + " --site " + site),
                 "site.yaml:4: weather: the weather file", "a folder");
}

TEST(OutputRule, AFamilysBadKeyIsBadInputEvenWhenNoMemberFits) {
  const Folder f("family");
  std::string family =
      testing::slurp(testing::source_path("config/machines/cc-climber-family.yaml"));
  // The smallest family: the house does not fit it (an answer, exit 1) ...
  const std::size_t at = family.find("length_m: [6, 48]");
  ASSERT_NE(at, std::string::npos);
  family.replace(at, 17, "length_m: [6, 7]  ");
  const std::string small = f.write("small.yaml", family);
  const std::string fit =
      "fit config/buildings/house.yaml --quiet -o " + f.path("x.yaml") + " --machine ";
  EXPECT_EQ(ccbuild_run(fit + small).exit_code, 1);
  // ... but with a key out of its range it is bad input, named where it is written.
  const std::size_t speed = family.find("deposition_speed_m_s: 0.2");
  ASSERT_NE(speed, std::string::npos);
  family.replace(speed, 25, "deposition_speed_m_s: 900");
  const std::string bad = f.write("bad.yaml", family);
  const auto r = ccbuild_run(fit + bad);
  expect_refused(r, "bad.yaml:", "an out-of-range speed");
  EXPECT_TRUE(contains(r.err, "deposition_speed_m_s")) << r.err;
  EXPECT_FALSE(fs::exists(f.path("x.yaml")));
}

TEST(OutputRule, AnEchoedValueIsCutShort) {
  const Folder f("echo");
  // A 10 MB name where a unit is expected, in a plan file, and 100 kB in a flag.
  const std::string huge(10 * 1024 * 1024, 'u');
  std::string plan = testing::slurp(f.path("plan.yaml"));
  const std::size_t units = plan.find("units: m");
  ASSERT_NE(units, std::string::npos);
  plan.replace(units, 8, "units: " + huge);
  f.write("huge.yaml", plan);
  const auto r = ccbuild_run("validate " + f.path("huge.yaml"));
  expect_refused(r, "bytes in all", "a 10 MB unit");
  EXPECT_LT(r.err.size(), 4096u);
  const auto flag =
      ccbuild_run("validate " + f.path("plan.yaml") + " --units " + std::string(100 * 1024, 'f'));
  EXPECT_EQ(flag.exit_code, 2);
  EXPECT_LT(flag.err.size(), 4096u) << flag.err.substr(0, 300);
}

}  // namespace
}  // namespace ccbuild
