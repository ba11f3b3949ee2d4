#pragma once
// An imported building written as files a user can review and edit (`ccbuild import`):
// the building file, and its plans in ccbuild's own YAML beside it, each number written
// so that it reads back exactly, each wall and opening naming what it came from.

#include <filesystem>
#include <string>
#include <vector>

#include "ccbuild/floors/plan.hpp"
#include "ccbuild/import/dxf.hpp"
#include "ccbuild/import/ifc.hpp"

namespace ccbuild::import {

/// The shortest text that reads back as exactly `value`.
std::string exact_text(double value);

/// A floor plan in ccbuild's plan YAML, from `drawing`; each wall and opening's comment
/// names `what` it came from.
std::string plan_yaml(const floors::FloorPlan& plan, const std::string& drawing,
                      const std::string& what = "the drawing's entity");

/// The first line of a plan file written beside the building file `building`: says whose
/// it is, so that --force replaces it only when it is that building's.
std::string plan_file_mark(const std::filesystem::path& building);

/// Where the building and its plan files go, and the profiles it names.
struct BuildingFileNames {
  std::filesystem::path building;  ///< the building file
  std::string machine, material;   ///< as the building names them (relative to its folder)
};

/// The files of an import: the building file's text and its plans' (each with its mark).
struct BuildingFiles {
  std::string building;
  std::vector<std::filesystem::path> plan_paths;  ///< beside the building file
  std::vector<std::string> plans;                 ///< the text of each
  std::vector<std::string> quantities;  ///< IFC: each floor's walls as drawn against the model's
};

/// An IFC model's building: one plan file per distinct storey plan (floors with the same
/// plan share its file), levels as the model states them, what the import left out and the
/// model's own quantities as comments.
BuildingFiles ifc_building_files(const IfcImport& read, const std::string& model,
                                 const BuildingFileNames& names);

/// The one plan file of a DXF drawing's building, beside `building`.
std::filesystem::path dxf_plan_path(const std::filesystem::path& building);

/// A DXF drawing's building: `floors` floors of `floor_height_m`, each on the one plan.
BuildingFiles dxf_building_files(const DxfPlan& read, const std::string& drawing,
                                 const BuildingFileNames& names, int floors, double floor_height_m,
                                 double layer_height_m);

}  // namespace ccbuild::import
