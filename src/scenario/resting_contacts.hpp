#pragma once
// What a shaking run reads from the contacts to decide that free blocks are at rest, still or
// may sleep (RunSettings::select_effects), all over the World's published ContactSummary.
#include <vector>

#include "rigid/dynamics/world.hpp"
#include "rigid/geometry/polygon2d.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {

/// Every free block slower than the given speeds (unit: m/s, rad/s).
bool at_rest(const dynamics::World& world, double speed, double angular_speed);

/// At rest relative to the ground: the pedestals move with ground_velocity and do not rotate, so
/// a block riding a coasting (or slowly moving) pedestal is at rest although its speed is not 0.
bool at_rest_relative(const dynamics::World& world, const Vec3& ground_velocity, double speed, double angular_speed);

/// The ground acceleration of a drive per interval (its velocity is linear between samples, so
/// the acceleration is constant on each interval), with suffix maxima; zero outside the record.
class DriveAcceleration {
 public:
  DriveAcceleration() = default;
  explicit DriveAcceleration(const GroundDrive& g);
  long count() const { return static_cast<long>(horizontal_.size()); }
  long interval(double t) const { return t <= 0 ? 0 : static_cast<long>(t / dt_); }
  double dt() const { return dt_; }
  /// Whether interval j stays within the levels: horizontal at most level_h and at most
  /// `fraction` of the quasi-static threshold ratio (g - |a_z|) (a downward ground acceleration
  /// lightens the blocks, so the threshold falls with the effective gravity), vertical at most
  /// level_z and fraction g.
  bool quiet(long j, double level_h, double level_z, double fraction, double ratio, double g) const;
  /// The same for every interval from j to the end of the record (a sufficient test: the largest
  /// horizontal against the smallest effective gravity).
  bool quiet_to_end(long j, double level_h, double level_z, double fraction, double ratio, double g) const;

 private:
  double dt_ = 1;
  std::vector<double> horizontal_, vertical_;  // |a_h|, |a_z| per interval (unit: m/s^2)
  std::vector<double> suffix_h_, suffix_z_;    // their maxima from each interval to the end
};

/// Scratch of quasi_static_ratio (reused from call to call).
struct SupportScratch {
  std::vector<geometry::Point2> points;
  std::vector<int> hull, order;
};

/// The smallest quasi-static acceleration, as a fraction of the (effective) gravity, at which a
/// free block could start to move: for each free block, rocking needs a/g > d/h (d: horizontal
/// distance from its centroid to the nearest edge of the support polygon of its loaded
/// subcontacts, h: centroid height above the lowest of them; physics.md §2, g tan(alpha) for a
/// rectangular block), sliding needs a/g > tan(atan(mu) - theta) on contacts tilted by theta.
/// Returns 0 when some free block does not rest on fixed blocks only (a stack: its threshold is
/// not this simple), with `supported` false.
double quasi_static_ratio(const dynamics::World& world, const dynamics::ContactSummary& contacts, double friction,
                          SupportScratch& scratch, bool& supported);

/// Loaded subcontacts per pair: unchanged from step to step while no block lifts a corner or
/// gains a contact.
void loaded_counts(const dynamics::ContactSummary& contacts, std::vector<std::size_t>& out);

/// Whether every loaded subcontact of every free block carries at least `fraction` of its block's
/// mean subcontact load. A rocking block unloads its heel corners to zero before they lift; an
/// elastic vibration of the block on its contact springs, or a horizontal push, unloads them in
/// proportion to its amplitude, the whole way at uplift.
bool corners_loaded(const dynamics::World& world, const dynamics::ContactSummary& contacts, double fraction);

}  // namespace rigid::scenario
