// Hostile input to the commands that read schedules back (report, diff, dry-run) and to
// every output path: the findings of the second mutation fuzz (issue 27), each refused
// with exit code 2, its message and its place, and no file changed.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "run_command.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::ordered_json;
using testing::contains;
using testing::run_shell;

// ccbuild ARGS under a deadline: a hang is a failure (exit code 124), not a stuck test.
testing::CommandResult run_bounded(const std::string& args, int seconds = 60) {
  return run_shell("timeout " + std::to_string(seconds) + " " + testing::ccbuild_binary() + " " +
                   args);
}

void expect_refused(const testing::CommandResult& r, const std::string& message,
                    const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err << r.out;
  EXPECT_TRUE(contains(r.err, "ccbuild: error: ")) << what;
  EXPECT_TRUE(contains(r.err, message)) << what;
  EXPECT_FALSE(contains(r.err, "internal error")) << what;
}

/// A folder of this test's files: copies of a plan, the bundled gantry (profile and URDF)
/// and the standard mix, so that nothing outside it can be damaged, and a schedule of them.
class Site {
 public:
  explicit Site(const std::string& name)
      : dir_(fs::temp_directory_path() /
             ("ccbuild_hostile_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    for (const auto& [from, to] : {std::pair{"tests/data/plans/cottage.yaml", "plan.yaml"},
                                   std::pair{"config/machines/cc-gantry.yaml", "cc-gantry.yaml"},
                                   std::pair{"config/machines/cc_gantry.urdf", "cc_gantry.urdf"},
                                   std::pair{"config/materials/standard-mix.yaml", "mix.yaml"}})
      fs::copy_file(testing::source_path(from), dir_ / to);
  }
  ~Site() { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string inputs() const {
    return path("plan.yaml") + " --machine " + path("cc-gantry.yaml") + " --material " +
           path("mix.yaml");
  }
  /// Schedules the plan to `name`; returns its path.
  std::string schedule(const std::string& name = "s.json") const {
    const auto r = run_bounded("schedule " + inputs() + " --quiet -o " + path(name));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return path(name);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return path(name);
  }
  std::string bytes(const std::string& name) const { return testing::slurp(dir_ / name); }

 private:
  fs::path dir_;
};

TEST(HostileInput, HandEditedSchedulesAreRefusedByReportDiffAndDryRun) {
  const Site site("edited");
  const std::string good = site.schedule();
  const std::string text = site.bytes("s.json");
  const json doc = json::parse(text);
  const std::string key = doc["layers"][0]["plan"];
  struct Edit {
    const char* name;
    std::function<std::string()> make;
    std::string message;
  };
  const auto edited = [&](const std::function<void(json&)>& f) {
    json d = doc;
    f(d);
    return d.dump(1) + "\n";
  };
  const Edit edits[] = {
      {"overlap",
       [&] {
         return edited([](json& d) {
           d["layers"][5]["start_s"] = d["layers"][5]["start_s"].get<double>() - 300.0;
           d["layers"][5]["end_s"] = d["layers"][5]["end_s"].get<double>() - 300.0;
         });
       },
       "/layers/5/start_s: one layer at a time"},
      {"nozzle count", [&] { return edited([](json& d) { d["layers"][3]["nozzles"] = 2; }); },
       "/layers/3/nozzles: nozzles: 2, but its plan"},
      {"missing key", [&] { return edited([](json& d) { d["layers"][3].erase("z_m"); }); },
       "/layers/3: \"z_m\" is missing"},
      {"wrong type",
       [&] {
         return edited(
             [&](json& d) { d["plans"][key]["nozzles"][0]["waypoints"][3]["x_m"] = "1.5"; });
       },
       "/plans/" + key + "/nozzles/0/waypoints/3/x_m: expected a number, got the string \"1.5\""},
      {"overflow",
       [&] {
         std::string t = text;
         const std::size_t at = t.find("\"makespan_s\": ") + 14;
         return t.replace(at, t.find(',', at) - at, "1e400");
       },
       "not valid JSON: number overflow"},
      {"deep nesting",
       [&] {
         std::string t = text;
         const std::size_t at = t.find("\"warnings\": [") + 13;
         return t.insert(at, std::string(100000, '[') + std::string(100000, ']'));
       },
       "nested more than 64 deep"},
      {"truncated", [&] { return text.substr(0, text.size() / 2); }, "not valid JSON"},
      // The dry-run's machines would load another file as their profile.
      {"machine profile not recorded",
       [&] { return edited([](json& d) { d["inputs"]["machine"]["profile"] = "/etc/passwd"; }); },
       "/inputs/machine/profile: expected one of the paths of /inputs/files, got "
       "\"/etc/passwd\""},
  };
  for (const Edit& e : edits) {
    SCOPED_TRACE(e.name);
    const std::string bad = site.write("bad.json", e.make());
    const std::string before = site.bytes("bad.json");
    const std::string html = site.path("out.html");
    for (const std::string& command :
         {"report " + bad + " -o " + html, "diff " + good + " " + bad, "diff " + bad + " " + good,
          "dry-run " + bad + " --lcm-url memq:// --timeout 5"}) {
      const auto r = run_bounded(command);
      expect_refused(r, bad + ":", command);
      expect_refused(r, e.message, command);
      EXPECT_FALSE(fs::exists(html)) << command;
      EXPECT_EQ(site.bytes("bad.json"), before) << command;
    }
  }
}

TEST(HostileInput, ASchedulesChangedInputIsNamed) {
  const Site site("changed");
  const std::string s = site.schedule();
  std::ofstream(site.path("mix.yaml"), std::ios::app) << "# edited after the schedule\n";
  const std::string html = site.path("out.html");
  // The dry-run runs its machines from the schedule's files, the report would draw a
  // schedule out of date: both refuse; diff, whose purpose is comparing schedules of
  // different inputs, names it.
  for (const std::string& command :
       {"report " + s + " -o " + html, "dry-run " + s + " --lcm-url memq:// --timeout 5"}) {
    const auto r = run_bounded(command);
    expect_refused(r, s + ": /inputs/files/", command);
    expect_refused(r, "mix.yaml changed since this schedule was made (SHA-256", command);
  }
  EXPECT_FALSE(fs::exists(html));
  const auto drawn = run_bounded("report " + s + " -o " + html + " --allow-changed-inputs");
  EXPECT_EQ(drawn.exit_code, 0) << drawn.err;
  EXPECT_TRUE(contains(drawn.err, "mix.yaml changed since this schedule was made"));
  EXPECT_TRUE(contains(testing::slurp(html), "mix.yaml changed since this schedule was made"));
  const auto diff = run_bounded("diff " + s + " " + s);
  EXPECT_EQ(diff.exit_code, 0) << diff.err;
  EXPECT_TRUE(contains(diff.out, "mix.yaml changed since this schedule was made"));
}

TEST(HostileInput, ASchedulePastTheSizeLimitIsRefusedAtOnce) {
  const Site site("big");
  const std::string big = site.write("big.json", "{");
  fs::resize_file(big, 257ull * 1024 * 1024);  // sparse: no disk used
  expect_refused(run_bounded("report " + big + " -o " + site.path("x.html"), 20),
                 "is 257 MiB; ccbuild reads schedules of at most 256 MiB", "257 MiB");
}

TEST(HostileInput, OutputsNeverReplaceWhatTheyShouldNot) {
  const Site site("outputs");
  const std::string s = site.schedule();
  const std::string plan = site.bytes("plan.yaml"), urdf = site.bytes("cc_gantry.urdf");
  // Two outputs on one file: the schedule would be lost under the report.
  const std::string both = site.path("both");
  fs::create_directories(site.path("sub"));
  expect_refused(
      run_bounded("schedule " + site.inputs() + " --quiet -o " + both + " --report " + both),
      "--report: is the same file as --output", "-o x --report x");
  EXPECT_FALSE(fs::exists(both));
  expect_refused(run_bounded("plan-layer " + site.path("plan.yaml") + " --svg " + both +
                             " --bound-certificate " + site.path("sub/../both")),
                 "--bound-certificate: is the same file as --svg", "--svg x --bound-certificate x");
  // An input, through a link or `..`.
  fs::create_symlink(site.path("plan.yaml"), site.path("link"));
  for (const std::string& out : {site.path("link"), site.path("sub/../plan.yaml")})
    expect_refused(run_bounded("schedule " + site.inputs() + " --quiet --force -o " + out),
                   "output would overwrite an input file", out);
  EXPECT_EQ(site.bytes("plan.yaml"), plan);
  // A FIFO is never replaced (nor waited on); a directory neither.
  const std::string fifo = site.path("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_refused(run_bounded("report " + s + " --force -o " + fifo, 20), "is a FIFO", "FIFO");
  EXPECT_TRUE(fs::is_fifo(fifo));
  expect_refused(run_bounded("report " + s + " --force -o " + site.path("sub")), "is a directory",
                 "folder");
  // A character device is never an output: refused before any work, the device kept.
  expect_refused(run_bounded("report " + s + " -o /dev/full"), "is a character device", "full");
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  const std::string device = site.path("null");
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {  // as root: /dev/null's
    expect_refused(run_bounded("report " + s + " --force -o " + device), "is a character device",
                   "a device made here");
    EXPECT_TRUE(fs::is_character_file(device));
    // The dry-run's journal on a device: refused before SQLite leaves a file beside it.
    expect_refused(run_bounded("dry-run " + s + " --lcm-url memq:// --journal " + device),
                   "--journal: is a character device", "journal on a device");
    EXPECT_FALSE(fs::exists(device + "-journal"));
    EXPECT_FALSE(fs::exists(device + "-wal"));
  }
  // A write that fails (a file-size limit, as a full disk) names the file, leaves nothing.
  const auto limited = run_shell("ulimit -f 64 && timeout 60 " + testing::ccbuild_binary() +
                                 " report " + s + " -o " + site.path("limited.html"));
  expect_refused(limited, "limited.html: cannot write output file: File too large", "ulimit -f");
  EXPECT_FALSE(fs::exists(site.path("limited.html")));
  // The dry-run's log: never an input (the schedule, the machine's profile or URDF, by any
  // path), never the journal, never a FIFO.
  for (const std::string& log :
       {s, site.path("cc_gantry.urdf"), site.path("cc-gantry.yaml"), site.path("sub/../s.json")})
    expect_refused(run_bounded("dry-run " + s + " --lcm-url memq:// --force --log " + log),
                   "--log: output would overwrite an input file", log);
  fs::create_symlink(site.path("cc_gantry.urdf"), site.path("urdf-link"));
  expect_refused(
      run_bounded("dry-run " + s + " --lcm-url memq:// --force --log " + site.path("urdf-link")),
      "--log: output would overwrite an input file", "link to the URDF");
  EXPECT_EQ(site.bytes("cc_gantry.urdf"), urdf);
  const std::string same = site.path("same");
  expect_refused(
      run_bounded("dry-run " + s + " --lcm-url memq:// --log " + same + " --journal " + same),
      "--journal: is the same file as --log", "log = journal");
  EXPECT_FALSE(fs::exists(same));
  expect_refused(run_bounded("dry-run " + s + " --lcm-url memq:// --force --log " + fifo, 20),
                 "--log: is a FIFO", "log on a FIFO");
  // --state-dir naming a file.
  const std::string notes = site.write("notes.txt", "precious");
  expect_refused(run_bounded("dry-run " + s + " --lcm-url memq:// --state-dir " + notes),
                 "--state-dir: exists and is not a folder", "state dir is a file");
  EXPECT_EQ(site.bytes("notes.txt"), "precious");
  // A state folder that cannot be made or written: refused before any machine starts (a
  // machine that cannot keep its record used to be restarted again and again).
  expect_refused(run_bounded("dry-run " + s + " --lcm-url memq:// --state-dir /proc/ccbuild-state"),
                 "--state-dir: cannot be made a folder", "state dir under /proc");
  expect_refused(run_bounded("dry-run " + s + " --lcm-url memq:// --journal /proc/ccbuild.journal"),
                 "--journal: cannot be written", "journal under /proc");
}

TEST(HostileInput, ExportsRefuseBadStartsAndNeverReplaceTheirSchedule) {
  const Site site("export");
  const std::string s = site.schedule();
  const std::string before = site.bytes("s.json");
  expect_refused(run_bounded("export " + s + " --format csv -o " + s + " --force"),
                 "output would overwrite an input file", "-o onto the schedule");
  EXPECT_EQ(site.bytes("s.json"), before);
  for (const std::string start : {"2027-02-29T07:00", "2027-03-01", "1970-12-31 23:59",
                                  "2201-01-01 00:00", "2027-03-01T24:00", "2027-03-01T07:00:00Z"})
    expect_refused(
        run_bounded("export " + s + " -o " + site.path("x.csv") + " --start '" + start + "'"),
        "--start: expected a local date and time", start);
  EXPECT_FALSE(fs::exists(site.path("x.csv")));
  expect_refused(run_bounded("export " + s + " --format mpp -o " + site.path("x.csv")), "--format",
                 "an unknown format");
  // A calendar and a project file need dates: without a site calendar, --start.
  for (const char* format : {"ical", "mspdi"}) {
    expect_refused(run_bounded("export " + s + " --format " + format + " -o " + site.path("x.ics")),
                   "--start: the schedule was made without a site calendar", format);
    EXPECT_FALSE(fs::exists(site.path("x.ics"))) << format;
  }
  // Both ends of the range (the end within the last year), and a leap day.
  for (const std::string start : {"1971-01-01T00:00", "2200-12-24 23:59:59", "2028-02-29 07:00"}) {
    const auto r = run_bounded("export " + s + " -o " + site.path("x.csv") + " --force --start '" +
                               start + "'");
    EXPECT_EQ(r.exit_code, 0) << start << r.err;
  }
  // A schedule on a site calendar is dated by it: --start is refused.
  const std::string dated = site.path("dated.json");
  const auto made =
      run_bounded("schedule " + site.inputs() + " --site " +
                  testing::source_path("config/sites/weekdays-berlin-2027.yaml").string() +
                  " --quiet -o " + dated);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  expect_refused(
      run_bounded("export " + dated + " -o " + site.path("y.csv") + " --start 2027-03-01T07:00"),
      "--start: the schedule has a site calendar", "--start on a calendar");
}

// `schedule --export` writes what `export` writes from the schedule it wrote, byte for byte;
// refused before any planning: a format that needs dates without a site calendar, an
// extension that names no format, an export onto an input.
TEST(HostileInput, ScheduleExportsAreExportsOfItsScheduleAndRefusedBeforePlanning) {
  const Site site("schedule-export");
  const std::string on_site =
      site.inputs() + " --site " +
      testing::source_path("config/sites/weekdays-berlin-2027.yaml").string() + " --quiet";
  const char* files[] = {"t.csv", "t.ics", "t.xml", "t.txt"};
  std::string exports;
  for (const char* f : files) exports += " --export " + site.path(f);
  const auto made = run_bounded("schedule " + on_site + " -o " + site.path("s.json") + exports);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  for (const char* f : files) {
    const std::string again = "again-" + std::string(f);
    const std::string format = std::string(f).substr(2) == "csv"   ? "csv"
                               : std::string(f).substr(2) == "ics" ? "ical"
                               : std::string(f).substr(2) == "xml" ? "mspdi"
                                                                   : "days";
    const auto r = run_bounded("export " + site.path("s.json") + " --format " + format + " -o " +
                               site.path(again));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(site.bytes(f), site.bytes(again)) << f;
    EXPECT_FALSE(site.bytes(f).empty()) << f;
  }
  // Without a site calendar: a CSV only.
  for (const char* f : {"u.ics", "u.xml", "u.txt"}) {
    expect_refused(run_bounded("schedule " + site.inputs() + " --quiet -o " + site.path("u.json") +
                               " --export " + site.path(f)),
                   "needs dates, and the building has no site calendar", f);
    EXPECT_FALSE(fs::exists(site.path("u.json"))) << f;
    EXPECT_FALSE(fs::exists(site.path(f))) << f;
  }
  const auto csv =
      run_bounded("schedule " + site.inputs() + " --quiet --export " + site.path("u.csv"));
  EXPECT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_TRUE(fs::exists(site.path("u.csv")));
  expect_refused(run_bounded("schedule " + on_site + " --export " + site.path("t.pdf")),
                 "the file's extension says what to export: .csv", "a .pdf");
  // The site's weather is a CSV the run reads: never written over, even with --force.
  const std::string weather =
      testing::slurp(testing::source_path("tests/data/weather/berlin-spring-2027.csv"));
  site.write("weather.csv", weather);
  site.write("site.yaml",
             "start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\nworking_hours: {mon-fri: "
             "07:00-17:00}\nweather: weather.csv\n");
  expect_refused(run_bounded("schedule " + site.inputs() + " --site " + site.path("site.yaml") +
                             " --quiet --force --export " + site.path("weather.csv")),
                 "output would overwrite an input file", "--export onto the weather");
  EXPECT_EQ(site.bytes("weather.csv"), weather);
}

TEST(HostileInput, DryRunFlagsAndFaultsAreCheckedAgainstTheMachinesAndTheSchedule) {
  const Site site("flags");
  const std::string s = site.schedule();
  const std::string dry = "dry-run " + s + " --lcm-url memq:// --timeout 5 ";
  const std::pair<std::string, std::string> cases[] = {
      {"--status-period 0.0005", "--status-period: must be from 0.001 to 86400 s"},
      {"--speed 2e9", "--speed: must be from 1 to 1e+09"},
      {"--inject pin=1001", "a count from 1 to 1000 expected in 'pin=1001'"},
      {"--inject clog=0:99999999999999999999", "FLOOR:LAYER expected"},
      {"--inject clog=gantry-9@0:1", "the schedule has no machine gantry-9 (it has gantry-1)"},
      {"--inject crash=gantry-2@1", "the schedule has no machine gantry-2"},
      {"--inject clog=9:0", "gantry-1 deposits nothing on floor 9 layer 0"},
      {"--inject clog=0:99", "gantry-1 deposits nothing on floor 0 layer 99"},
      {"--inject pin=1", "the schedule has no climbs, so no pin is ever inserted"},
      {"--inject stall=1e8", "before the stall"},
      {"--inject crash=100000", "never reaches its 100000-th"},
      {"--inject clog=0:1,clog=0:2", "clog on gantry-1 given twice"},
  };
  for (const auto& [flags, message] : cases)
    expect_refused(run_bounded(dry + flags), message, flags);
  // The machines' records: another schedule's, unnamed, or not a record at all.
  fs::create_directories(site.path("state"));
  const std::string state = " --state-dir " + site.path("state");
  site.write("state/gantry-1.state", "10 0 5 0 0 0 0\n");
  expect_refused(run_bounded(dry + state), "names no schedule (schedule.sha256)", "no marker");
  site.write("state/schedule.sha256", std::string(64, 'a') + "\n");
  expect_refused(run_bounded(dry + state), "holds the machines' records of another schedule",
                 "another schedule's records");
  const auto sum = run_shell("sha256sum " + s);
  site.write("state/schedule.sha256", sum.out.substr(0, 64) + "\n");
  site.write("state/gantry-1.state", "10 0 5 0 0 0 0\nnot a record\n");
  expect_refused(run_bounded(dry + state),
                 site.path("state/gantry-1.state") + ":2: expected 'job_id start_s end_s",
                 "garbage record");
  EXPECT_EQ(site.bytes("state/gantry-1.state"), "10 0 5 0 0 0 0\nnot a record\n");
}

TEST(HostileInput, AnInfeasibleScheduleIsNotDryRunUnlessAsked) {
  const Site site("infeasible");
  const std::string s = site.path("s.json");
  const auto r = run_bounded(
      "schedule tests/data/buildings/cottage.yaml --quiet --machine "
      "tests/data/machines/two-gantries.yaml --material "
      "tests/data/materials/two-gantry-mix.yaml -o " +
      s);
  ASSERT_EQ(r.exit_code, 1) << r.err << r.out;
  expect_refused(run_bounded("dry-run " + s + " --lcm-url memq:// --timeout 5"),
                 s + ": /feasible: the schedule is not feasible (floor", "infeasible");
}

}  // namespace
}  // namespace ccbuild
