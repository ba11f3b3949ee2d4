#pragma once
// The DXF importer's walls (not public): what dxflib's lines become, and how face lines
// pair into walls, their ends meet at junctions, and gaps between them become openings.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/floors/plane.hpp"
#include "note_log.hpp"

namespace ccbuild::import::detail {

using Eigen::Vector2d;

/// An entity's handle as the drawing writes it (hex), or "(no handle)".
std::string hex_handle(int handle);

/// A straight line of the drawing, in drawing units.
struct DrawnLine {
  Vector2d a, b;
  int handle = -1;
  std::string layer;
};

/// A gap in a wall's line read as an opening, from the wall's start.
struct FoundGap {
  double offset_m = 0.0, width_m = 0.0;
  bool window = false;
  std::string source;
  /// The door or window block inserted in the gap (an index into the marks join_gaps
  /// was given): the gap is that opening, never a second one.
  std::optional<std::size_t> mark;
};

/// A door or window block inserted in the drawing: its width along its x axis, in metres.
struct OpeningMark {
  Vector2d a, b;
  bool window = false;
};

/// A wall found: its centreline in metres, its thickness (unset: drawn as a centreline).
struct FoundWall {
  Vector2d a, b;
  std::optional<double> thickness_m;
  std::string source;  ///< "entity 1A on layer A-WALL" (and its partner)
  std::vector<FoundGap> gaps{};
};

using floors::cross;

/// Wall lines crowd around `line` (an index into what was searched) beyond what any floor
/// plan has: more than kMaxNearPairsPerLine pairs per line lie within `within_m` of each
/// other. Thrown by the searches below; read_dxf_plan says where, as an input error.
struct CrowdedLines {
  std::size_t line;
  double within_m;
};
/// Pairs of lines near one another that a search takes, on average per line (a plan has a
/// few per line: a face's partner, the lines at its junctions).
inline constexpr std::size_t kMaxNearPairsPerLine = 64;

/// Face lines (in drawing units, `scale` metres each) facing each other at most
/// `max_thickness_m` apart, over at least half the shorter and no further apart at either
/// end of the stretch they share, become walls along their middle; what pairs with nothing
/// is said in `notes`. Throws CrowdedLines.
std::vector<FoundWall> pair_faces(const std::vector<DrawnLine>& faces, double scale,
                                  double max_thickness_m, NoteLog& notes);

/// Extends face-pair walls' ends to the middle line of the wall they meet.
void join_ends(std::vector<FoundWall>& walls);

/// Joins walls in line across gaps of at most `max_gap_m` into one wall with an opening
/// in each gap (a window where a `glazing` line lies in it). Each free end is linked to at
/// most kMaxGapPartners facing ends, its nearest.
/// Joins walls broken at openings: facing free ends of walls along one line, at most
/// `max_gap_m` apart, become one wall with the gap as an opening. A gap is joined when a
/// door or window block is inserted in it (its kind then the mark's), or, with
/// `every_gap`, always (a window where a glazing line lies in it, else a door).
std::vector<FoundWall> join_gaps(std::vector<FoundWall> walls,
                                 const std::vector<DrawnLine>& glazing,
                                 const std::vector<OpeningMark>& marks, bool every_gap,
                                 double scale, double max_gap_m);
inline constexpr std::size_t kMaxGapPartners = 8;

}  // namespace ccbuild::import::detail
