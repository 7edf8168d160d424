// `rigid motion info|synth|check`: ground-motion summaries, synthetic AT2 sets, and record lists
// checked against their listed GMRotI values. The work lives in rigid_io / rigid_motion; this
// file only parses options and prints.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "lab_input.hpp"
#include "output_options.hpp"
#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/io/csv.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/io/record_list.hpp"
#include "rigid/motion/butterworth.hpp"
#include "rigid/motion/lab_processing.hpp"
#include "rigid/motion/synth.hpp"

namespace rigid::app {

namespace {

struct InfoOptions {
  std::vector<std::string> sets;
  bool json = false;
  bool resample = false;
  double headerless_dt = 0.0;
  std::vector<double> sa_periods;
  std::string baseline = "none";
  LabFlags lab;
  std::string dump;  ///< --dump CSV: the lab motion's processed acceleration
};

struct SynthOptions {
  std::string kind;
  std::string out;
  double dt = 0.0, duration = 0.0, t0 = 0.0;
  double amplitude_g = 1.0, period = 0.0, azimuth_deg = 0.0;
  double pgv_m_s = 0.5, gamma = 2.0, nu_deg = 0.0;
  std::uint64_t seed = 1;
  double pga_g = 0.3, t_peak = 5.0, shape = 3.0, f_mid = 5.0, f_slope = -0.1, zeta_f = 0.3;
  double fc = 0.2, vertical_ratio = 0.6;
  int components = 3;
  int digits = 7;
};

struct CheckOptions {
  std::string list;
  std::string root;
  bool resample = false;
};

motion::Baseline parse_baseline(const std::string& s) {
  if (s == "none") return motion::Baseline::none;
  if (s == "linear") return motion::Baseline::velocity_linear;
  if (s == "quadratic") return motion::Baseline::velocity_quadratic;
  throw InputError("", 0, "--baseline must be none, linear or quadratic, got '" + s + "'");
}

// `motion info --lab`: what the pedestal would be driven with, as the lab's PGA, PGV, PGV/PGA
void run_lab_info(const InfoOptions& o) {
  const io::LabFormat format = lab_format_from_flags(o.lab);
  const motion::GroundMotion m = io::read_lab_motion(o.lab.file, format);
  const motion::Peaks p = motion::peaks(m.x, m.dt);
  const double pga_g = p.pga / kGravity, pgv_pga = p.pga > 0 ? p.pgv / p.pga : 0.0;
  if (o.json) {
    io::Json j;
    j["name"] = m.name;
    j["source"] = o.lab.file;
    j["channel"] = io::lab_channel_name(format.channel);
    j["processing"] = io::describe_lab_processing(format);
    j["npts"] = m.npts();
    j["dt_s"] = m.dt;
    j["duration_s"] = m.duration();
    j["pga_g"] = pga_g;
    j["pgv_m_s"] = p.pgv;
    j["pgv_pga_s"] = pgv_pga;
    j["pgd_m"] = p.pgd;
    // the filters as designed, in scipy's sos layout [b0, b1, b2, 1, a1, a2], so that they can be
    // checked against scipy.signal.butter: the band-pass, and the combined channel's crossover pair
    const auto sos_json = [](const std::vector<motion::Biquad>& sections) {
      io::Json rows = io::Json::array();
      for (const motion::Biquad& b : sections) rows.push_back({b.b0, b.b1, b.b2, 1.0, b.a1, b.a2});
      return rows;
    };
    const motion::LabProcessing& q = format.processing;
    j["filter_sos"] =
        q.band_pass ? sos_json(motion::butterworth_bandpass(q.low_hz, q.high_hz, q.order, m.dt)) : io::Json::array();
    if (format.channel == io::LabChannel::combined) {
      j["crossover_lowpass_sos"] = sos_json(motion::butterworth_lowpass(q.crossover_hz, q.order, m.dt));
      j["crossover_highpass_sos"] = sos_json(motion::butterworth_highpass(q.crossover_hz, q.order, m.dt));
    }
    std::printf("%s\n", io::json_line(j).c_str());
  } else {
    std::printf("%s  (%s)\n", m.name.c_str(), o.lab.file.c_str());
    std::printf("  %s\n", io::describe_lab_processing(format).c_str());
    std::printf("  npts %zu, dt %.6g s, duration %.4g s\n", m.npts(), m.dt, m.duration());
    std::printf("  PGA %.5g g, PGV %.5g m/s, PGV/PGA %.5g s, PGD %.5g m\n", pga_g, p.pgv, pgv_pga, p.pgd);
  }
  if (!o.dump.empty()) {
    // through the one CSV writer, never over the recording or format it came from
    io::refuse_output_over_inputs(o.dump, {o.lab.file, o.lab.format});
    io::write_output_file(o.dump, [&](std::ostream& out) {
      io::CsvWriter csv(out);
      csv.row({"t_s", "acceleration_m_s2"});
      for (std::size_t i = 0; i < m.x.size(); ++i) csv.field(double(i) * m.dt).field(m.x[i]).end_row();
    });
  }
}

void run_info(const InfoOptions& o) {
  if (!o.lab.file.empty()) {
    if (!o.sets.empty()) throw InputError("", 0, "give AT2 sets or --lab, not both");
    if (!o.sa_periods.empty() || o.resample || o.headerless_dt != 0.0 || o.baseline != "none")
      throw InputError("", 0,
                       "--sa, --resample, --dt and --baseline apply to AT2 sets (a lab recording's: --lab-baseline)");
    run_lab_info(o);
    return;
  }
  if (o.sets.empty()) throw InputError("", 0, "motion info needs a set (SET ...) or --lab FILE");
  if (!o.dump.empty()) throw InputError("", 0, "--dump applies to --lab recordings");
  io::SetReadOptions read;
  read.at2.dt = o.headerless_dt;
  read.align.resample = o.resample;
  motion::MeasureOptions measures;
  measures.baseline = parse_baseline(o.baseline);
  for (const std::string& set : o.sets) {
    const std::string r = io::motion_info_report(set, read, measures, o.sa_periods, o.json);
    std::fputs(r.c_str(), stdout);
    if (o.json) std::fputc('\n', stdout);
    std::fflush(stdout);
  }
}

// options given on the command line that do not apply to the chosen kind are errors
void check_applicable(CLI::App* cmd, const std::string& kind,
                      const std::map<std::string, std::vector<std::string>>& allowed) {
  const auto& ok = allowed.at(kind);
  for (const CLI::Option* opt : cmd->get_options()) {
    if (opt->count() == 0 || opt->get_lnames().empty()) continue;
    const std::string name = opt->get_lnames().front();
    if (name == "out" || name == "dt" || name == "duration" || name == "digits" || name == "help") continue;
    if (std::find(ok.begin(), ok.end(), name) == ok.end())
      throw InputError("", 0, "--" + name + " does not apply to synth kind '" + kind + "'");
  }
}

void run_synth(CLI::App* cmd, const SynthOptions& o) {
  const std::map<std::string, std::vector<std::string>> allowed = {
      {"sine", {"amplitude-g", "period", "t0", "azimuth-deg"}},
      {"cosine", {"amplitude-g", "period", "t0", "azimuth-deg"}},
      {"ricker", {"amplitude-g", "period", "t0", "azimuth-deg"}},
      {"mp", {"pgv-m-s", "period", "gamma", "nu-deg", "t0", "azimuth-deg"}},
      {"stochastic",
       {"seed", "pga-g", "t-peak", "shape", "f-mid", "f-slope", "zeta-f", "fc", "components", "vertical-ratio"}}};
  if (!allowed.count(o.kind))
    throw InputError("", 0, "unknown synth kind '" + o.kind + "' (sine, cosine, ricker, mp, stochastic)");
  check_applicable(cmd, o.kind, allowed);
  const std::filesystem::path out(o.out);
  const std::string name = out.filename().string();
  if (name.empty()) throw InputError("", 0, "--out must be DIR/NAME, got '" + o.out + "'");
  const bool azimuth = cmd->get_option("--azimuth-deg")->count() > 0;
  motion::GroundMotion m;
  if (o.kind == "sine" || o.kind == "cosine" || o.kind == "ricker") {
    motion::PulseParams p;
    p.kind = o.kind == "sine"     ? motion::PulseKind::one_sine
             : o.kind == "cosine" ? motion::PulseKind::one_cosine
                                  : motion::PulseKind::ricker;
    p.amplitude_g = o.amplitude_g;
    if (o.period != 0.0) p.period = o.period;
    p.t0 = o.t0;
    p.duration = o.duration;
    if (o.dt != 0.0) p.dt = o.dt;
    p.two_horizontals = azimuth;
    p.azimuth_deg = o.azimuth_deg;
    m = motion::pulse_motion(name, p);
  } else if (o.kind == "mp") {
    motion::MavroeidisParams p;
    p.pgv = o.pgv_m_s;
    if (o.period != 0.0) p.period = o.period;
    p.gamma = o.gamma;
    p.nu_deg = o.nu_deg;
    p.t0 = o.t0;
    p.duration = o.duration;
    if (o.dt != 0.0) p.dt = o.dt;
    p.two_horizontals = azimuth;
    p.azimuth_deg = o.azimuth_deg;
    m = motion::mavroeidis_motion(name, p);
  } else {
    motion::StochasticParams p;
    p.seed = o.seed;
    if (o.duration != 0.0) p.duration = o.duration;
    if (o.dt != 0.0) p.dt = o.dt;
    p.pga_g = o.pga_g;
    p.t_peak = o.t_peak;
    p.shape = o.shape;
    p.f_mid = o.f_mid;
    p.f_slope = o.f_slope;
    p.zeta_f = o.zeta_f;
    p.fc = o.fc;
    p.components = o.components;
    p.vertical_ratio = o.vertical_ratio;
    m = motion::stochastic_motion(name, p);
  }
  std::error_code ec;
  if (!out.parent_path().empty()) std::filesystem::create_directories(out.parent_path(), ec);
  io::At2WriteOptions w;
  w.digits = o.digits;
  w.title = "RIGID SYNTHETIC GROUND MOTION (PEER NGA AT2 FORMAT)";
  for (const std::string& path : io::write_motion_set(m, o.out, w)) std::printf("%s\n", path.c_str());
}

void run_check(const CheckOptions& o) {
  const io::RecordList list = io::read_record_list(o.list);
  io::SetReadOptions read;
  read.base_dir = o.root.empty() ? list.base_dir : o.root;
  read.align.resample = o.resample;
  for (const io::RecordEntry& e : list.records) {
    const std::string r = io::to_json(io::check_record(e, read));
    std::printf("%s\n", r.c_str());
    std::fflush(stdout);
  }
}

}  // namespace

void register_motion_command(CLI::App& app) {
  CLI::App* motion = app.add_subcommand("motion", "Ground motions: summaries, synthetic records, record lists");
  motion->require_subcommand(1);

  auto info = std::make_shared<InfoOptions>();
  CLI::App* ic =
      motion->add_subcommand("info",
                             "Summarise ground-motion sets: npts, dt, duration, per-component PGA (g), PGV (cm/s), "
                             "PGD (cm) and, with two horizontals, GMRotD50/GMRotI50/RotD50 (Boore 2006, 2010)");
  ic->add_option("sets", info->sets,
                 "SET = NAME-X.AT2 (NAME-Y.AT2, NAME-Z.AT2 join when present) or H1.AT2,H2.AT2[,V.AT2] "
                 "(roles may be explicit: x=...,y=...,z=...)");
  ic->add_flag("--json", info->json, "One JSON object per set, one per line");
  ic->add_flag("--resample", info->resample,
               "Components of unequal dt or length: resample to the smallest dt (linear) and "
               "zero-pad to the longest, instead of an error");
  ic->add_option("--dt", info->headerless_dt, "Time step of headerless AT2 files (s)");
  ic->add_option("--sa", info->sa_periods, "5%-damped PSA at these periods (s), comma-separated")
      ->delimiter(',')
      ->allow_extra_args(false);  // `--sa 1,2 SET...`: the sets stay positional
  ic->add_option("--baseline", info->baseline,
                 "Velocity baseline correction: none (PEER records are processed), "
                 "linear or quadratic (least-squares polynomial through v(0)=0 removed)")
      ->capture_default_str();
  add_lab_options(*ic, info->lab);
  ic->add_option("--dump", info->dump, "With --lab: write the processed acceleration as CSV (t_s, acceleration_m_s2)");
  ic->callback([info] {
    reject_lab_flags_without_file(info->lab);
    run_info(*info);
  });

  auto synth = std::make_shared<SynthOptions>();
  CLI::App* sc = motion->add_subcommand("synth",
                                        "Write a synthetic AT2 set DIR/NAME-X.AT2 (+ -Y, -Z): sine | cosine | ricker "
                                        "(acceleration pulses), mp (Mavroeidis-Papageorgiou 2003 velocity pulse), "
                                        "stochastic (Rezaeian-Der Kiureghian 2008, seeded)");
  sc->add_option("kind", synth->kind, "sine, cosine, ricker, mp or stochastic")->required();
  add_output_prefix(*sc, synth->out, "the AT2 set NAME-X.AT2 (+ -Y, -Z)")->required();
  sc->add_option("--dt", synth->dt, "Time step (s); default 0.005 for pulses, 0.01 stochastic");
  sc->add_option("--duration", synth->duration, "Record length (s); default: pulse + quiet time, 20 s stochastic");
  sc->add_option("--digits", synth->digits, "Significant digits written (7: PEER's E15.7)")->capture_default_str();
  sc->add_option("--amplitude-g", synth->amplitude_g, "Pulse acceleration amplitude (g)")->capture_default_str();
  sc->add_option("--period", synth->period, "Pulse period Tp (s); default 0.5 (mp: 1)");
  sc->add_option("--t0", synth->t0, "Pulse start (sine/cosine/ricker) or centre (mp) (s)")->capture_default_str();
  sc->add_option("--azimuth-deg", synth->azimuth_deg,
                 "Direction of the pulse from x toward y (deg); writes X and Y (default: X only)");
  sc->add_option("--pgv-m-s", synth->pgv_m_s, "mp: velocity amplitude A (m/s)")->capture_default_str();
  sc->add_option("--gamma", synth->gamma, "mp: oscillatory character gamma (> 1)")->capture_default_str();
  sc->add_option("--nu-deg", synth->nu_deg, "mp: phase nu (deg)")->capture_default_str();
  sc->add_option("--seed", synth->seed, "stochastic: seed")->capture_default_str();
  sc->add_option("--pga-g", synth->pga_g, "stochastic: PGA of each horizontal (g)")->capture_default_str();
  sc->add_option("--t-peak", synth->t_peak, "stochastic: time of peak intensity (s)")->capture_default_str();
  sc->add_option("--shape", synth->shape, "stochastic: modulating shape alpha2 (> 1)")->capture_default_str();
  sc->add_option("--f-mid", synth->f_mid, "stochastic: filter frequency at t-peak (Hz)")->capture_default_str();
  sc->add_option("--f-slope", synth->f_slope, "stochastic: filter frequency slope (Hz/s)")->capture_default_str();
  sc->add_option("--zeta-f", synth->zeta_f, "stochastic: filter damping ratio")->capture_default_str();
  sc->add_option("--fc", synth->fc, "stochastic: high-pass corner (Hz)")->capture_default_str();
  sc->add_option("--components", synth->components, "stochastic: 1 (X), 2 (X,Y) or 3 (X,Y,Z)")->capture_default_str();
  sc->add_option("--vertical-ratio", synth->vertical_ratio, "stochastic: vertical/horizontal PGA")
      ->capture_default_str();
  sc->callback([sc, synth] { run_synth(sc, *synth); });

  auto check = std::make_shared<CheckOptions>();
  CLI::App* cc = motion->add_subcommand("check",
                                        "Compare a record list's GMRotI50 PGA/PGV (table TSV or .ABF) with the values "
                                        "computed from the files; one JSON line per record");
  cc->add_option("list", check->list, "Record list: table .tsv or batch .abf")->required();
  cc->add_option("--root", check->root, "Directory of the records (default: the list's)");
  cc->add_flag("--resample", check->resample, "Resample/zero-pad unequal components");
  cc->callback([check] { run_check(*check); });
}

}  // namespace rigid::app
