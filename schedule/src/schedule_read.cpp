// read_schedule: a schedule's JSON back into the model (schedule_json.hpp), every key and
// type checked with a plausible range for every number, then re-validated by the rules of
// schedule_rules.cpp and its recorded inputs compared with the files on disk.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <tuple>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/common/limits.hpp"
#include "ccbuild/common/sha256.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "inputs_read.hpp"
#include "json_reader.hpp"
#include "read_limits.hpp"
#include "schedule_rules.hpp"

namespace ccbuild::schedule {
namespace {

using detail::JsonAt;
using namespace detail::read_limits;
using json = nlohmann::json;

/// Unit names met in the document, by index in order of first appearance.
int unit_index(RecordedInputs& in, const JsonAt& at) {
  const std::string name = at.string(200);
  const auto it = std::find(in.unit_names.begin(), in.unit_names.end(), name);
  if (it != in.unit_names.end()) return static_cast<int>(it - in.unit_names.begin());
  if (in.unit_names.size() >= kMaxSmall) at.refuse("too many distinct climbing units");
  in.unit_names.push_back(name);
  return static_cast<int>(in.unit_names.size()) - 1;
}

/// With a calendar: the timestamps beside `start_s` and `end_s` must be theirs.
void check_times(const JsonAt& j, const site::SiteCalendar* calendar, double start_s, double end_s,
                 const char* start_key = "start_time", const char* end_key = "end_time") {
  if (!calendar) return;
  for (const auto& [key, t_s] :
       {std::pair<const char*, double>{start_key, start_s}, {end_key, end_s}}) {
    const std::string want = calendar->timestamp(t_s);
    if (j.at(key).string(40) != want)
      j.at(key).refuse("expected " + want + ", the local time of " + printf_string("%.6f s", t_s) +
                       " on the site's calendar");
  }
}

/// The keys of an object, with the calendar's where there is one.
std::vector<std::string> keys_with(std::vector<std::string> keys,
                                   const site::SiteCalendar* calendar,
                                   const std::vector<std::string>& calendar_keys) {
  if (calendar) keys.insert(keys.end(), calendar_keys.begin(), calendar_keys.end());
  return keys;
}

std::vector<WaitReason> read_reasons(const JsonAt& list) {
  std::vector<WaitReason> out;
  bool bound = false;
  for (const auto& r : list.elements(kMaxSmall)) {
    r.only_keys({"kind", "required_s", "from_s", "binding_s", "detail"});
    WaitReason w;
    const std::string kind = r.at("kind").string(100);
    const auto named = wait_kind_named(kind);
    if (!named) r.at("kind").refuse("expected " + wait_kind_names() + ", got \"" + kind + "\"");
    w.kind = *named;
    w.required_s = r.at("required_s").number(kDuration_s, "s");
    // When it began to hold and how long it bound (absent before they were kept: then
    // each held from the start, and the binding times are worked out here).
    if (const auto from = r.maybe("from_s")) w.from_s = from->number(kDuration_s, "s");
    if (const auto binding = r.maybe("binding_s")) {
      w.binding_s = binding->number(kDuration_s, "s");
      bound = true;
    }
    w.detail = r.at("detail").string(kMaxText);
    out.push_back(std::move(w));
  }
  if (!bound) bind_wait_reasons(out);
  return out;
}

PieceEnd read_piece_end(const JsonAt& e) {
  e.only_keys({"wall", "piece", "x_m", "y_m"});
  PieceEnd p;
  p.wall = e.at("wall").integer(1, kMaxWallId);
  p.piece = static_cast<int>(e.at("piece").integer(1, kMaxPiece));
  p.x_m = e.at("x_m").number(kCoordinate_m, "m");
  p.y_m = e.at("y_m").number(kCoordinate_m, "m");
  return p;
}

ScheduledLayer read_layer(const JsonAt& j, const site::SiteCalendar* calendar,
                          const site::SiteConditions* conditions) {
  j.only_keys(keys_with(
      {"floor",
       "layer",
       "z_m",
       "z_bottom_m",
       "geometry",
       "plan",
       "nozzles",
       "method",
       "start_s",
       "end_s",
       "deposition_s",
       "airtime_s",
       "max_idle_s",
       "move_before_s",
       "pipes_before_s",
       "wait_before_s",
       "wait_reasons",
       "purge_before",
       "interval_s",
       "local_interval_min_s",
       "local_interval_max_s",
       "local_interval_min_at",
       "local_interval_max_at",
       "piece_ends_checked",
       "concrete_m3",
       "peak_flow_m3_h",
       "below_strength_mpa",
       "below_required_mpa",
       "planned_joint"},
      calendar,
      conditions ? std::vector<std::string>{"start_time", "end_time", "equivalent_interval_min_s",
                                            "equivalent_interval_max_s"}
                 : std::vector<std::string>{"start_time", "end_time"}));
  ScheduledLayer l;
  l.floor = static_cast<int>(j.at("floor").integer(0, kMaxFloor));
  l.layer = static_cast<int>(j.at("layer").integer(0, kMaxLayer));
  l.z_top_m = j.at("z_m").number(kCoordinate_m, "m");
  l.z_bottom_m = j.at("z_bottom_m").number(kCoordinate_m, "m");
  if (l.z_bottom_m >= l.z_top_m) j.at("z_m").refuse("must be above z_bottom_m");
  l.geometry = static_cast<int>(j.at("geometry").integer(1, kMaxGeometry));
  l.plan = j.at("plan").string(200);
  l.nozzles = static_cast<int>(j.at("nozzles").integer(1, kMaxNozzles));
  l.method = j.at("method").string(200);
  l.start_s = j.at("start_s").number(kTime_s, "s");
  l.end_s = j.at("end_s").number(kTime_s, "s");
  if (l.end_s < l.start_s) j.at("end_s").refuse("must not be before start_s");
  l.deposition_s = j.at("deposition_s").number(kDuration_s, "s");
  l.airtime_s = j.at("airtime_s").number(kDuration_s, "s");
  l.max_idle_s = j.at("max_idle_s").number(kDuration_s, "s");
  l.move_before_s = j.at("move_before_s").number(kDuration_s, "s");
  l.pipes_before_s = j.at("pipes_before_s").number(kDuration_s, "s");
  l.wait_before_s = j.at("wait_before_s").number(kDuration_s, "s");
  l.wait_reasons = read_reasons(j.at("wait_reasons"));
  l.purge_before = j.at("purge_before").boolean();
  check_times(j, calendar, l.start_s, l.end_s);
  // Before lintels, only schedules on a calendar had planned joints.
  if (const auto joint = j.maybe("planned_joint"))
    l.planned_joint = joint->boolean();
  else if (calendar)
    j.at("planned_joint");
  if (conditions) {
    const Range any = Range::closed(-1e10, 1e10);
    l.equivalent_interval_min_s = j.at("equivalent_interval_min_s").number_or_null(any, "s");
    l.equivalent_interval_max_s = j.at("equivalent_interval_max_s").number_or_null(any, "s");
  }
  l.interval_s = j.at("interval_s").number_or_null(kDuration_s, "s");
  l.local_interval_min_s =
      j.at("local_interval_min_s").number_or_null(Range::closed(-1e10, 1e10), "s");
  l.local_interval_max_s =
      j.at("local_interval_max_s").number_or_null(Range::closed(-1e10, 1e10), "s");
  const JsonAt min_at = j.at("local_interval_min_at"), max_at = j.at("local_interval_max_at");
  if (l.local_interval_min_s.has_value() != !min_at.is_null())
    min_at.refuse("expected a piece end exactly when local_interval_min_s is a number");
  if (l.local_interval_max_s.has_value() != !max_at.is_null())
    max_at.refuse("expected a piece end exactly when local_interval_max_s is a number");
  if (l.local_interval_min_s.has_value() != l.local_interval_max_s.has_value())
    j.at("local_interval_max_s")
        .refuse("expected a number exactly when local_interval_min_s is one");
  if (!min_at.is_null()) l.local_min_at = read_piece_end(min_at);
  if (!max_at.is_null()) l.local_max_at = read_piece_end(max_at);
  l.piece_ends_checked = static_cast<int>(j.at("piece_ends_checked").integer(0, 100'000'000));
  // Quantities (absent in schedules written before them).
  if (const auto v = j.maybe("concrete_m3")) l.concrete_m3 = v->number(Range::closed(0, 1e6), "m3");
  if (const auto f = j.maybe("peak_flow_m3_h"))
    l.peak_flow_m3_s = f->number(Range::closed(0, 1e6), "m3/h") / 3600.0;
  // The buildability the report draws (absent in schedules written before it).
  if (const auto v = j.maybe("below_strength_mpa"))
    l.below_strength_mpa = v->number_or_null(kStrength_mpa, "MPa");
  if (const auto v = j.maybe("below_required_mpa"))
    l.below_required_mpa = v->number_or_null(kStrength_mpa, "MPa");
  if (l.below_strength_mpa.has_value() != l.below_required_mpa.has_value())
    j.at("below_required_mpa").refuse("expected a number exactly when below_strength_mpa is one");
  return l;
}

/// A plan's pieces as a layer: points shared where pieces share an end.
floors::Layer read_pieces(const JsonAt& list) {
  floors::Layer layer;
  auto point = [&](const JsonAt& at) {
    const auto xy = at.elements(2);
    if (xy.size() != 2) at.refuse("expected [x, y]");
    const Eigen::Vector2d p(xy[0].number(kCoordinate_m, "m"), xy[1].number(kCoordinate_m, "m"));
    for (std::size_t k = 0; k < layer.points.size(); ++k)
      if (layer.points[k] == p) return static_cast<int>(k);
    layer.points.push_back(p);
    return static_cast<int>(layer.points.size()) - 1;
  };
  for (const auto& s : list.elements(kMaxItems)) {
    s.only_keys(
        {"wall", "piece", "piece_count", "start_m", "end_m", "length_m", "bead", "width_m"});
    floors::LayerSegment seg;
    seg.wall_id = s.at("wall").integer(1, kMaxWallId);
    seg.piece = static_cast<int>(s.at("piece").integer(1, kMaxPiece)) - 1;
    seg.piece_count = static_cast<int>(s.at("piece_count").integer(1, kMaxPiece));
    if (seg.piece >= seg.piece_count) s.at("piece").refuse("must be at most piece_count");
    seg.start_point = point(s.at("start_m"));
    seg.end_point = point(s.at("end_m"));
    seg.length_m = s.at("length_m").number(kLength_m, "m");
    if (s.maybe("bead") || s.maybe("width_m")) {
      const std::string role = s.at("bead").string(16);
      const auto parsed = floors::parse_bead_role(role);
      if (!parsed)
        s.at("bead").refuse("expected pass, skin, core or tie, got '" + echoed(role) + "'");
      seg.role = *parsed;
      seg.width_m = s.at("width_m").number(Range::above(0, 10), "m");
    }
    layer.segments.push_back(seg);
  }
  return layer;
}

std::vector<planner::Waypoint> read_waypoints(const JsonAt& list) {
  std::vector<planner::Waypoint> out;
  const auto items = list.elements(kMaxItems);
  out.reserve(items.size());
  for (const auto& w : items) {
    w.only_keys({"t_s", "x_m", "y_m", "z_m", "heading_rad", "extruding", "wall", "piece"});
    planner::Waypoint p;
    p.t_s = w.at("t_s").number(kTime_s, "s");
    p.position_m = {w.at("x_m").number(kCoordinate_m, "m"), w.at("y_m").number(kCoordinate_m, "m")};
    p.z_m = w.at("z_m").number(kCoordinate_m, "m");
    p.heading_rad = w.at("heading_rad").number(kHeading_rad, "rad");
    p.extruding = w.at("extruding").boolean();
    p.wall = w.at("wall").integer(p.extruding ? 1 : 0, kMaxWallId);
    p.piece = static_cast<int>(w.at("piece").integer(p.extruding ? 1 : 0, kMaxPiece));
    out.push_back(p);
  }
  return out;
}

SchedulePlan read_plan(const std::string& key, const JsonAt& j, bool allow_digests) {
  j.only_keys({"geometry", "nozzles_used", "method", "z_top_m", "layer_time_s", "min_gap_m",
               "pieces", "nozzles"});
  SchedulePlan p;
  p.key = key;
  p.geometry = static_cast<int>(j.at("geometry").integer(1, kMaxGeometry));
  p.nozzles = static_cast<int>(j.at("nozzles_used").integer(1, kMaxNozzles));
  p.method = j.at("method").string(200);
  p.z_top_m = j.at("z_top_m").number(kCoordinate_m, "m");
  p.layer_time_s = j.at("layer_time_s").number(kDuration_s, "s");
  if (p.nozzles > 1)
    p.min_gap_m = j.at("min_gap_m").number(Range::closed(-1e5, 1e5), "m");
  else if (!j.at("min_gap_m").is_null())
    j.at("min_gap_m").refuse("expected null for a plan of one nozzle");
  p.layer = read_pieces(j.at("pieces"));
  const auto nozzles = j.at("nozzles").elements(kMaxNozzles);
  for (std::size_t n = 0; n < nozzles.size(); ++n) {
    nozzles[n].only_keys({"nozzle", "waypoints", "waypoints_digest"});
    if (nozzles[n].at("nozzle").integer(0, kMaxNozzles) != static_cast<std::int64_t>(n))
      nozzles[n].at("nozzle").refuse(
          printf_string("expected %zu: nozzles are numbered in rail "
                        "order from 0",
                        n));
    if (const auto digest = nozzles[n].maybe("waypoints_digest")) {
      if (!allow_digests)
        digest->refuse(
            "this schedule keeps its paths' digests only (a regression golden, written with "
            "--path-digests); this command needs the paths: schedule it again without it");
      if (!p.waypoints.empty() || nozzles[n].maybe("waypoints"))
        digest->refuse("expected the waypoints or their digest for every nozzle, not both");
      digest->only_keys({"waypoints", "sha256"});
      PathDigest d;
      d.waypoints = static_cast<std::size_t>(
          digest->at("waypoints").integer(2, static_cast<std::int64_t>(kMaxItems)));
      d.sha256 = digest->at("sha256").string(64);
      if (d.sha256.size() != 64 ||
          d.sha256.find_first_not_of("0123456789abcdef") != std::string::npos)
        digest->at("sha256").refuse("expected 64 lowercase hex digits (a SHA-256)");
      p.digests.push_back(std::move(d));
      continue;
    }
    if (!p.digests.empty())
      nozzles[n].refuse("expected the digest of every nozzle's path, as for nozzle 0");
    p.waypoints.push_back(read_waypoints(nozzles[n].at("waypoints")));
  }
  return p;
}

climb::Anchor read_anchor(const JsonAt& a, RecordedInputs& in) {
  a.only_keys({"id", "unit", "floor", "wall", "after_layer", "x_m", "y_m", "z_m", "outward",
               "by_default_rule"});
  climb::Anchor out;
  out.id = a.at("id").string(200);
  out.unit = unit_index(in, a.at("unit"));
  if (a.at("floor").is_null()) {
    if (!a.at("wall").is_null() || !a.at("after_layer").is_null())
      a.at("wall").refuse("expected null in the foundation (floor null)");
    out.floor = -1;
    out.wall_id = 0;
    out.layer = -1;
  } else {
    out.floor = static_cast<int>(a.at("floor").integer(0, kMaxFloor));
    out.wall_id = a.at("wall").integer(1, kMaxWallId);
    out.layer = static_cast<int>(a.at("after_layer").integer(0, kMaxLayer));
  }
  out.centre_m = {a.at("x_m").number(kCoordinate_m, "m"), a.at("y_m").number(kCoordinate_m, "m"),
                  a.at("z_m").number(kCoordinate_m, "m")};
  const auto outward = a.at("outward").elements(2);
  if (outward.size() != 2) a.at("outward").refuse("expected [x, y]");
  out.outward = {outward[0].number(Range::closed(-1, 1)), outward[1].number(Range::closed(-1, 1))};
  out.by_default_rule = a.at("by_default_rule").boolean();
  return out;
}

climb::ClimbStage read_stage(const JsonAt& s, RecordedInputs& in) {
  s.only_keys({"stage", "platform_z_m", "first", "last", "top_m", "anchors"});
  climb::ClimbStage out;
  out.index = static_cast<int>(s.at("stage").integer(0, kMaxLayer));
  out.platform_z_m = s.at("platform_z_m").number(kCoordinate_m, "m");
  for (auto [key, ref] : {std::pair{"first", &out.first}, std::pair{"last", &out.last}}) {
    const JsonAt r = s.at(key);
    r.only_keys({"floor", "layer"});
    ref->floor = static_cast<int>(r.at("floor").integer(0, kMaxFloor));
    ref->layer = static_cast<int>(r.at("layer").integer(0, kMaxLayer));
  }
  out.top_m = s.at("top_m").number(kCoordinate_m, "m");
  for (const auto& a : s.at("anchors").elements(kMaxSmall))
    out.anchors.push_back(read_anchor(a, in));
  return out;
}

template <class Code>
Code code_named(const JsonAt& at, const std::vector<Code>& codes, std::string (*name)(Code)) {
  const std::string text = at.string(100);
  std::string known;
  for (Code c : codes) {
    if (name(c) == text) return c;
    known += (known.empty() ? "" : ", ") + name(c);
  }
  at.refuse("expected one of " + known + ", got \"" + text + "\"");
}

climb::ClimbPlan read_climb_plan(const JsonAt& c, RecordedInputs& in) {
  c.only_keys({"from_stage", "to_stage", "status", "status_reason", "duration_s", "min_clearance_m",
               "phases"});
  climb::ClimbPlan out;
  out.from_stage = static_cast<int>(c.at("from_stage").integer(0, kMaxLayer));
  out.to_stage = static_cast<int>(c.at("to_stage").integer(0, kMaxLayer));
  using climb::ClimbCode;
  const ClimbCode code =
      code_named<ClimbCode>(c.at("status"),
                            {ClimbCode::kFeasible, ClimbCode::kNoAnchor, ClimbCode::kBlocked,
                             ClimbCode::kUnstable, ClimbCode::kTimeLimit},
                            &climb::to_string);
  out.status = climb::ClimbStatus(code, c.at("status_reason").string(kMaxText));
  out.duration_s = c.at("duration_s").number(kDuration_s, "s");
  out.min_clearance_m =
      c.at("min_clearance_m").number_or_null(kCoordinate_m, "m").value_or(INFINITY);
  using Kind = climb::ClimbPhase::Kind;
  for (const auto& p : c.at("phases").elements(kMaxSmall)) {
    p.only_keys({"kind", "unit", "joints", "following_joints", "duration_s", "min_clearance_m",
                 "strokes", "waypoints"});
    climb::ClimbPhase phase;
    phase.kind = code_named<Kind>(
        p.at("kind"),
        {Kind::kPark, Kind::kBalance, Kind::kRelease, Kind::kTransit, Kind::kInsert, Kind::kLift},
        &climb::to_string);
    phase.unit = p.at("unit").is_null() ? -1 : unit_index(in, p.at("unit"));
    for (const auto& name : p.at("joints").elements(kMaxSmall))
      phase.joints.push_back(name.string(200));
    for (const auto& name : p.at("following_joints").elements(kMaxSmall))
      phase.following_joints.push_back(name.string(200));
    phase.duration_s = p.at("duration_s").number(kDuration_s, "s");
    phase.min_clearance_m =
        p.at("min_clearance_m").number_or_null(kCoordinate_m, "m").value_or(INFINITY);
    phase.strokes = static_cast<int>(p.at("strokes").integer(0, 100'000));
    bool following = true;
    const auto points = p.at("waypoints").elements(kMaxItems);
    for (std::size_t k = 0; k < points.size(); ++k) {
      const JsonAt& w = points[k];
      w.only_keys({"t_s", "values", "following"});
      phase.t_s.push_back(w.at("t_s").number(kDuration_s, "s"));
      std::vector<double> values;
      for (const auto& v : w.at("values").elements(kMaxSmall))
        values.push_back(v.number(Range::closed(-1e5, 1e5)));
      if (values.size() != phase.joints.size())
        w.at("values").refuse(
            printf_string("expected %zu values, one per joint", phase.joints.size()));
      phase.path.push_back(std::move(values));
      if (const auto legs = w.maybe("following")) {
        if (!following) legs->refuse("following values after waypoints without them");
        std::vector<double> values_following;
        for (const auto& v : legs->elements(kMaxSmall))
          values_following.push_back(v.number(Range::closed(-1e5, 1e5)));
        if (values_following.size() != phase.following_joints.size())
          legs->refuse(printf_string("expected %zu values, one per following joint",
                                     phase.following_joints.size()));
        phase.following.push_back(std::move(values_following));
      } else {
        following = false;
      }
    }
    out.phases.push_back(std::move(phase));
  }
  return out;
}

Event read_event(const JsonAt& j, RecordedInputs& in) {
  Event e;
  const site::SiteCalendar* calendar = in.calendar.get();
  const auto only = [&](std::vector<std::string> keys) {
    j.only_keys(keys_with(std::move(keys), calendar, {"start_time", "end_time"}));
  };
  const std::string kind = j.at("kind").string(20);
  if (kind == "pipe") {
    e.kind = Event::Kind::kPipe;
    only({"kind", "start_s", "end_s", "floor", "after_layer", "crew", "detail", "anchor",
          "wait_before_s"});
    e.anchor = read_anchor(j.at("anchor"), in);
  } else if (kind == "slab" || kind == "purge" || kind == "joint") {
    e.kind = kind == "slab"    ? Event::Kind::kSlab
             : kind == "purge" ? Event::Kind::kPurge
                               : Event::Kind::kJoint;
    only({"kind", "start_s", "end_s", "floor", "after_layer", "crew", "detail", "roof",
          "wait_before_s"});
    if (const auto roof = j.maybe("roof")) e.roof = roof->boolean();
  } else if (kind == "pour") {
    e.kind = Event::Kind::kPour;
    only({"kind", "start_s", "end_s", "floor", "after_layer", "crew", "detail", "roof",
          "concrete_m3", "wait_before_s"});
    e.roof = j.at("roof").boolean();
    e.concrete_m3 = j.at("concrete_m3").number(Range::closed(0, 1e7), "m3");
  } else if (kind == "lintel") {
    e.kind = Event::Kind::kLintel;
    only({"kind", "start_s", "end_s", "floor", "after_layer", "crew", "detail", "lintel",
          "wait_before_s"});
    const JsonAt l = j.at("lintel");
    l.only_keys({"opening", "wall", "offset_m", "width_m", "from_m", "to_m", "start_m", "end_m",
                 "sill_m", "head_m", "head_z_m", "type", "height_m", "by"});
    LintelTask task;
    task.opening = l.at("opening").string(200);
    task.wall = l.at("wall").integer(1, std::int64_t{1} << 53);
    const Range along = Range::closed(-1e5, 1e5);
    task.offset_m = l.at("offset_m").number(along, "m");
    task.width_m = l.at("width_m").number(Range::above(0, 1e5), "m");
    task.from_m = l.at("from_m").number(along, "m");
    task.to_m = l.at("to_m").number(along, "m");
    if (task.to_m < task.from_m) l.at("to_m").refuse("must not be before from_m");
    for (const auto& [key, point] :
         {std::pair<const char*, Eigen::Vector2d*>{"start_m", &task.start_m},
          {"end_m", &task.end_m}}) {
      const auto xy = l.at(key).elements(3);
      if (xy.size() != 2) l.at(key).refuse("expected [x, y]");
      *point = {xy[0].number(kCoordinate_m, "m"), xy[1].number(kCoordinate_m, "m")};
    }
    task.sill_m = l.at("sill_m").number(Range::closed(0, 1e3), "m");
    task.head_m = l.at("head_m").number(Range::closed(0, 1e3), "m");
    if (task.head_m <= task.sill_m) l.at("head_m").refuse("must be above sill_m");
    task.head_z_m = l.at("head_z_m").number(kCoordinate_m, "m");
    detail::read_lintel_kind(l, task.type, task.by_arm);
    task.height_m = l.at("height_m").number(Range::closed(0, 10), "m");
    e.lintel = std::move(task);
  } else if (kind == "climb") {
    e.kind = Event::Kind::kClimb;
    only({"kind", "start_s", "end_s", "floor", "after_layer", "crew", "detail", "from_stage",
          "to_stage", "wait_before_s", "wait_reasons", "anchors", "youngest_anchor_strength",
          "climb"});
    ClimbEvent c;
    c.from_stage = static_cast<int>(j.at("from_stage").integer(0, kMaxLayer));
    c.to_stage = static_cast<int>(j.at("to_stage").integer(0, kMaxLayer));
    c.wait_before_s = j.at("wait_before_s").number(kDuration_s, "s");
    c.wait_reasons = read_reasons(j.at("wait_reasons"));
    for (const auto& a : j.at("anchors").elements(kMaxSmall)) {
      if (in.conditions)
        a.only_keys({"id", "unit", "age_s", "strength_mpa", "required_mpa", "equivalent_age_s"});
      else
        a.only_keys({"id", "unit", "age_s", "strength_mpa", "required_mpa"});
      ClimbEvent::AnchorLoad load;
      load.id = a.at("id").string(200);
      load.unit = a.at("unit").string(200);
      load.age_s = a.at("age_s").number(kDuration_s, "s");
      load.strength_mpa = a.at("strength_mpa").number(kStrength_mpa, "MPa");
      load.required_mpa = a.at("required_mpa").number(kStrength_mpa, "MPa");
      load.equivalent_age_s =
          in.conditions ? a.at("equivalent_age_s").number(kDuration_s, "s") : load.age_s;
      c.anchors.push_back(std::move(load));
    }
    // The chart's points (absent in schedules written before them).
    if (const auto points = j.maybe("youngest_anchor_strength"))
      for (const auto& p : points->elements(kAnchorCurvePoints)) {
        const auto pair = p.elements(2);
        if (pair.size() != 2) p.refuse("expected [time_s, strength_mpa]");
        c.youngest_anchor_strength.push_back(
            {pair[0].number(kTime_s, "s"), pair[1].number(kStrength_mpa, "MPa")});
      }
    c.plan = read_climb_plan(j.at("climb"), in);
    e.climb = std::move(c);
  } else {
    j.at("kind").refuse("expected pipe, climb, slab, pour, lintel, purge or joint, got \"" + kind +
                        "\"");
  }
  e.start_s = j.at("start_s").number(kTime_s, "s");
  e.end_s = j.at("end_s").number(kTime_s, "s");
  if (e.end_s < e.start_s) j.at("end_s").refuse("must not be before start_s");
  check_times(j, calendar, e.start_s, e.end_s);
  e.floor = static_cast<int>(j.at("floor").integer(0, kMaxFloor));
  e.layer = static_cast<int>(j.at("after_layer").integer(0, kMaxLayer));
  e.detail = j.at("detail").string(kMaxText);
  if (const auto crew = j.maybe("crew")) e.crew = static_cast<int>(crew->integer(0, 100));
  if (!e.climb)
    if (const auto w = j.maybe("wait_before_s")) e.wait_before_s = w->number(kDuration_s, "s");
  if (e.climb) {
    e.climb->start_s = e.start_s;
    e.climb->end_s = e.end_s;
  }
  return e;
}

Infeasibility read_infeasibility(const JsonAt& j) {
  j.only_keys({"kind", "floor", "layer", "message", "required_s", "achieved_s", "fix"});
  Infeasibility inf;
  const std::string kind = j.at("kind").string(100);
  const auto named = infeasibility_kind_named(kind);
  if (!named)
    j.at("kind").refuse(
        "expected max-interval, no-plan, strength, climb, calendar or joint, got \"" + kind + "\"");
  inf.kind = *named;
  inf.floor = static_cast<int>(j.at("floor").integer(0, kMaxFloor));
  inf.layer = static_cast<int>(j.at("layer").integer(0, kMaxLayer));
  inf.message = j.at("message").string(kMaxText);
  inf.required_s = j.at("required_s").number(Range::closed(-1e10, 1e10), "s");
  inf.achieved_s = j.at("achieved_s").number(Range::closed(-1e10, 1e10), "s");
  const JsonAt fix = j.at("fix");
  fix.only_keys({"text", "nozzles_needed", "deposition_speed_needed_m_s", "max_interval_needed_s"});
  inf.fix = fix.at("text").string(kMaxText);
  if (!fix.at("nozzles_needed").is_null())
    inf.nozzles_needed = static_cast<int>(fix.at("nozzles_needed").integer(1, 1000));
  inf.deposition_speed_needed_m_s =
      fix.at("deposition_speed_needed_m_s").number_or_null(Range::above(0, 1e6), "m/s");
  inf.max_interval_needed_s = fix.at("max_interval_needed_s").number_or_null(kDuration_s, "s");
  return inf;
}

ScheduleTotals read_totals(const JsonAt& t, std::size_t& layers,
                           const site::SiteCalendar* calendar) {
  t.only_keys(keys_with({"makespan_s", "layers", "deposition_s", "airtime_s", "moves_s", "waits_s",
                         "pipes_s", "purges_s", "climbs_s", "slabs_s", "machine_s", "concrete_m3",
                         "joints_s", "lintels_s", "crew_h"},
                        calendar, {"start_time", "finish_time"}));
  ScheduleTotals out;
  out.makespan_s = t.at("makespan_s").number(kTime_s, "s");
  layers = static_cast<std::size_t>(t.at("layers").integer(0, kMaxLayers));
  out.deposition_s = t.at("deposition_s").number(kDuration_s, "s");
  out.airtime_s = t.at("airtime_s").number(kDuration_s, "s");
  out.moves_s = t.at("moves_s").number(kDuration_s, "s");
  out.waits_s = t.at("waits_s").number(kDuration_s, "s");
  out.pipes_s = t.at("pipes_s").number(kDuration_s, "s");
  out.purges_s = t.at("purges_s").number(kDuration_s, "s");
  out.climbs_s = t.at("climbs_s").number(kDuration_s, "s");
  out.slabs_s = t.at("slabs_s").number(kDuration_s, "s");
  out.machine_s = t.at("machine_s").number(kDuration_s, "s");
  if (const auto v = t.maybe("concrete_m3"))
    out.concrete_m3 = v->number(Range::closed(0, 1e9), "m3");
  // Older schedules: joints only on a calendar, no lintels or crews.
  if (const auto v = t.maybe("joints_s"))
    out.joints_s = v->number(kDuration_s, "s");
  else if (calendar)
    t.at("joints_s");
  if (const auto v = t.maybe("lintels_s")) out.lintels_s = v->number(kDuration_s, "s");
  if (const auto v = t.maybe("crew_h")) out.crew_h = v->number(Range::closed(0, 1e9), "h");
  if (calendar) {
    check_times(t, calendar, 0.0, out.makespan_s, "start_time", "finish_time");
  }
  return out;
}

WorkDay read_day(const JsonAt& j) {
  j.only_keys({"date", "layers", "first", "last", "printing_s", "concrete_m3", "deliveries",
               "crew_h", "stop", "detail"});
  WorkDay d;
  d.date = j.at("date").string(20);
  if (!site::parse_local_date(d.date)) j.at("date").refuse("expected a date as YYYY-MM-DD");
  d.layers = static_cast<int>(j.at("layers").integer(1, kMaxLayers));
  for (const auto& [key, floor, layer] :
       {std::tuple<const char*, int*, int*>{"first", &d.first_floor, &d.first_layer},
        {"last", &d.last_floor, &d.last_layer}}) {
    const auto pair = j.at(key).elements(2);
    if (pair.size() != 2) j.at(key).refuse("expected [floor, layer]");
    *floor = static_cast<int>(pair[0].integer(0, kMaxFloor));
    *layer = static_cast<int>(pair[1].integer(0, kMaxLayer));
  }
  d.printing_s = j.at("printing_s").number(kDuration_s, "s");
  d.concrete_m3 = j.at("concrete_m3").number(Range::closed(0, 1e9), "m3");
  d.deliveries = static_cast<int>(j.at("deliveries").integer(0, 10'000'000));
  if (const auto v = j.maybe("crew_h")) d.crew_h = v->number(Range::closed(0, 1e9), "h");
  const std::string stop = j.at("stop").string(20);
  const auto end = day_end_named(stop);
  if (!end) j.at("stop").refuse("expected " + day_end_names() + ", got \"" + stop + "\"");
  d.stop = *end;
  d.detail = j.at("detail").string(kMaxText);
  return d;
}

}  // namespace

ScheduleDocument parse_schedule(const std::string& text, const std::string& file,
                                bool allow_path_digests) {
  detail::check_nesting(text, file, limits::kMaxNestingDepth, "a schedule");
  ScheduleDocument doc;
  detail::JsonText located(file, text);
  {
    // The DOM is the largest thing in memory; it goes once the model is read.
    const json dom = detail::parse_located(text, file);
    const JsonAt root(located, dom, "");
    if (!dom.is_object() || !dom.contains("format") || dom["format"] != "ccbuild-schedule")
      root.refuse(
          "expected a ccbuild schedule (\"format\": \"ccbuild-schedule\"), from `ccbuild "
          "schedule -o`");
    const json& version = dom.contains("schema_version") ? dom["schema_version"] : json();
    if (version != kScheduleSchemaVersion)
      root.at("schema_version")
          .refuse("expected schema_version " + std::to_string(kScheduleSchemaVersion) + ", got " +
                  version.dump() +
                  (version.is_number_integer() && version.get<long long>() < kScheduleSchemaVersion
                       ? ": a schedule from an older ccbuild; schedule the building again "
                         "(`ccbuild schedule BUILDING -o FILE`)"
                       : ""));
    RecordedInputs& in = doc.inputs;
    in = detail::read_inputs(root);
    const site::SiteCalendar* calendar = in.calendar.get();
    root.only_keys(keys_with(
        {"format", "schema_version", "ccbuild_version", "inputs", "feasible", "infeasibility",
         "totals", "layers", "plans", "stages", "events", "deliveries", "warnings"},
        calendar, {"days"}));
    Schedule& s = doc.schedule;
    s.feasible = root.at("feasible").boolean();
    if (!root.at("infeasibility").is_null())
      s.infeasibility = read_infeasibility(root.at("infeasibility"));
    std::size_t layer_count = 0;
    s.totals = read_totals(root.at("totals"), layer_count, calendar);
    for (const auto& l : root.at("layers").elements(kMaxLayers))
      s.layers.push_back(read_layer(l, calendar, in.conditions.get()));
    if (calendar)
      for (const auto& d : root.at("days").elements(kMaxLayers)) s.days.push_back(read_day(d));
    if (layer_count != s.layers.size())
      root.at("totals").at("layers").refuse(
          printf_string("says %zu layers; the schedule has %zu", layer_count, s.layers.size()));
    for (const auto& [key, p] : root.at("plans").members(kMaxPlans)) {
      if (key.empty() || key.size() > 200) p.refuse("expected a plan key of 1 to 200 characters");
      s.plans.emplace(key, read_plan(key, p, allow_path_digests));
    }
    for (const auto& st : root.at("stages").elements(kMaxSmall))
      s.stages.push_back(read_stage(st, in));
    for (const auto& e : root.at("events").elements(kMaxEvents))
      s.events.push_back(read_event(e, in));
    if (const auto list = root.maybe("deliveries"))
      for (const auto& d : list->elements(kMaxEvents)) {
        d.only_keys(keys_with({"due_s", "m3", "floor", "layer"}, calendar, {"due_time"}));
        Delivery delivery;
        delivery.due_s = d.at("due_s").number(kTime_s, "s");
        check_times(d, calendar, delivery.due_s, delivery.due_s, "due_time", "due_time");
        delivery.m3 = d.at("m3").number(Range::above(0.0, 1e4), "m3");
        delivery.floor = static_cast<int>(d.at("floor").integer(0, kMaxFloor));
        delivery.layer = static_cast<int>(d.at("layer").integer(0, kMaxLayer));
        s.deliveries.push_back(delivery);
      }
    for (const auto& w : root.at("warnings").elements(kMaxSmall))
      s.warnings.push_back(w.string(kMaxText));
  }
  detail::check_schedule_rules(doc, located);
  return doc;
}

ReadSchedule read_schedule(const std::filesystem::path& path, const ReadScheduleOptions& options) {
  namespace fs = std::filesystem;
  const std::string file = path.string();
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw InputError(file, 0, "", "cannot open file (does it exist?)");
  if (!fs::is_regular_file(status))
    throw InputError(file, 0, "",
                     "is not a regular file (a folder, FIFO or device?); expected a schedule JSON");
  const auto size = fs::file_size(path, ec);
  if (!ec && size > kMaxScheduleBytes)
    throw InputError(file, 0, "",
                     printf_string("is %ju MiB; ccbuild reads schedules of at most %ju MiB",
                                   size >> 20, kMaxScheduleBytes >> 20));
  std::string text;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(file, 0, "", "cannot open file (permissions?)");
    note_file_read(path);  // an input of this run: never one of its outputs
    text.reserve(static_cast<std::size_t>(size));
    char chunk[64 * 1024];
    while (in && text.size() <= kMaxScheduleBytes) {
      in.read(chunk, sizeof chunk);
      text.append(chunk, static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) throw InputError(file, 0, "", "cannot read file");
    if (text.size() > kMaxScheduleBytes)
      throw InputError(file, 0, "", "grew past the size limit while it was read");
  }
  ReadSchedule out;
  out.document = parse_schedule(text, file, options.allow_path_digests);
  text = std::string();
  // The recorded inputs, by path (as recorded, from here) and SHA-256.
  const auto& files = out.document.inputs.files;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const std::string field = "/inputs/files/" + std::to_string(k);
    const fs::path recorded = files[k].path;
    if (!fs::is_regular_file(recorded, ec)) {
      const std::string said = "the input " + files[k].path +
                               " this schedule was made from is not found here (relative "
                               "paths are from where `ccbuild schedule` ran)";
      if (options.inputs == RecordedInputCheck::kRefuseChangedOrMissing)
        throw InputError(file, 0, field + "/path", said);
      out.notes.push_back(said);
      continue;
    }
    const std::string now = sha256_file_hex(recorded);
    if (now == files[k].sha256) continue;
    const std::string said =
        "the input " + files[k].path + " changed since this schedule was made (SHA-256 " +
        files[k].sha256.substr(0, 12) + " recorded, " + now.substr(0, 12) + " now)";
    if (options.inputs == RecordedInputCheck::kNote)
      out.notes.push_back(said);
    else
      throw InputError(file, 0, field + "/sha256", said + "; schedule it again");
  }
  return out;
}

}  // namespace ccbuild::schedule
