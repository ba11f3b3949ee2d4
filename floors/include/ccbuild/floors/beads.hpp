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
  double bead_width_m = 0.0;  ///< the width one pass of the nozzle lays, m
  WallPattern pattern = WallPattern::kSolid;
};

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

/// How many beads wide a wall of `thickness_m` is for a bead of `bead_width_m`: 1 up to
/// one bead (within 1 micrometre), 0 strictly between one and two (such a wall cannot be
/// printed: one bead is too thin, two overlap), 2 from two beads on (the skins; whatever
/// lies between them is the pattern's).
int beads_across(double thickness_m, double bead_width_m);

}  // namespace ccbuild::floors
