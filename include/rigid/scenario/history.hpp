#pragma once
/// A run's time history as arrays, for seeing the rock move (rigidpy.run, `rigid run --plot`):
/// every free block's tilt, accumulated slip, pose and contact state, and the table's (the first
/// fixed block's) displacement and velocity and the motion's acceleration, sampled by RunSettings::observer. No I/O.
#include <string>
#include <vector>

#include "rigid/dynamics/world.hpp"
#include "rigid/motion/ground_motion.hpp"

namespace rigid::scenario {

/// Frames of a run. Per-block arrays are frame-major: value (frame f, block b) at f * blocks + b,
/// vectors with their 3 (position, contact force, table) or 4 (orientation w, x, y, z)
/// components innermost.
struct History {
  std::vector<std::string> blocks;  ///< the free blocks' names, scene order
  /// per block: its centre of mass above its lowest point at the first frame (unit: m), the
  /// length a side view draws it with
  std::vector<double> base_height_m;
  std::vector<double> time_s;                ///< frame times (unit: s)
  std::vector<double> tilt_rad;              ///< scenario::tilt from the block's initial orientation
  std::vector<double> slip_m;                ///< accumulated frictional slip (World::slip)
  std::vector<double> position_m;            ///< centre of mass, world frame
  std::vector<double> orientation;           ///< body-to-world unit quaternion (w, x, y, z)
  std::vector<int> contacts;                 ///< loaded subcontacts touching it (0 before the first step)
  std::vector<double> contact_force_n;       ///< total contact force on the block (World::contact_force)
  std::vector<double> table_displacement_m;  ///< first fixed block's centre less its initial one
  std::vector<double> table_velocity_m_s;    ///< first fixed block's velocity
  /// The motion's acceleration at the frame times, linear between its samples (0 after its end
  /// and for an absent component)
  std::vector<double> table_acceleration_m_s2;
  std::size_t frames() const { return time_s.size(); }
};

/// Fills a History from the World it is shown: pass `observer()` as RunSettings::observer.
class HistoryRecorder {
 public:
  /// `motion`: the motion the run is driven by, exactly as simulated (scaled, rotated); it must
  /// outlive the recorder.
  explicit HistoryRecorder(const motion::GroundMotion& motion) : motion_(motion) {}
  void record(const dynamics::World& world);
  const History& history() const { return history_; }

 private:
  Vec3 acceleration_at(double t) const;
  const motion::GroundMotion& motion_;
  History history_;
  std::vector<int> free_;  // body indices of the free blocks
  int table_ = -1;         // body index of the first fixed block, -1 when none
  Vec3 table_start_{0, 0, 0};
  dynamics::ContactSummary summary_;
};

}  // namespace rigid::scenario
