#include "rigid/io/design_job.hpp"

#include <filesystem>
#include <sstream>

#include <toml++/toml.h>

#include "input_file.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/output_file.hpp"

namespace rigid::io {

void write_design_job(const std::string& path, const DesignJob& job) {
  // the job lives in a work folder: relative paths (the caller's, against its working directory)
  // are written absolute
  const auto absolute = [](const std::string& p) { return std::filesystem::absolute(p).lexically_normal().string(); };
  toml::table root;
  toml::array angles;
  for (double a : job.rotation_angles_deg) angles.push_back(a);
  toml::table campaign{{"seed", static_cast<std::int64_t>(job.seed)},
                       {"rotation_angles_deg", angles},
                       {"stop_after", job.stop_after}};
  if (job.scale_list_g.empty()) {
    campaign.insert("scales", job.scales);
  } else {
    toml::array scales;
    for (double s : job.scale_list_g) scales.push_back(s);
    campaign.insert("scales", scales);
  }
  root.insert("campaign", campaign);
  toml::array objects;
  objects.push_back(toml::table{{"name", job.object_name}, {"scene", absolute(job.scene)}});
  root.insert("object", objects);
  if (!job.variants.empty()) {
    toml::array variants;
    for (const auto& v : job.variants) {
      toml::table t;
      for (const auto& [key, value] : v) {
        if (const double* d = std::get_if<double>(&value)) t.insert(key, *d);
        else t.insert(key, std::get<std::string>(value));
      }
      variants.push_back(t);
    }
    root.insert("variant", variants);
  }
  toml::array records;
  for (const auto& r : job.records)
    records.push_back(toml::table{{"lab", absolute(r.lab)}, {"start", r.start}, {"end", r.end}});
  root.insert("record", records);
  if (!job.lab_format_file.empty()) {
    const std::string text = read_input_file(job.lab_format_file, kMaxTextFileBytes);
    toml::table source;
    try {
      source = toml::parse(text, job.lab_format_file);
    } catch (const toml::parse_error& e) {
      throw InputError(job.lab_format_file, long(e.source().begin.line), std::string(e.description()));
    }
    const toml::table* lab = source["lab"].as_table();
    if (!lab) throw InputError(job.lab_format_file, 0, "has no [lab] table (the recordings' format)");
    root.insert("lab", *lab);
  }
  root.insert("run", toml::table{{"free_time_s", job.free_time_s}});

  std::ostringstream text;
  std::istringstream comment(job.comment);
  for (std::string line; std::getline(comment, line);) text << "# " << line << "\n";
  text << toml::toml_formatter(root, toml::toml_formatter::default_flags & ~toml::format_flags::indentation) << "\n";
  write_output_file(path, [&](std::ostream& out) { out << text.str(); });
}

}  // namespace rigid::io
