// The writer that mirrors read_job_file: a JobFile out as a job file the reader takes back as the
// same JobFile. Commands that design their own campaigns (the shake-table workflow) write their
// jobs through it, so what they run is an ordinary job: resumable, hashed, open to `rigid campaign`.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <toml++/toml.h>

#include "job_record_names.hpp"
#include "lab_toml.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/job_file.hpp"
#include "rigid/io/output_file.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

std::string absolute(const std::string& p) { return fs::absolute(p).lexically_normal().string(); }

// A "start:stop:step" range, from the stated decimals it was read as (read_job_file keeps them in
// scales_g and its float sums in drive_scales_g): %.15g gives back the digits that were written.
std::string scale_range(const std::vector<double>& stated) {
  char text[96];
  const double step = stated.size() > 1 ? stated[1] - stated[0] : 1.0;
  std::snprintf(text, sizeof text, "%.15g:%.15g:%.12g", stated.front(), stated.back(), step);
  return text;
}

toml::table campaign_table(const JobFile& job) {
  const JobFile defaults;
  toml::table t{{"seed", static_cast<std::int64_t>(job.seed)}, {"stop_after", job.stop_after}};
  if (!job.output.empty()) t.insert("output", absolute(job.output));
  if (job.scales_g == std::vector<double>{kAsRecordedScale}) {
    t.insert("scales", "as recorded");
  } else if (!job.drive_scales_g.empty()) {
    t.insert("scales", scale_range(job.scales_g));
  } else {
    toml::array scales;
    for (double s : job.scales_g) scales.push_back(s);
    t.insert("scales", scales);
  }
  if (job.rotation_angles_deg.empty()) {
    t.insert("rotations", job.rotations);
  } else {
    toml::array angles;
    for (double a : job.rotation_angles_deg) angles.push_back(a);
    t.insert("rotation_angles_deg", angles);
  }
  if (job.checkpoint_interval_s != defaults.checkpoint_interval_s)
    t.insert("checkpoint_interval_s", job.checkpoint_interval_s);
  if (job.grace_s != defaults.grace_s) t.insert("grace_s", job.grace_s);
  return t;
}

toml::array object_tables(const JobFile& job) {
  toml::array objects;
  for (const JobFileObject& o : job.objects) {
    toml::table t{{"name", o.name}, {"scene", absolute(o.scene)}};
    if (!o.state.empty()) t.insert("state", absolute(o.state));
    objects.push_back(t);
  }
  return objects;
}

// Every variant as listed values: a sampled [sweep] is written as the variants it drew.
toml::array variant_tables(const scenario::VariantSpace& space) {
  toml::array variants;
  for (const auto& values : space.variants) {
    toml::table t;
    for (std::size_t k = 0; k < space.keys.size(); ++k) {
      const scenario::VariantParameterInfo& info = scenario::variant_parameter(space.keys[k]);
      const scenario::VariantValue& v = values[k];
      if (!info.text) {
        t.insert(info.name, v.number);
      } else if (space.keys[k] == scenario::VariantKey::scene) {
        t.insert(info.name, absolute(v.text));
      } else {
        t.insert(info.name, v.text);
      }
    }
    variants.push_back(t);
  }
  return variants;
}

toml::array record_tables(const JobFile& job) {
  toml::array records;
  for (const JobRecord& r : job.records) {
    toml::table t;
    // a set spec keeps its roles (x=, y=, z=); each file absolute
    std::string spec, part;
    std::stringstream in(r.spec);
    while (std::getline(in, part, ',')) {
      const auto eq = part.find('=');
      const std::string role = eq == std::string::npos ? "" : part.substr(0, eq + 1);
      spec += (spec.empty() ? "" : ",") + role + absolute(part.substr(role.size()));
    }
    t.insert(r.lab ? "lab" : "motion", spec);
    const std::string derived = r.lab ? lab_record_name(r.spec) : record_name(r.spec);
    if (!r.name.empty() && r.name != derived) t.insert("name", r.name);  // empty: the reader derives it
    // a window with an end is written whole; an open one only by its start
    if (std::isfinite(r.end)) {
      t.insert("start", r.start);
      t.insert("end", r.end);
    } else if (r.start != 0) {
      t.insert("start", r.start);
    }
    if (!r.earthquake.empty()) t.insert("earthquake", r.earthquake);
    if (r.resample) t.insert("align", "resample");
    records.push_back(t);
  }
  return records;
}

toml::table run_table(const RunTable& run) {
  toml::table t;
  const auto text = [&](const char* key, const std::optional<RunText>& v) {
    if (v && v->text) t.insert(key, *v->text);
  };
  const auto number = [&](const char* key, const std::optional<double>& v) {
    if (v) t.insert(key, *v);
  };
  text("model", run.model);
  text("contact", run.contact);
  text("effects", run.effects);
  text("accuracy", run.accuracy);
  text("integrator", run.integrator);
  number("duration_s", run.duration_s);
  number("free_time_s", run.free_time_s);
  number("dt_s", run.dt_s);
  number("safety", run.safety);
  number("solver_tolerance", run.solver_tolerance);
  if (run.solver_max_sweeps) t.insert("solver_max_sweeps", static_cast<std::int64_t>(*run.solver_max_sweeps));
  return t;
}

}  // namespace

void write_job_file(const std::string& path, const JobFile& job, const std::string& comment) {
  toml::table root;
  root.insert("campaign", campaign_table(job));
  root.insert("object", object_tables(job));
  if (job.variants.count() > 0) root.insert("variant", variant_tables(job.variants));
  if (!job.record_list.empty()) {
    root.insert("records", absolute(job.record_list));
  } else {
    root.insert("record", record_tables(job));
  }
  const bool lab = std::any_of(job.records.begin(), job.records.end(), [](const JobRecord& r) { return r.lab; });
  if (lab) {
    const toml::table format = lab_format_table(job.lab_format);
    if (!format.empty()) root.insert("lab", format);
  }
  const toml::table run = run_table(job.run);
  if (!run.empty()) root.insert("run", run);

  std::ostringstream text;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) text << "# " << line << "\n";
  text << toml::toml_formatter(root, toml::toml_formatter::default_flags & ~toml::format_flags::indentation) << "\n";
  write_output_file(path, [&](std::ostream& out) { out << text.str(); });
}

}  // namespace rigid::io
