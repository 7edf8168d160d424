// rigid_ode_peer: the `rigid bench` peer scene run in ODE (Open Dynamics Engine), as an outside
// reference for speed and for the overturning threshold. Not part of the engine: it uses none of
// Rigid's code, only the same scene (src/app/bench_command.cpp, library::block_on_pedestal).
//
// Scene: block 2b x 0.5 x 2h, h = 0.5 m, b = h tan(0.2), density 2600, friction 0.6, centred on
// a 2(b + 0.02) x 0.54 x 0.2 m pedestal whose top is z = 0. The pedestal is a kinematic body
// moved by the ground (as in Rigid); ground acceleration a(t) = A sin(2 pi t / T) along x for
// 0 <= t <= T = 0.5 s, zero after. Overturn: the block's centroid below the pedestal's lowest
// point (z = -0.2), Rigid's default failure rule; the run stops there, otherwise at 15 s.
#include <ode/ode.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kGravity = 9.80665;
constexpr double kPi = std::numbers::pi;

struct Options {
  double dt = 1e-3;        // s
  double duration = 15.0;  // s
  double period = 0.5;     // s, pulse period T
  double amplitude = -1;   // g; < 0: not asked
  bool threshold = false;
  bool quick = false;  // dWorldQuickStep instead of dWorldStep
  int repeat = 1;
  bool json = false;
  double erp = 0.2;
  double cfm = 1e-9;
  double tolerance = 0.0025;  // g, bisection bracket width
};

// ODE reports solver trouble (e.g. "LCP internal error") through dMessage and carries on; count
// those messages per run and say so, rather than print them mid-output.
int g_solver_messages = 0;
double g_first_message_time = -1, g_time = 0;
void on_message(int, const char*, va_list) {
  if (g_solver_messages++ == 0) g_first_message_time = g_time;
}

// Ground displacement along x of the one-sine pulse (unit: m); integrating the velocity exactly
// lets the pedestal land on d(t1) every step instead of drifting with a sampled velocity.
double ground_x(double amp, double period, double t) {
  const double w = 2 * kPi / period;
  const double c = amp / w;  // velocity scale A T / (2 pi)
  if (t >= period) return c * period;
  return c * (t - std::sin(w * t) / w);
}

struct Run {
  bool overturned = false;
  long steps = 0;
  double failure_time = 0;  // s
  double wall = 0;          // s, whole run: world set-up, stepping, tear-down
  double stepping = 0;      // s, the step loop alone
  double stepping_cpu = 0;  // s, its CPU time: less sensitive than wall to a busy machine
  double max_tilt = 0;      // rad
  double max_drift = 0;     // m, centroid displacement relative to the pedestal
  int solver_messages = 0;
  double first_message_time = -1;  // s
};

Run simulate(double amplitude_g, const Options& o) {
  const auto start = Clock::now();
  const double h = 0.5, b = h * std::tan(0.2), depth = 0.5, density = 2600, mu = 0.6;
  const double margin = 0.02, ped_height = 0.2;
  const double amp = amplitude_g * kGravity;

  dWorldID world = dWorldCreate();
  dWorldSetGravity(world, 0, 0, -kGravity);
  // ERP 0.2 removes a fifth of any overlap per step: enough to keep the block on the surface
  // without the popping that ERP near 1 gives. CFM 1e-9 makes contacts effectively rigid
  // (k = ERP / (dt CFM) = 2e11 N/m at 1 ms: the block sinks a few nanometres under its weight)
  // while keeping the LCP regular.
  dWorldSetERP(world, o.erp);
  dWorldSetCFM(world, o.cfm);
  // Plastic, rigid contact: no extra slop layer, no auto-disable (the block must react to the
  // pulse from rest).
  dWorldSetContactSurfaceLayer(world, 0);
  dWorldSetAutoDisableFlag(world, 0);
  dJointGroupID contacts = dJointGroupCreate(0);

  dBodyID pedestal = dBodyCreate(world);
  dBodySetKinematic(pedestal);
  dBodySetPosition(pedestal, 0, 0, -0.5 * ped_height);
  dGeomID ped_geom = dCreateBox(nullptr, 2 * (b + margin), depth + 2 * margin, ped_height);
  dGeomSetBody(ped_geom, pedestal);

  dBodyID block = dBodyCreate(world);
  dMass mass;
  dMassSetBox(&mass, density, 2 * b, depth, 2 * h);
  dBodySetMass(block, &mass);
  dBodySetPosition(block, 0, 0, h);
  dGeomID block_geom = dCreateBox(nullptr, 2 * b, depth, 2 * h);
  dGeomSetBody(block_geom, block);

  Run r;
  g_solver_messages = 0;
  g_first_message_time = -1;
  const long steps = std::lround(o.duration / o.dt);
  dContact contact[8];
  const auto loop_start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  for (long k = 0; k < steps; ++k) {
    const double t0 = double(k) * o.dt, t1 = double(k + 1) * o.dt;
    // Kinematic pedestal: its velocity is held during the step, so the step's mean velocity
    // takes it from d(t0) to d(t1) exactly.
    const double x0 = ground_x(amp, o.period, t0), x1 = ground_x(amp, o.period, t1);
    dBodySetPosition(pedestal, x0, 0, -0.5 * ped_height);
    dBodySetLinearVel(pedestal, (x1 - x0) / o.dt, 0, 0);

    // Only two geoms: dCollide directly, no space needed. Box-box gives up to 8 points.
    const int n = dCollide(block_geom, ped_geom, 8, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
      // Approx1: friction limit mu * normal force per direction (a Coulomb pyramid);
      // without it ODE's mu is a fixed force in newtons. No dContactBounce: plastic impacts.
      contact[i].surface = dSurfaceParameters{};
      contact[i].surface.mode = dContactApprox1;
      contact[i].surface.mu = mu;
      dJointID j = dJointCreateContact(world, contacts, &contact[i]);
      dJointAttach(j, block, pedestal);
    }
    g_time = t1;
    if (o.quick)
      dWorldQuickStep(world, o.dt);
    else
      dWorldStep(world, o.dt);
    dJointGroupEmpty(contacts);
    ++r.steps;

    const dReal* p = dBodyGetPosition(block);
    const dReal* R = dBodyGetRotation(block);  // 3x4 row-major; R[10]: body z . world z
    r.max_tilt = std::max(r.max_tilt, std::acos(std::clamp(double(R[10]), -1.0, 1.0)));
    r.max_drift = std::max(r.max_drift, std::hypot(p[0] - x1, p[1], p[2] - h));
    if (p[2] < -ped_height) {
      r.overturned = true;
      r.failure_time = t1;
      break;
    }
  }
  r.stepping = std::chrono::duration<double>(Clock::now() - loop_start).count();
  r.stepping_cpu = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  r.solver_messages = g_solver_messages;
  r.first_message_time = g_first_message_time;

  dGeomDestroy(block_geom);
  dGeomDestroy(ped_geom);
  dJointGroupDestroy(contacts);
  dWorldDestroy(world);
  r.wall = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Medians of the timings of many runs.
struct Timings {
  std::vector<double> wall, stepping, cpu;
  void add(const Run& r) {
    wall.push_back(r.wall);
    stepping.push_back(r.stepping);
    cpu.push_back(r.stepping_cpu);
  }
};

// Same search as `rigid bench`: bisection between 0.2 g and 0.5 g until the bracket is at most
// 0.0025 g wide (7 runs); the threshold is the bracket's middle.
struct Threshold {
  double g = 0;
  int runs = 0;
  int solver_messages = 0;
};
Threshold threshold(const Options& o, Timings& times) {
  Threshold t;
  double lo = 0.2, hi = 0.5;
  while (hi - lo > o.tolerance) {
    const double mid = 0.5 * (lo + hi);
    const Run r = simulate(mid, o);
    (r.overturned ? hi : lo) = mid;
    times.add(r);
    t.solver_messages += r.solver_messages;
    ++t.runs;
  }
  t.g = 0.5 * (lo + hi);
  return t;
}

[[noreturn]] void usage(int code) {
  std::fprintf(code ? stderr : stdout,
               "usage: rigid_ode_peer (--amplitude G | --threshold) [options]\n"
               "  --amplitude G    one run at peak ground acceleration G (in g); G = 0 checks rest\n"
               "  --threshold      overturning amplitude by bisection between 0.2 g and 0.5 g\n"
               "  --tolerance G    bisection bracket width in g (default 0.0025)\n"
               "  --dt S           time step in s (default 0.001)\n"
               "  --quick          dWorldQuickStep (iterative, 20 iterations) instead of dWorldStep\n"
               "  --erp E --cfm C  world ERP and CFM (default 0.2 and 1e-9)\n"
               "  --repeat N       repeat N times; walls are medians over all runs\n"
               "  --json           print one JSON object\n");
  std::exit(code);
}

Options parse(int argc, char** argv) {
  Options o;
  auto value = [&](int& i) {
    if (i + 1 >= argc) usage(2);
    char* end = nullptr;
    const double v = std::strtod(argv[++i], &end);
    if (*end != '\0' || !std::isfinite(v)) usage(2);
    return v;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--amplitude")
      o.amplitude = value(i);
    else if (a == "--threshold")
      o.threshold = true;
    else if (a == "--tolerance")
      o.tolerance = value(i);
    else if (a == "--dt")
      o.dt = value(i);
    else if (a == "--quick")
      o.quick = true;
    else if (a == "--erp")
      o.erp = value(i);
    else if (a == "--cfm")
      o.cfm = value(i);
    else if (a == "--repeat")
      o.repeat = int(value(i));
    else if (a == "--json")
      o.json = true;
    else if (a == "--help" || a == "-h")
      usage(0);
    else
      usage(2);
  }
  const bool ok = (o.amplitude >= 0) != o.threshold && o.dt > 0 && o.dt <= 0.1 && o.tolerance > 0 && o.erp >= 0 &&
                  o.erp <= 1 && o.cfm >= 0 && o.repeat >= 1;
  if (!ok) usage(2);
  return o;
}

// The keys every --json line starts with: engine, solver and its settings.
nlohmann::ordered_json peer_json(const Options& o, const char* solver) {
  nlohmann::ordered_json j;
  j["engine"] = std::string("ODE ") + RIGID_ODE_VERSION;
  j["solver"] = solver;
  j["dt_s"] = o.dt;
  j["erp"] = o.erp;
  j["cfm"] = o.cfm;
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  dInitODE2(0);
  if (!dCheckConfiguration("ODE_double_precision")) {
    std::fprintf(stderr, "rigid_ode_peer: this ODE is single precision; the benchmark needs double\n");
    return 1;
  }
  dSetMessageHandler(on_message);
  const char* solver = o.quick ? "dWorldQuickStep" : "dWorldStep";
  Timings times;
  if (!o.threshold) {
    Run r;
    for (int i = 0; i < o.repeat; ++i) times.add(r = simulate(o.amplitude, o));
    const double wall = median(times.wall), stepping = median(times.stepping), cpu = median(times.cpu);
    char verdict[48] = "no";
    if (r.overturned) std::snprintf(verdict, sizeof verdict, "yes at %.4g s", r.failure_time);
    if (o.json) {
      nlohmann::ordered_json j = peer_json(o, solver);
      j["amplitude_g"] = o.amplitude;
      j["overturned"] = r.overturned;
      j["failure_time_s"] = r.overturned ? r.failure_time : -1.0;
      j["steps"] = r.steps;
      j["wall_s_median"] = wall;
      j["stepping_s_median"] = stepping;
      j["stepping_cpu_s_median"] = cpu;
      j["max_tilt_rad"] = r.max_tilt;
      j["max_drift_m"] = r.max_drift;
      j["solver_messages"] = r.solver_messages;
      j["repeat"] = o.repeat;
      std::printf("%s\n", j.dump().c_str());
    } else
      std::printf(
          "ODE %s, %s, dt %g s, ERP %g, CFM %g, one-sine %g g, T 0.5 s: overturned %s, %ld steps, "
          "%.4f s wall (stepping %.4f s wall, %.4f s CPU), max tilt %.4g rad, max drift %.3g m, "
          "%d solver messages; medians of %d\n",
          RIGID_ODE_VERSION, solver, o.dt, o.erp, o.cfm, o.amplitude, verdict, r.steps, wall, stepping, cpu, r.max_tilt,
          r.max_drift, r.solver_messages, o.repeat);
    if (r.solver_messages && !o.json) std::printf("  first solver message at t = %g s\n", r.first_message_time);
  } else {
    Threshold t;
    int messages = 0;
    for (int i = 0; i < o.repeat; ++i) messages += (t = threshold(o, times)).solver_messages;
    const double wall = median(times.wall), stepping = median(times.stepping), cpu = median(times.cpu);
    if (o.json) {
      nlohmann::ordered_json j = peer_json(o, solver);
      j["threshold_g"] = t.g;
      j["tolerance_g"] = o.tolerance;
      j["runs"] = t.runs;
      j["wall_s_per_run_median"] = wall;
      j["stepping_s_per_run_median"] = stepping;
      j["stepping_cpu_s_per_run_median"] = cpu;
      j["solver_messages"] = messages;
      j["repeat"] = o.repeat;
      std::printf("%s\n", j.dump().c_str());
    } else
      std::printf(
          "ODE %s, %s, dt %g s, ERP %g, CFM %g: overturning threshold %.4f g (bisected to %g g; 2D Housner "
          "0.2975 g); %d runs, %.4f s wall per run (stepping %.4f s wall, %.4f s CPU), %d solver "
          "messages; medians over %d search(es)\n",
          RIGID_ODE_VERSION, solver, o.dt, o.erp, o.cfm, t.g, o.tolerance, t.runs, wall, stepping, cpu, messages,
          o.repeat);
  }
  dCloseODE();
  return 0;
}
