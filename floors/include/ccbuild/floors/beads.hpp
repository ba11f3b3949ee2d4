#pragma once
// Walls thicker than one bead, printed as several beads per layer (docs/formats.md,
// "Walls of any thickness"). The nozzle lays a bead of its own width; a thicker wall is
// two skins along its faces, closed around its free ends and the jambs of its openings,
// and between them, as the building says, nothing (a cavity), a poured core, or a
// zig-zag tie. The skins are the outline of the layer's thick walls (their union, with
// L, T and X junctions filled) offset inwards by half a bead, computed with
// Boost.Geometry; each straight stretch of a skin belongs to the wall it runs along.

#include <optional>
#include <string>

namespace ccbuild::floors {

/// What fills a wall between its two skins.
enum class WallPattern {
  kSkins,          ///< the skins only: a cavity between them
  kSolid,          ///< the skins and a core poured along the wall's middle
  kSkinsWithTies,  ///< the skins and a zig-zag tie between them
};

/// "skins", "solid", "skins-with-ties".
const char* wall_pattern_name(WallPattern pattern);
/// The pattern named so; nullopt for any other text.
std::optional<WallPattern> parse_wall_pattern(const std::string& name);

/// How a plan's walls become beads. With `bead_width_m` 0 (plans read outside a project
/// with a machine) every wall is one pass along its middle, whatever its thickness.
struct BeadSpec {
  double bead_width_m = 0.0;  ///< the nozzle's own width: a thick wall's skins, m
  WallPattern pattern = WallPattern::kSolid;
  /// The narrowest and widest bead one pass lays, m (docs/formats.md, "Bead widths"); 0:
  /// `bead_width_m` only.
  double narrowest_m = 0.0, widest_m = 0.0;
};

/// How a wall of some thickness is printed.
enum class WallPrint {
  kTooThin,       ///< thinner than the narrowest bead: it cannot be printed
  kOnePass,       ///< one bead of the wall's thickness along its middle
  kTwoSkins,      ///< two skins of half the wall each, nothing between them
  kSkinsAndFill,  ///< two skins of the nozzle's width and the pattern between them
  kBetween,       ///< wider than the widest bead and narrower than two narrowest: cannot
};

/// A wall's beads across its thickness: how, and the width of its pass or of each skin.
struct WallBeads {
  WallPrint how = WallPrint::kOnePass;
  double bead_width_m = 0.0;  ///< the pass's or each skin's width, m; 0 when not printed
};

/// The fewest beads, each within the spec's range, that make up a wall `thickness_m`
/// thick (within a micrometre): one pass up to the widest bead; two skins of half the wall
/// up to twice the nozzle's width; from there, skins of the nozzle's width and the
/// pattern's fill between them. The one statement of the rule: the slicer, the project's
/// check, `validate` and the tests call it.
WallBeads wall_beads(double thickness_m, const BeadSpec& spec);

/// What a bead is to its wall.
enum class BeadRole {
  kPass,  ///< a whole wall in one pass along its middle (a wall one bead thick)
  kSkin,  ///< along a face of a thicker wall, or a return around its end
  kCore,  ///< a poured core along the wall's middle (pattern solid)
  kTie,   ///< one leg of a zig-zag tie between the skins (pattern skins-with-ties)
};

/// "pass", "skin", "core", "tie".
const char* bead_role_name(BeadRole role);
std::optional<BeadRole> parse_bead_role(const std::string& name);

}  // namespace ccbuild::floors
