#pragma once
// The variant axis of a job file: a [sweep] table (Latin hypercube or grid over ranges and lists)
// or [[variant]] tables, read into a scenario::VariantSpace. Private to rigid_io (job_file.cpp).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "rigid/scenario/variant.hpp"

namespace rigid::io {

/// The job's variants (count() == 0 when it has neither [sweep] nor [[variant]]); `lines`
/// receives the line of the [sweep] table or of each [[variant]]. Every problem is a
/// rigid::InputError naming the job file and line: an unknown parameter, a value the parameter
/// does not admit (negative friction, restitution above 1), an empty range or list, both tables.
/// Scene files of a `scene` parameter are resolved against `base` and must exist; `objects` is
/// the number of [[object]]s (alternative scenes need exactly one).
scenario::VariantSpace read_variants(const toml::table& root, const std::string& path,
                                     const std::filesystem::path& base, std::uint64_t campaign_seed,
                                     std::size_t objects, std::vector<long>& lines);

}  // namespace rigid::io
