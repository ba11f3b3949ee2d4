#pragma once
// The exports as files, shared by `ccbuild export` and `ccbuild schedule --export`.

#include <filesystem>
#include <string>
#include <vector>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/report/exports.hpp"

namespace ccbuild::cli {

/// The export formats: csv, ical, mspdi, days.
const std::vector<std::string>& export_formats();
/// Whether `format` needs dates (a site calendar or --start): all but csv.
bool export_needs_dates(const std::string& format);
/// The format of an export file by its extension: .csv csv, .ics ical, .xml mspdi, .txt
/// days. Throws InputError (field `field`) for another.
std::string export_format_of(const std::filesystem::path& path, const std::string& field);

/// Writes `format` of `document` for `path` (claimed in `outputs`, in place when they are
/// committed), and returns what was written, in words ("870 crew tasks and milestones ...
/// as iCalendar"). Throws InputError when it cannot be dated or written.
std::string write_export(const schedule::ScheduleDocument& document,
                         const report::ExportDates& dates, const std::string& format,
                         const std::filesystem::path& path, OutputClaims& outputs);

}  // namespace ccbuild::cli
