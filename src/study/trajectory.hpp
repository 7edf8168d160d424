#pragma once
// Runs of the study's scenes sampled by the observer, their distance to a reference run, and the
// one-sine overturning threshold of a scene (module-private).
#include <chrono>
#include <vector>

#include "rigid/study/accuracy_study.hpp"

namespace rigid::study {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t);

/// Median; NaN for no values.
double median(std::vector<double> v);

struct Trajectory {
  std::vector<double> t;
  int nfree = 0;
  std::vector<Vec3> pos;         // centroid relative to the first fixed body, per free block
  std::vector<double> tilt;      // per free block (unit: rad)
  double energy_err = 0;         // largest energy gained from nothing (or drift, if conservative) / scale
  double max_rotation = 0;       // largest rotation of any free block from its start (unit: rad)
  double first_turn = kNoValue;  // first time a free block has turned more than 1 degree (unit: s)
  scenario::RunOutcome outcome;
  double wall = 0;
};

/// One case of the scene under `ground` (x component; empty: none), through scenario::simulate_case.
Trajectory run_trajectory(const scenario::Scene& scene, const motion::GroundMotion& ground,
                          scenario::RunSettings settings, bool conservative, double interval);

struct TrajectoryError {
  double tilt_rms_deg = 0, pos_rms_mm = 0, rel = 0;
};

// Both trajectories on one grid from 0 to the later end; a run that stopped (overturned or at
// rest) holds its last state.
TrajectoryError compare(const Trajectory& a, const Trajectory& ref, double interval);

// Smallest one-sine amplitude (unit: g) that overturns the scene, by bisection between lo and hi
// (widened when they do not bracket); stops when the bracket is narrower than rel_tol * hi.
double pulse_threshold(const scenario::Scene& scene, const scenario::RunSettings& settings, double period, double lo,
                       double hi, double rel_tol, double& wall);

}  // namespace rigid::study
