#include "rigid/campaign/options.hpp"

#include "rigid/core/error.hpp"
#include "rigid/io/job_file.hpp"

namespace rigid::campaign {
namespace {

// An override is part of what the cube holds: appended to the job text, so to its hash (set once
// at the end of load_campaign_job), a resume under another value is refused.
void record_override(scenario::Job& job, const std::string& flag, const std::string& value) {
  job.text += "\n# command line: " + flag + " " + value + "\n";
}

}  // namespace

scenario::Job load_campaign_job(const CampaignOptions& options) {
  scenario::Job job = io::load_job(options.job);
  if (!options.output.empty()) job.output = options.output;
  if (!options.model.empty()) {
    const std::optional<scenario::ModelKind> kind = scenario::parse_model_kind(options.model);
    if (!kind) throw InputError("", 0, "--model must be dem3d or rocking2d");
    job.model = *kind;
    record_override(job, "--model", options.model);
  }
  if (!options.contact.empty()) {
    contact::ContactModel model;
    if (!contact::parse_contact_model(options.contact, model)) {
      throw InputError("", 0, "--contact must be rigid or penalty");
    }
    job.contact = options.contact;
    record_override(job, "--contact", options.contact);
  }
  if (!options.effects.empty() && options.effects != "auto" && options.effects != "all") {
    throw InputError("", 0, "--effects must be auto or all");
  }
  if (!options.effects.empty() && (options.effects == "auto") != job.run.select_effects) {
    job.run.select_effects = options.effects == "auto";
    record_override(job, "--effects", options.effects);
  }
  if (!options.accuracy.empty()) {
    const scenario::AccuracyPreset* preset = scenario::find_accuracy_preset(options.accuracy);
    if (!preset) throw InputError("", 0, "--accuracy must be " + scenario::accuracy_preset_list());
    // the preset enters the job hash (io::job_hash), so a resume with another preset is refused
    job.accuracy = preset->name;
    scenario::apply_accuracy(*preset, job.accuracy_overrides, job.run);
  }
  job.hash = io::job_hash(job);
  return job;
}

}  // namespace rigid::campaign
