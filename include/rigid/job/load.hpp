#pragma once
/// A job from its job file (io::read_job_file), checked and assembled: the [run] settings
/// parsed into RunOverrides and applied, every object expanded into its variants, the cell count
/// bounded; and the overrides of a command line applied on top.
#include <string>

#include "rigid/job/job.hpp"
#include "rigid/job/run_overrides.hpp"

namespace rigid::job {

/// Reads and checks a job file. Every problem is a rigid::InputError naming the file and line,
/// before any work starts.
Job load_job(const std::string& path);

/// The [run] table's settings, parsed and checked (errors name the job file and line).
RunOverrides overrides_of(const io::RunTable& run, const std::string& path);

/// Applies overrides given on a command line (filled by the caller, which names its flags) over
/// the job's own. The flags given enter the job's text (and with the accuracy preset its hash),
/// so a resume under other settings is refused; an effects flag that leaves the job's value as
/// it was changes nothing.
void apply_command_line(Job& job, const RunOverrides& flags);

}  // namespace rigid::job
