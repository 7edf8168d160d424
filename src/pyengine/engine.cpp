// rigidpy._engine: one simulation through the C++ engine for rigidpy.run (src/python/rigidpy/
// simulation.py turns what it returns into an xarray Dataset). It takes the path `rigid run` takes
// (src/app/run_command.cpp): a job of one cell built from the settings (job::one_cell_job,
// job::set_text_setting), its model (job::assemble_model) and its case (job::simulate_one_cell);
// bad input raises rigidpy.errors.InputError with the one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/job/job.hpp"
#include "rigid/job/model.hpp"
#include "rigid/motion/ground_motion.hpp"
#include "rigid/scenario/history.hpp"
#include "rigid/scenario/rocking2d.hpp"

namespace py = pybind11;

namespace {

using rigid::InputError;
namespace job = rigid::job;
namespace scenario = rigid::scenario;

// The settings of rigidpy.run, as its keyword arguments (None: the default `rigid run` takes).
struct RunRequest {
  std::string scene;
  std::string motion;  // AT2 set spec: NAME-X.AT2 or H1.AT2,H2.AT2[,V.AT2]; empty: no motion
  double target_pga_g = 0;
  double factor = 1;
  double start_s = 0;
  double end_s = std::numeric_limits<double>::infinity();
  double rotation_deg = 0;
  std::optional<std::string> contact, model, accuracy, effects, integrator, state;
  std::optional<double> duration_s, free_time_s, dt_s, safety;
  double interval_s = 0.01;
};

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("", 0, what);
}

job::RunOverrides overrides_of(const RunRequest& r) {
  job::RunOverrides o;
  const auto text = [&](job::Setting setting, const char* name, const std::optional<std::string>& value) {
    if (value) job::set_text_setting(o, setting, *value, {"", 0, name});
  };
  text(job::Setting::contact, "contact", r.contact);
  text(job::Setting::model, "model", r.model);
  text(job::Setting::accuracy, "accuracy", r.accuracy);
  text(job::Setting::effects, "effects", r.effects);
  text(job::Setting::integrator, "integrator", r.integrator);
  const auto positive = [](const char* name, const std::optional<double>& v, bool zero_ok) {
    require(!v || (std::isfinite(*v) && (*v > 0 || (zero_ok && *v == 0))),
            std::string(name) + " = " + std::to_string(v.value_or(0)) + ": must be a " +
                (zero_ok ? "number >= 0" : "positive number"));
  };
  positive("duration", r.duration_s, false);
  positive("free_time", r.free_time_s, true);
  positive("dt", r.dt_s, false);
  positive("safety", r.safety, false);
  o.duration = r.duration_s.value_or(0);
  o.free_time = r.free_time_s.value_or(5.0);
  if (r.dt_s) o.dt = r.dt_s;
  if (r.safety) o.safety = r.safety;
  return o;
}

rigid::motion::GroundMotion motion_of(const RunRequest& r) {
  if (r.motion.empty()) return {};
  require(std::isfinite(r.factor), "factor: must be a finite number");
  require(r.target_pga_g >= 0 && std::isfinite(r.target_pga_g), "target_pga: must be a positive number of g");
  require(r.start_s >= 0 && std::isfinite(r.start_s), "start: must be a number of seconds >= 0");
  require(r.end_s > 0, "end: must be a positive number of seconds");
  require(std::isfinite(r.rotation_deg) && std::abs(r.rotation_deg) <= 1e6,
          "rotation: must be a finite angle in degrees");
  rigid::motion::MotionTransform t;
  t.start = r.start_s;
  t.end = r.end_s;
  t.factor = r.factor;
  t.target_pga_g = r.target_pga_g;
  t.rotation = r.rotation_deg * rigid::kPi / 180.0;
  return rigid::motion::transformed(rigid::io::read_motion_set(r.motion), t);
}

template <class T>
py::array_t<T> array(const std::vector<T>& v, std::vector<py::ssize_t> shape) {
  py::array_t<T> a(shape);
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict outcome_dict(const scenario::RunOutcome& r) {
  py::dict d;
  d["overturned"] = r.overturned;
  d["failure_time_s"] = r.failure_time_s ? py::cast(*r.failure_time_s) : py::none();
  d["failed_block"] = r.failed_block;
  d["steps"] = r.steps;
  d["dt_s"] = r.dt_s;
  d["simulated_s"] = r.simulated_s;
  d["max_tilt_deg"] = r.max_tilt_rad * 180.0 / rigid::kPi;
  d["max_slip_m"] = r.max_slip_m;
  d["max_overlap_m"] = r.max_overlap_m;
  d["ended_at_rest"] = r.ended_at_rest;
  d["unconverged_steps"] = r.unconverged_steps;
  d["max_solver_sweeps"] = r.max_solver_sweeps;
  return d;
}

py::dict history_dict(const scenario::History& h) {
  const auto n = py::ssize_t(h.frames());
  const auto b = py::ssize_t(h.blocks.size());
  py::dict d;
  d["block"] = h.blocks;
  d["base_height_m"] = h.base_height_m;
  d["time_s"] = array(h.time_s, {n});
  d["tilt_rad"] = array(h.tilt_rad, {n, b});
  d["slip_m"] = array(h.slip_m, {n, b});
  d["position_m"] = array(h.position_m, {n, b, 3});
  d["orientation"] = array(h.orientation, {n, b, 4});
  d["contacts"] = array(h.contacts, {n, b});
  d["contact_force_n"] = array(h.contact_force_n, {n, b, 3});
  d["table_displacement_m"] = array(h.table_displacement_m, {n, 3});
  d["table_velocity_m_s"] = array(h.table_velocity_m_s, {n, 3});
  d["table_acceleration_m_s2"] = array(h.table_acceleration_m_s2, {n, 3});
  return d;
}

// One run: {"outcome": ..., "engine": "dem3d"|"rocking2d", "warnings": [...], "motion": {...},
// "history": {...} (dem3d only)}.
py::dict run(const RunRequest& r) {
  require(std::isfinite(r.interval_s) && r.interval_s > 0, "interval: must be a positive number of seconds");
  scenario::Scene scene = rigid::io::load_scene(r.scene);
  const std::vector<std::string> warnings = scene.warnings;
  if (r.state) rigid::io::apply_state(*r.state, scene);
  job::Job one = job::one_cell_job(overrides_of(r));
  const bool block2d = one.engine == scenario::Engine::rocking2d;
  if (block2d) {
    require(!r.dt_s && !r.safety && !r.integrator,
            "dt, safety and integrator do not apply to model rocking2d (its integrator takes fixed steps of its "
            "own); leave them out or use model dem3d");
    scenario::rocking_block_of(scene);
  }
  rigid::motion::GroundMotion m = motion_of(r);
  py::dict motion;
  motion["name"] = m.name;
  motion["dt_s"] = m.dt;
  motion["duration_s"] = m.duration();
  std::optional<scenario::HistoryRecorder> recorder;
  scenario::RunOutcome outcome;
  {
    py::gil_scoped_release release;  // the simulation touches no Python object
    if (!block2d) {
      recorder.emplace(m);
      one.run.observer = [&recorder](const rigid::dynamics::World& w) { recorder->record(w); };
      one.run.observe_interval = r.interval_s;
    }
    const scenario::Model model = job::assemble_model(one, {std::move(scene)}, {m});
    outcome = job::simulate_one_cell(one, model);
  }
  py::dict out;
  out["outcome"] = outcome_dict(outcome);
  out["engine"] = block2d ? "rocking2d" : "dem3d";
  out["warnings"] = warnings;
  out["motion"] = motion;
  if (recorder) out["history"] = history_dict(recorder->history());
  return out;
}

}  // namespace

PYBIND11_MODULE(_engine, mod) {
  mod.doc() = "Rigid's C++ engine: one simulation (rigidpy.run is the interface)";
  // rigid::InputError (a bad scene, record or setting) as the package's own InputError
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      const py::object error = py::module_::import("rigidpy.errors").attr("InputError");
      PyErr_SetString(error.ptr(), e.what());
    }
  });
  py::class_<RunRequest>(mod, "RunRequest")
      .def(py::init<>())
      .def_readwrite("scene", &RunRequest::scene)
      .def_readwrite("motion", &RunRequest::motion)
      .def_readwrite("target_pga_g", &RunRequest::target_pga_g)
      .def_readwrite("factor", &RunRequest::factor)
      .def_readwrite("start_s", &RunRequest::start_s)
      .def_readwrite("end_s", &RunRequest::end_s)
      .def_readwrite("rotation_deg", &RunRequest::rotation_deg)
      .def_readwrite("contact", &RunRequest::contact)
      .def_readwrite("model", &RunRequest::model)
      .def_readwrite("accuracy", &RunRequest::accuracy)
      .def_readwrite("effects", &RunRequest::effects)
      .def_readwrite("integrator", &RunRequest::integrator)
      .def_readwrite("state", &RunRequest::state)
      .def_readwrite("duration_s", &RunRequest::duration_s)
      .def_readwrite("free_time_s", &RunRequest::free_time_s)
      .def_readwrite("dt_s", &RunRequest::dt_s)
      .def_readwrite("safety", &RunRequest::safety)
      .def_readwrite("interval_s", &RunRequest::interval_s);
  mod.def("run", &run, py::arg("request"), "One simulation: outcome, engine, warnings, motion and history");
}
