#pragma once
/// The objects a job simulates: each of its [[object]]s in each of its variants.
#include <vector>

#include "rigid/io/job_file.hpp"
#include "rigid/job/job.hpp"
#include "rigid/scenario/variant.hpp"

namespace rigid::job {

/// Every object in every variant, object-major (index base * variants + variant), with its base
/// index, variant index and the variant's alternative scene; the objects as they are (base and
/// variant -1) when `variants` has none.
std::vector<JobObject> expand_variants(const std::vector<io::JobFileObject>& objects,
                                       const scenario::VariantSpace& variants);

}  // namespace rigid::job
