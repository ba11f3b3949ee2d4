// read_schedule: a schedule's JSON read back into the model gives the same bytes when
// written again; a hand-edited one that breaks a rule, a type or a limit is refused with
// the file, the line, the JSON pointer and the rule; its recorded inputs are compared with
// the files on disk.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/schedule_diff.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "test_support.hpp"

namespace ccbuild::schedule {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

std::string golden_text(const std::string& name) {
  return testing::slurp(testing::source_path("tests/regression/" + name + ".schedule.json"));
}

std::string text_of(const json& doc) {
  return doc.dump(1) + "\n";
}

/// The house's golden schedule edited by `edit`, then parsed: the error it gives.
InputError refusal(const std::function<void(json&)>& edit) {
  json doc = json::parse(golden_text("house"));
  edit(doc);
  const std::string text = text_of(doc);
  return testing::expect_input_error([&] { parse_schedule(text, "house.json"); });
}

/// The 1-based line of the first line of `text` holding `part`, after line `from`.
int line_holding(const std::string& text, const std::string& part, int from = 0) {
  int line = 1;
  for (std::size_t at = 0; at < text.size(); ++line) {
    const std::size_t end = text.find('\n', at);
    if (line > from && text.substr(at, end - at).find(part) != std::string::npos) return line;
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return 0;
}

TEST(ReadSchedule, WritingWhatWasReadGivesTheSameBytes) {
  // The house's golden keeps its paths; the others their digests (--path-digests).
  for (const char* name : {"house", "apartment", "tower"}) {
    const std::string text = golden_text(name);
    const ScheduleDocument doc = parse_schedule(text, name, true);
    EXPECT_EQ(schedule_json(doc.inputs, doc.schedule).dump(1) + "\n", text) << name;
    EXPECT_FALSE(diff_schedules(doc, parse_schedule(text, name, true), {}).differs()) << name;
  }
}

TEST(ReadSchedule, PathDigestsStandForThePathsInDiffOnly) {
  const std::string text = golden_text("house");
  const ScheduleDocument full = parse_schedule(text, "house");
  ScheduleJsonOptions digests;
  digests.path_digests = true;
  const std::string small = schedule_json(full.inputs, full.schedule, digests).dump(1) + "\n";
  // The plans, where the paths are, shrink to under a third.
  const auto plans_size = [](const std::string& json_text) {
    return nlohmann::json::parse(json_text)["plans"].dump(1).size();
  };
  EXPECT_LT(plans_size(small), plans_size(text) / 3);
  EXPECT_LT(small.size(), text.size());
  // Read back and written again: the same bytes; compared with the full one: the same.
  const ScheduleDocument golden = parse_schedule(small, "small.json", true);
  EXPECT_EQ(schedule_json(golden.inputs, golden.schedule).dump(1) + "\n", small);
  EXPECT_FALSE(diff_schedules(golden, full, {}).differs());
  EXPECT_FALSE(diff_schedules(full, golden, {}).differs());
  // One waypoint a micrometre off: its plan's digest no longer matches.
  ScheduleDocument moved = full;
  auto& plan = moved.schedule.plans.begin()->second;
  plan.waypoints[0][3].position_m.x() += 1e-6;
  const ScheduleDiff d = diff_schedules(golden, moved, {});
  EXPECT_EQ(d.differing_plans, 1);
  EXPECT_TRUE(testing::contains(d.changes.back(), "plan " + plan.key + ": its timed paths differ"));
  // Commands that need the paths refuse it, naming where.
  const InputError e = testing::expect_input_error([&] { parse_schedule(small, "small.json"); });
  EXPECT_EQ(e.first().field, "/plans/" + plan.key + "/nozzles/0/waypoints_digest");
  EXPECT_TRUE(testing::contains(e.what(), "keeps its paths' digests only"));
}

TEST(ReadSchedule, TheModelIsTyped) {
  const ScheduleDocument doc = parse_schedule(golden_text("tower"), "tower", true);
  EXPECT_TRUE(doc.schedule.feasible);
  EXPECT_EQ(doc.schedule.layers.size(), 250u);
  EXPECT_TRUE(doc.inputs.machine.climbing);
  EXPECT_EQ(doc.inputs.machine.rail_axis, machine::RailAxis::kX);
  EXPECT_EQ(doc.inputs.unit_names.size(), 4u);
  EXPECT_FALSE(doc.schedule.stages.empty());
  int climbs = 0;
  for (const auto& e : doc.schedule.events)
    if (e.kind == Event::Kind::kClimb) {
      ++climbs;
      ASSERT_TRUE(e.climb);
      EXPECT_FALSE(e.climb->plan.phases.empty());
    }
  EXPECT_EQ(climbs, 9);
}

TEST(ReadSchedule, ALayerMovedOntoTheOneBeforeIsRefused) {
  // Moved 300 s earlier: it overlaps the layer before it.
  const InputError e = refusal([](json& d) {
    d["layers"][5]["start_s"] = d["layers"][5]["start_s"].get<double>() - 300.0;
    d["layers"][5]["end_s"] = d["layers"][5]["end_s"].get<double>() - 300.0;
  });
  EXPECT_TRUE(testing::contains(e.what(), "/layers/5/start_s: one layer at a time"));
  EXPECT_EQ(e.first().file, "house.json");
  EXPECT_GT(e.first().line, 0);
}

TEST(ReadSchedule, ALayerMovedLaterIsRefusedByItsIntervals) {
  // Later by 300 s: no overlap, but its waits and intervals no longer add up.
  const InputError e = refusal([](json& d) {
    for (std::size_t k = 6; k < d["layers"].size(); ++k) {
      d["layers"][k]["start_s"] = d["layers"][k]["start_s"].get<double>() + 300.0;
      d["layers"][k]["end_s"] = d["layers"][k]["end_s"].get<double>() + 300.0;
    }
  });
  EXPECT_TRUE(testing::contains(e.what(), "/layers/6/start_s: one layer at a time"));
  EXPECT_TRUE(testing::contains(e.what(), "/layers/6/local_interval_min_s: local intervals"));
}

TEST(ReadSchedule, ANozzleCountThatIsNotItsPlansIsRefused) {
  const InputError e = refusal([](json& d) { d["layers"][3]["nozzles"] = 2; });
  EXPECT_TRUE(testing::contains(e.what(), "/layers/3/nozzles: nozzles: 2, but its plan"));
}

TEST(ReadSchedule, MissingKeysWrongTypesAndUnknownKeysAreLocated) {
  {
    json doc = json::parse(golden_text("house"));
    doc["layers"][3].erase("z_m");
    const std::string text = text_of(doc);
    const InputError e = testing::expect_input_error([&] { parse_schedule(text, "h.json"); });
    EXPECT_EQ(e.first().field, "/layers/3");
    EXPECT_TRUE(testing::contains(e.first().message, "\"z_m\" is missing"));
    // The line of layer 3's object: the fourth "floor" after "layers".
    int line = line_holding(text, "\"layers\"");
    for (int k = 0; k < 4; ++k) line = line_holding(text, "\"floor\"", line);
    EXPECT_EQ(e.first().line, line - 1);  // the "{" before it
  }
  {
    json doc = json::parse(golden_text("house"));
    const std::string key = doc["layers"][0]["plan"];
    doc["plans"][key]["nozzles"][0]["waypoints"][3]["x_m"] = "1.5";
    const std::string text = text_of(doc);
    const InputError e = testing::expect_input_error([&] { parse_schedule(text, "h.json"); });
    EXPECT_EQ(e.first().field, "/plans/" + key + "/nozzles/0/waypoints/3/x_m");
    EXPECT_TRUE(testing::contains(e.first().message, "expected a number, got the string \"1.5\""));
    EXPECT_EQ(e.first().line, line_holding(text, "\"x_m\": \"1.5\""));
  }
  {
    const InputError e = refusal([](json& d) { d["layers"][0]["nozle"] = 1; });
    EXPECT_TRUE(testing::contains(e.what(), "unknown key \"nozle\"; did you mean \"nozzles\"?"));
  }
}

TEST(ReadSchedule, NumbersOutOfRangeAndOverflowsAreRefused) {
  EXPECT_TRUE(testing::contains(refusal([](json& d) { d["layers"][2]["start_s"] = -5.0; }).what(),
                                "/layers/2/start_s: must be from 0 to 1e+10 s, got -5.0"));
  std::string text = golden_text("house");
  const std::size_t at = text.find("\"makespan_s\": ") + 14;
  text.replace(at, text.find(',', at) - at, "1e400");
  const InputError e = testing::expect_input_error([&] { parse_schedule(text, "h.json"); });
  EXPECT_TRUE(testing::contains(e.what(), "not valid JSON: number overflow"));
  EXPECT_EQ(e.first().line, line_holding(text, "1e400"));
}

TEST(ReadSchedule, DeepNestingAndTruncationAreRefusedWithTheirLine) {
  const InputError deep = testing::expect_input_error(
      [] { parse_schedule("{\"a\": " + std::string(100000, '[') + "}", "deep.json"); });
  EXPECT_TRUE(testing::contains(deep.what(), "nested more than 64 deep"));
  EXPECT_EQ(deep.first().line, 1);
  const std::string text = golden_text("house");
  const std::string half = text.substr(0, text.size() / 2);
  const InputError cut = testing::expect_input_error([&] { parse_schedule(half, "cut.json"); });
  EXPECT_TRUE(testing::contains(cut.what(), "not valid JSON"));
  EXPECT_NEAR(cut.first().line, static_cast<int>(std::count(half.begin(), half.end(), '\n')), 1);
}

TEST(ReadSchedule, PlansAreCheckedAgainstTheirLayers) {
  // No plans at all: every layer names a plan that is not there.
  EXPECT_TRUE(testing::contains(refusal([](json& d) { d["plans"] = json::object(); }).what(),
                                "/layers/0/plan: plans: \"g1n1"));
  // A piece deposited twice, a piece never deposited.
  const InputError twice = refusal([](json& d) {
    auto& w = d["plans"]["g1n1"]["nozzles"][0]["waypoints"];
    for (auto& p : w)
      if (p["extruding"] && p["wall"] != w[0]["wall"]) {
        p["wall"] = w[0]["wall"];
        p["piece"] = w[0]["piece"];
        break;
      }
  });
  EXPECT_TRUE(testing::contains(twice.what(), "coverage"));
}

TEST(ReadSchedule, WhereTheExtremeIntervalLiesIsRecomputed) {
  // The smallest local interval's piece end written from the largest's: the mutant that
  // survived the earlier suite.
  json doc = json::parse(golden_text("house"));
  std::size_t edited = 0;
  for (std::size_t k = 0; k < doc["layers"].size(); ++k) {
    auto& l = doc["layers"][k];
    if (l["local_interval_min_at"].is_null()) continue;
    if (std::abs(l["local_interval_min_s"].get<double>() -
                 l["local_interval_max_s"].get<double>()) < 1.0)
      continue;
    l["local_interval_min_at"] = l["local_interval_max_at"];
    edited = k;
    break;
  }
  ASSERT_GT(edited, 0u);
  const std::string text = text_of(doc);
  const InputError e = testing::expect_input_error([&] { parse_schedule(text, "h.json"); });
  EXPECT_TRUE(testing::contains(
      e.what(), "/layers/" + std::to_string(edited) + "/local_interval_min_at: local intervals"));
}

TEST(ReadSchedule, FeasibilityAndTotalsMustAddUp) {
  EXPECT_TRUE(testing::contains(refusal([](json& d) { d["feasible"] = false; }).what(),
                                "/feasible: feasibility"));
  EXPECT_TRUE(testing::contains(refusal([](json& d) {
                                  d["totals"]["waits_s"] = d["totals"]["waits_s"].get<double>() + 1;
                                }).what(),
                                "/totals/waits_s: totals"));
  EXPECT_TRUE(
      testing::contains(refusal([](json& d) { d["layers"][4]["wait_before_s"] = 7.0; }).what(),
                        "/layers/4/wait_before_s: waits"));
}

// What the report's buildability chart draws is the material's strength rule at the
// layer's recomputed intervals, and the load of the walls above: a value that is not is
// refused by name.
TEST(ReadSchedule, TheStrengthTheReportDrawsIsRecomputed) {
  auto scaled = [](const char* key, double factor) -> std::string {
    return refusal(
               [=](json& d) { d["layers"][4][key] = d["layers"][4][key].get<double>() * factor; })
        .what();
  };
  EXPECT_TRUE(testing::contains(scaled("below_strength_mpa", 1.01),
                                "/layers/4/below_strength_mpa: strength"));
  EXPECT_TRUE(testing::contains(scaled("below_required_mpa", 0.99),
                                "/layers/4/below_required_mpa: strength"));
  // Both or neither.
  EXPECT_TRUE(testing::contains(
      refusal([](json& d) { d["layers"][4]["below_required_mpa"] = nullptr; }).what(),
      "expected a number exactly when below_strength_mpa is one"));
}

TEST(ReadSchedule, ThePlacementIsReadBackAndDiffNamesAChange) {
  const ScheduleDocument house = parse_schedule(golden_text("house"), "house.json");
  EXPECT_EQ(house.inputs.placement.how, PlacedBy::kAsDrawn);
  const InputError how = refusal([](json& d) { d["inputs"]["placement"]["how"] = "moved"; });
  EXPECT_EQ(how.first().field, "/inputs/placement/how");
  EXPECT_TRUE(testing::contains(how.what(), "\"as drawn\", \"site\" or \"centred\""));
  const InputError origin =
      refusal([](json& d) { d["inputs"]["placement"]["origin_m"] = json::array({1.0}); });
  EXPECT_EQ(origin.first().field, "/inputs/placement/origin_m");
  // A schedule from before placement was recorded: as drawn.
  json old = json::parse(golden_text("house"));
  old["inputs"].erase("placement");
  EXPECT_EQ(parse_schedule(text_of(old), "old.json").inputs.placement.how, PlacedBy::kAsDrawn);
  // Moved by a millimetre: a change, whatever the tolerance (every coordinate moves).
  ScheduleDocument moved = house;
  moved.inputs.placement.how = PlacedBy::kSite;
  moved.inputs.placement.origin_m.x() = 0.001;
  const ScheduleDiff d = diff_schedules(house, moved, {});
  ASSERT_TRUE(d.differs());
  EXPECT_TRUE(testing::contains(d.changes.front(), "placement: as drawn, origin (0.000, 0.000) m"))
      << d.changes.front();
  EXPECT_TRUE(testing::contains(d.changes.front(), "-> site, origin (0.001, 0.000) m"));
}

TEST(DiffTolerance, ARelativeToleranceIsAShareOfTheReference) {
  DiffTolerance t;
  t.relative = 0.095;
  // 100 -> 110 moves 10: 9.5% of the reference (100) is 9.5, too little; 9.5% of the new
  // value (110) would be 10.45, enough. The reference decides.
  EXPECT_FALSE(t.allows(100.0, 110.0));
  EXPECT_TRUE(t.allows(110.0, 100.0));
  t.relative = 0.1;
  EXPECT_TRUE(t.allows(100.0, 110.0));  // at equality
  EXPECT_FALSE(t.allows(100.0, 110.001));
  // The larger of the absolute and the relative part applies.
  t.absolute_s = 12.0;
  EXPECT_TRUE(t.allows(100.0, 112.0));
  EXPECT_FALSE(t.allows(100.0, 112.01));
  // Unset values equal each other only.
  EXPECT_TRUE(t.allows(std::nullopt, std::nullopt));
  EXPECT_FALSE(t.allows(std::nullopt, 0.0));
  EXPECT_FALSE(t.allows(0.0, std::nullopt));
}

TEST(ReadSchedule, ARecordedInputThatChangedIsNamed) {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_read_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  json doc = json::parse(golden_text("house"));
  const fs::path input = dir / "plan.yaml";
  std::ofstream(input) << "walls: []\n";
  doc["inputs"]["files"][0]["path"] = input.string();
  doc["inputs"]["files"][0]["sha256"] = std::string(64, '0');
  const fs::path file = dir / "s.json";
  std::ofstream(file) << text_of(doc);
  // Refused by default, and when missing files are refused too.
  for (const auto check :
       {RecordedInputCheck::kRefuseChanged, RecordedInputCheck::kRefuseChangedOrMissing}) {
    ReadScheduleOptions o;
    o.inputs = check;
    const InputError e = testing::expect_input_error([&] { read_schedule(file, o); });
    EXPECT_EQ(e.first().field, "/inputs/files/0/sha256");
    EXPECT_TRUE(testing::contains(e.what(), "changed since this schedule was made"));
  }
  ReadScheduleOptions note;
  note.inputs = RecordedInputCheck::kNote;
  const ReadSchedule read = read_schedule(file, note);
  ASSERT_FALSE(read.notes.empty());
  EXPECT_TRUE(testing::contains(read.notes[0], input.string() + " changed"));
  // A missing input: named, refused only when asked.
  fs::remove(input);
  EXPECT_FALSE(read_schedule(file).notes.empty());
  ReadScheduleOptions strict;
  strict.inputs = RecordedInputCheck::kRefuseChangedOrMissing;
  EXPECT_TRUE(testing::contains(
      testing::expect_input_error([&] { read_schedule(file, strict); }).what(), "not found here"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild::schedule
