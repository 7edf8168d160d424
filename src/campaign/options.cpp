#include "rigid/campaign/options.hpp"

#include "rigid/job/load.hpp"

namespace rigid::campaign {

job::Job load_campaign_job(const CampaignOptions& options) {
  job::Job job = job::load_job(options.job);
  if (!options.output.empty()) job.output = options.output;
  if (options.read_overrides) job::apply_command_line(job, options.read_overrides());
  return job;
}

}  // namespace rigid::campaign
