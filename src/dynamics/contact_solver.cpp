#include "rigid/dynamics/contact_solver.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <Eigen/LU>

namespace rigid::dynamics {

Vec3 relative_velocity(const SolverBody& a, const SolverBody& b, const Vec3& ra, const Vec3& rb) {
  return (b.velocity + b.angular_velocity.cross(rb)) - (a.velocity + a.angular_velocity.cross(ra));
}

namespace {

// A normal-only impulse p_n n on b, its opposite on a (lever terms precomputed).
void apply_normal(SolverBody& a, SolverBody& b, const ContactRow& r, double pn) {
  a.velocity -= (a.inverse_mass * pn) * r.normal;
  a.angular_velocity -= pn * r.turn_a;
  b.velocity += (b.inverse_mass * pn) * r.normal;
  b.angular_velocity += pn * r.turn_b;
}

// Relative normal velocity at a row's point: n . (v_b + w_b x r_b - v_a - w_a x r_a), with
// n . (w x r) = w . (r x n) precomputed.
double normal_velocity(const SolverBody& a, const SolverBody& b, const ContactRow& r) {
  return r.normal.dot(b.velocity - a.velocity) + b.angular_velocity.dot(r.rb_n) - a.angular_velocity.dot(r.ra_n);
}

// A patch impulse (force impulse along the tangents at the centre, twisting impulse about n).
void apply_patch(SolverBody& a, SolverBody& b, const FrictionPatch& p, const Eigen::Vector3d& impulse) {
  const Vec3 force = impulse.x() * p.tangent1 + impulse.y() * p.tangent2;
  const Vec3 twist = impulse.z() * p.normal;
  a.velocity -= a.inverse_mass * force;
  a.angular_velocity -= a.inverse_inertia * (p.ra.cross(force) + twist);
  b.velocity += b.inverse_mass * force;
  b.angular_velocity += b.inverse_inertia * (p.rb.cross(force) + twist);
}

// Sliding velocity at the patch centre along the tangents, and twisting rate about the normal.
Eigen::Vector3d patch_velocity(const SolverBody& a, const SolverBody& b, const FrictionPatch& p) {
  const Vec3 u = relative_velocity(a, b, p.ra, p.rb);
  return {p.tangent1.dot(u), p.tangent2.dot(u), p.normal.dot(b.angular_velocity - a.angular_velocity)};
}

// Normal row: p_n = max(0, p_n + m (target - u_n)). Returns the change.
double solve_normal(SolverBody& a, SolverBody& b, ContactRow& r) {
  const double un = normal_velocity(a, b, r);
  const double pn = std::max(0.0, r.normal_impulse + r.normal_mass * (r.target_normal_velocity - un));
  const double change = pn - r.normal_impulse;
  if (change != 0) {
    apply_normal(a, b, r, change);
    r.normal_impulse = pn;
  }
  return change;
}

// The largest change of any body's velocities since `before`, as a multiple of the tolerances.
double largest_motion_change(const std::vector<SolverBody>& bodies, const std::vector<SolverBody>& before,
                             const SolverSettings& settings) {
  double change = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].inverse_mass == 0) continue;
    change = std::max(
        {change, (bodies[i].velocity - before[i].velocity).cwiseAbs().maxCoeff() / settings.velocity_tolerance,
         (bodies[i].angular_velocity - before[i].angular_velocity).cwiseAbs().maxCoeff() / settings.angular_tolerance});
  }
  return change;
}

// One Gauss-Seidel visit of a patch: each normal row, then the friction of the patch.
void sweep_patch(SolverBody& a, SolverBody& b, ContactRow* rows, FrictionPatch& p) {
  double total = 0;
  for (int k = 0; k < p.row_count; ++k) {
    solve_normal(a, b, rows[k]);
    total += rows[k].normal_impulse;
  }
  // Coulomb on the patch: the impulse that stops sliding and twisting, projected radially
  // onto the ellipsoid |(f_1, f_2, tau / radius)| <= mu N
  Eigen::Vector3d impulse = p.impulse - p.mass * patch_velocity(a, b, p);
  const double limit = p.friction * total;
  const double size = std::hypot(impulse.x(), impulse.y(), p.radius > 0 ? impulse.z() / p.radius : 0.0);
  if (size > limit) impulse *= size > 0 ? limit / size : 0.0;
  const Eigen::Vector3d change = impulse - p.impulse;
  if (!change.isZero()) {
    apply_patch(a, b, p, change);
    p.impulse = impulse;
  }
}

// The exact solve of one patch with every other impulse held: its closed normal rows and its
// friction together. Sizes are bounded so that nothing is allocated.
constexpr int kMaxBlockNormals = 12;
constexpr int kMaxBlockRows = kMaxBlockNormals + 3;
using BlockMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlockRows, kMaxBlockRows>;
using BlockVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxBlockRows, 1>;
using NormalMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlockNormals, kMaxBlockNormals>;
using NormalVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxBlockNormals, 1>;
using FrictionGain = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, kMaxBlockNormals>;
using FrictionVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;

// A row's velocity: linear . (v_b - v_a) + angular_b . w_b - angular_a . w_a.
struct BlockRow {
  Vec3 linear, angular_a, angular_b;
};

// One patch as a small dense problem: W = J M^-1 J^T over its closed normal rows and its friction
// rows (two tangents at the centre, and the twist when the patch has a radius), and c, the rows'
// velocities above their targets without this patch's impulses.
struct PatchBlock {
  int normals = 0, frictions = 0;
  BlockMatrix w;
  BlockVector c;
  NormalVector current;  ///< the normal rows' impulses before the solve
  double friction = 0, radius = 0;
  // The friction that stops the patch's sliding and twisting for normal impulses x_n is
  // q = -W_tt^-1 (W_tn x_n + c_t) = -(G x_n + g); Coulomb takes its radial projection onto the
  // ellipsoid, as the Gauss-Seidel friction row does at its fixed point.
  FrictionGain gain;
  FrictionVector offset;
  // the normal rows' system while the patch sticks: W_nn - W_nt G and c_n - W_nt g
  NormalMatrix stick;
  NormalVector stick_c;

  double size(const Eigen::Vector3d& f) const {
    return std::hypot(f.x(), f.y(), frictions == 3 ? f.z() / radius : 0.0);
  }
  Eigen::Vector3d stopping(const NormalVector& xn) const {
    Eigen::Vector3d q = Eigen::Vector3d::Zero();
    if (frictions > 0) q.head(frictions) = -(gain * xn + offset);
    return q;
  }
};

void build_block(const SolverBody& a, const SolverBody& b, const BlockRow* jac, const FrictionPatch& patch,
                 PatchBlock& block) {
  const int size = block.normals + block.frictions;
  const int normals = block.normals, frictions = block.frictions;
  Vec3 turn_a[kMaxBlockRows], turn_b[kMaxBlockRows];
  for (int i = 0; i < size; ++i) {
    turn_a[i] = a.inverse_inertia * jac[i].angular_a;
    turn_b[i] = b.inverse_inertia * jac[i].angular_b;
  }
  const double linear = a.inverse_mass + b.inverse_mass;
  block.w.resize(size, size);
  block.c.resize(size);
  BlockVector x(size);
  for (int i = 0; i < size; ++i) {
    for (int j = 0; j < size; ++j) {
      block.w(i, j) =
          linear * jac[i].linear.dot(jac[j].linear) + jac[i].angular_a.dot(turn_a[j]) + jac[i].angular_b.dot(turn_b[j]);
    }
    block.c(i) = jac[i].linear.dot(b.velocity - a.velocity) + jac[i].angular_b.dot(b.angular_velocity) -
                 jac[i].angular_a.dot(a.angular_velocity);
    x(i) = i < normals ? block.current(i) : patch.impulse(i - normals);
  }
  block.c -= block.w * x;  // the targets are subtracted by the caller
  block.friction = patch.friction;
  block.radius = patch.radius;
  block.gain.resize(frictions, normals);
  block.offset.resize(frictions);
  block.stick = block.w.topLeftCorner(normals, normals);
  block.stick_c = block.c.head(normals);
  if (frictions == 0) return;
  Eigen::Matrix3d ktt = Eigen::Matrix3d::Identity();
  ktt.topLeftCorner(frictions, frictions) = block.w.bottomRightCorner(frictions, frictions);
  const Eigen::Matrix3d inverse = ktt.inverse();
  block.gain = inverse.topLeftCorner(frictions, frictions) * block.w.bottomLeftCorner(frictions, normals);
  block.offset = inverse.topLeftCorner(frictions, frictions) * block.c.tail(frictions);
  block.stick -= block.w.topRightCorner(normals, frictions) * block.gain;
  block.stick_c -= block.w.topRightCorner(normals, frictions) * block.offset;
}

// The normal impulses on the rows `active` that zero their velocities under the system (m, rhs),
// zero elsewhere.
NormalVector solve_active(const NormalMatrix& m, const NormalVector& rhs, const bool* active) {
  const int normals = static_cast<int>(rhs.size());
  int chosen[kMaxBlockNormals];
  int count = 0;
  for (int i = 0; i < normals; ++i) {
    if (active[i]) chosen[count++] = i;
  }
  NormalVector xn = NormalVector::Zero(normals);
  if (count == 0) return xn;
  NormalMatrix reduced(count, count);
  NormalVector right(count);
  double largest = 0;
  for (int i = 0; i < count; ++i) {
    right(i) = -rhs(chosen[i]);
    for (int j = 0; j < count; ++j) reduced(i, j) = m(chosen[i], chosen[j]);
    largest = std::max(largest, std::abs(reduced(i, i)));
  }
  // the coplanar rows of a face are redundant (W singular): a vanishing regularization picks one
  // of the equivalent splits while moving the velocities by ~1e-12 of their change
  reduced.diagonal().array() += 1e-12 * largest;
  const NormalVector solution = reduced.partialPivLu().solve(right);
  for (int i = 0; i < count; ++i) xn(chosen[i]) = solution(i);
  return xn;
}

// Active-set pivoting on the normal rows (Signorini: x >= 0, velocity >= target, one of them
// tight), alternating with the friction state (sticking, or sliding in a direction found by fixed
// point). False when it does not settle within its pivots; `xn` and `friction` are the solution.
bool pivot_block(const PatchBlock& block, double tolerance, NormalVector& xn, Eigen::Vector3d& friction) {
  const int normals = block.normals, frictions = block.frictions;
  // no finer than rounding allows: a tolerance below it would make the pivots flip on noise
  const double velocity_tolerance = std::max(tolerance, 1e-12 * block.c.cwiseAbs().maxCoeff());
  bool active[kMaxBlockNormals];
  Eigen::Vector3d q = block.stopping(xn);
  const double start_limit = block.friction * xn.sum();
  const double start_size = block.size(q);
  bool sticking = start_size <= start_limit;
  Eigen::Vector3d direction = sticking ? Eigen::Vector3d::Zero() : Eigen::Vector3d(q / start_size);
  {
    BlockVector now = block.w.leftCols(normals) * xn + block.c;
    if (frictions > 0) now += block.w.rightCols(frictions) * (sticking ? q : start_limit * direction).head(frictions);
    for (int i = 0; i < normals; ++i) active[i] = xn(i) > 0 || now(i) < 0;
  }
  for (int pivot = 0; pivot < 4 * normals + 24; ++pivot) {
    // the normal rows' system for this friction state: sticking, the Schur complement; sliding
    // along `direction`, friction mu N direction with N the sum of the normal impulses
    NormalMatrix m = block.stick;
    NormalVector rhs = block.stick_c;
    if (!sticking) {
      m = block.w.topLeftCorner(normals, normals);
      rhs = block.c.head(normals);
      if (frictions > 0) {
        const NormalVector along = block.w.topRightCorner(normals, frictions) * direction.head(frictions);
        m += block.friction * along * NormalVector::Ones(normals).transpose();
      }
    }
    xn = solve_active(m, rhs, active);
    const NormalVector residual = m * xn + rhs;
    const double scale = xn.size() > 0 ? xn.cwiseAbs().maxCoeff() : 0.0;
    int drop = -1, add = -1;
    for (int i = 0; i < normals; ++i) {
      if (active[i] && xn(i) < -1e-12 * scale && (drop < 0 || xn(i) < xn(drop))) drop = i;
      if (!active[i] && residual(i) < -velocity_tolerance && (add < 0 || residual(i) < residual(add))) add = i;
    }
    if (drop >= 0 || add >= 0) {
      const int flip = drop >= 0 ? drop : add;
      active[flip] = !active[flip];
      continue;
    }
    xn = xn.cwiseMax(0.0);
    const Eigen::Vector3d next = block.stopping(xn);
    const double limit = block.friction * xn.sum();
    const double next_size = block.size(next);
    if (next_size <= limit) {
      if (sticking) {
        friction = next;
        return true;
      }
      sticking = true;
      continue;
    }
    const Eigen::Vector3d next_direction = next / next_size;
    const Eigen::Vector3d moved = limit * (next_direction - direction);
    const double moved_velocity =
        frictions > 0 ? (block.w.rightCols(frictions) * moved.head(frictions)).cwiseAbs().maxCoeff() : 0.0;
    if (!sticking && moved_velocity <= velocity_tolerance) {
      friction = limit * next_direction;
      return true;
    }
    sticking = false;
    direction = next_direction;
  }
  return false;
}

// Rows a patch may have for its hull to be sought (a scanned base has tens of points).
constexpr int kMaxHullCandidates = 256;

// The rows among index[0, count) whose points are corners of the convex hull of all their points
// on the patch's plane (Andrew's monotone chain), collinear and interior points left out: the
// centre of pressure the corners admit is the whole hull, so the patch can carry the same loads.
// Overwrites index with them and returns their count.
int hull_corners(const ContactRow* rows, const FrictionPatch& patch, int* index, int count) {
  double x[kMaxHullCandidates], y[kMaxHullCandidates];
  double extent = 0;
  for (int i = 0; i < count; ++i) {
    const Vec3& r = rows[index[i]].rb;
    x[index[i]] = patch.tangent1.dot(r);
    y[index[i]] = patch.tangent2.dot(r);
  }
  std::sort(index, index + count, [&](int p, int q) { return x[p] < x[q] || (x[p] == x[q] && y[p] < y[q]); });
  for (int i = 1; i < count; ++i) {
    extent = std::max(extent, std::hypot(x[index[i]] - x[index[0]], y[index[i]] - y[index[0]]));
  }
  // a turn smaller than this is no turn: the point is on the edge (unit: m^2)
  const double flat = 1e-9 * extent * extent;
  auto turn = [&](int o, int p, int q) { return (x[p] - x[o]) * (y[q] - y[o]) - (y[p] - y[o]) * (x[q] - x[o]); };
  int hull[2 * kMaxHullCandidates];
  int size = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const int floor = size;
    for (int step = 0; step < count; ++step) {
      const int i = pass == 0 ? index[step] : index[count - 1 - step];
      while (size >= floor + 2 && turn(hull[size - 2], hull[size - 1], i) <= flat) --size;
      hull[size++] = i;
    }
    --size;  // the last point of a chain starts the other
  }
  std::copy(hull, hull + size, index);
  return size;
}

}  // namespace

bool solve_patch_exactly(SolverBody& a, SolverBody& b, ContactRow* rows, FrictionPatch& patch, PatchProblem problem,
                         double velocity_tolerance) {
  const bool velocity = problem == PatchProblem::velocity;
  constexpr double kOpen = -std::numeric_limits<double>::infinity();
  // the rows taking part: a row open at the midpoint (target -inf) takes no impulse
  if (patch.row_count > kMaxHullCandidates) return false;
  int index[kMaxHullCandidates];
  int count = 0;
  for (int k = 0; k < patch.row_count; ++k) {
    if (velocity && rows[k].target_normal_velocity == kOpen) continue;
    index[count++] = k;
  }
  const int taking_part = count;
  // a patch of many points (a scanned base): only the corners of their convex hull carry load;
  // the other points lie between them on the plane and follow (checked after the solve)
  if (count > kMaxBlockNormals) count = hull_corners(rows, patch, index, count);
  if (count > kMaxBlockNormals) return false;
  PatchBlock block;
  block.normals = count;
  block.frictions = !velocity ? 0 : patch.radius > 0 ? 3 : 2;
  if (block.frictions > 0 && patch.mass.isZero()) return false;  // no friction row to solve exactly
  auto impulse_of = [velocity](ContactRow& r) -> double& { return velocity ? r.normal_impulse : r.correction_impulse; };
  // rows that take no impulse: open ones, and points between the hull's corners
  bool loaded[kMaxHullCandidates] = {};
  for (int i = 0; i < count; ++i) loaded[index[i]] = true;
  for (int k = 0; k < patch.row_count; ++k) {
    ContactRow& r = rows[k];
    if (!loaded[k] && impulse_of(r) != 0) {
      apply_normal(a, b, r, -impulse_of(r));
      impulse_of(r) = 0;
    }
  }
  const int normals = block.normals;
  BlockRow jac[kMaxBlockRows];
  block.current.resize(normals);
  for (int i = 0; i < normals; ++i) {
    ContactRow& r = rows[index[i]];
    jac[i] = {r.normal, r.ra_n, r.rb_n};
    block.current(i) = impulse_of(r);
  }
  const Vec3 tangents[2] = {patch.tangent1, patch.tangent2};
  for (int i = 0; i < std::min(block.frictions, 2); ++i) {
    jac[normals + i] = {tangents[i], patch.ra.cross(tangents[i]), patch.rb.cross(tangents[i])};
  }
  if (block.frictions == 3) jac[normals + 2] = {Vec3::Zero(), patch.normal, patch.normal};
  build_block(a, b, jac, patch, block);
  for (int i = 0; i < normals; ++i) {
    const ContactRow& r = rows[index[i]];
    const double target = velocity ? r.target_normal_velocity : r.correction_velocity;
    block.c(i) -= target;
    block.stick_c(i) -= target;
  }
  NormalVector xn = block.current;
  Eigen::Vector3d friction = Eigen::Vector3d::Zero();
  if (!pivot_block(block, velocity_tolerance, xn, friction)) return false;
  for (int i = 0; i < normals; ++i) {
    ContactRow& r = rows[index[i]];
    const double change = xn(i) - impulse_of(r);
    if (change != 0) apply_normal(a, b, r, change);
    impulse_of(r) = xn(i);
  }
  if (block.frictions > 0) {
    const Eigen::Vector3d change = friction - patch.impulse;
    if (!change.isZero()) apply_patch(a, b, patch, change);
    patch.impulse = friction;
  }
  if (taking_part == count) return true;
  for (int k = 0; k < patch.row_count; ++k) {
    const ContactRow& r = rows[k];
    if (loaded[k] || (velocity && r.target_normal_velocity == kOpen)) continue;
    const double target = velocity ? r.target_normal_velocity : r.correction_velocity;
    if (normal_velocity(a, b, r) < target - velocity_tolerance) return false;
  }
  return true;
}

void set_tangents(FrictionPatch& p) {
  // any orthonormal pair completing n: the limit is isotropic, so which one is immaterial
  const Vec3& n = p.normal;
  const Vec3 helper =
      std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : (std::abs(n.y()) < 0.57735 ? Vec3::UnitY() : Vec3::UnitZ());
  p.tangent1 = n.cross(helper).normalized();
  p.tangent2 = n.cross(p.tangent1);
}

void prepare(const std::vector<SolverBody>& bodies, std::vector<ContactRow>& rows,
             std::vector<FrictionPatch>& patches) {
  for (auto& r : rows) {
    const SolverBody& a = bodies[r.a];
    const SolverBody& b = bodies[r.b];
    r.ra_n = r.ra.cross(r.normal);
    r.rb_n = r.rb.cross(r.normal);
    r.turn_a = a.inverse_inertia * r.ra_n;
    r.turn_b = b.inverse_inertia * r.rb_n;
    const double k = a.inverse_mass + b.inverse_mass + r.ra_n.dot(r.turn_a) + r.rb_n.dot(r.turn_b);
    r.normal_mass = k > 0 ? 1.0 / k : 0.0;
  }
  for (auto& p : patches) {
    const SolverBody& a = bodies[p.a];
    const SolverBody& b = bodies[p.b];
    // J = [t1 at the centre; t2 at the centre; rotation about n], K = J M^-1 J^T
    const Vec3 tangents[2] = {p.tangent1, p.tangent2};
    Vec3 angular_a[3], angular_b[3];
    for (int i = 0; i < 2; ++i) {
      angular_a[i] = p.ra.cross(tangents[i]);
      angular_b[i] = p.rb.cross(tangents[i]);
    }
    angular_a[2] = angular_b[2] = p.normal;
    Eigen::Matrix3d k;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double linear = (i < 2 && j < 2 && i == j) ? a.inverse_mass + b.inverse_mass : 0.0;
        k(i, j) = linear + angular_a[i].dot(a.inverse_inertia * angular_a[j]) +
                  angular_b[i].dot(b.inverse_inertia * angular_b[j]);
      }
    }
    p.mass.setZero();
    if (p.radius > 0) {
      if (k.determinant() > 0) p.mass = k.inverse();
    } else if (k.topLeftCorner<2, 2>().determinant() > 0) {
      // a point contact: sliding only, twisting is free
      p.mass.topLeftCorner<2, 2>() = k.topLeftCorner<2, 2>().inverse();
    }
  }
}

void warm_start(std::vector<SolverBody>& bodies, const std::vector<ContactRow>& rows,
                const std::vector<FrictionPatch>& patches) {
  for (const auto& r : rows) {
    if (r.normal_impulse != 0) apply_normal(bodies[r.a], bodies[r.b], r, r.normal_impulse);
  }
  for (const auto& p : patches) {
    if (!p.impulse.isZero()) apply_patch(bodies[p.a], bodies[p.b], p, p.impulse);
  }
}

// Whether patch j shares no free body with another patch: then nothing else moves its bodies, and
// its exact solve is final. Patches that share one (a stack) are visited point by point, which
// measured cheaper there than block sweeps of exact patch solves (a three-rock stack: 4x less
// CPU time for the same share of capped steps).
bool isolated(const std::vector<SolverBody>& bodies, const std::vector<FrictionPatch>& patches, std::size_t j) {
  const auto free = [&](int body) { return bodies[std::size_t(body)].inverse_mass != 0; };
  for (std::size_t k = 0; k < patches.size(); ++k) {
    if (k == j) continue;
    for (const int body : {patches[j].a, patches[j].b}) {
      if (free(body) && (patches[k].a == body || patches[k].b == body)) return false;
    }
  }
  return true;
}

SolverResult solve_velocities(std::vector<SolverBody>& bodies, std::vector<ContactRow>& rows,
                              std::vector<FrictionPatch>& patches, const SolverSettings& settings,
                              std::vector<SolverBody>& scratch) {
  SolverResult result;
  const double velocity_tolerance = 1e-3 * settings.velocity_tolerance;
  bool all_isolated = true;
  for (std::size_t j = 0; j < patches.size() && all_isolated; ++j) all_isolated = isolated(bodies, patches, j);
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    scratch = bodies;
    bool exact = true;
    for (auto& p : patches) {
      // invariant (debug builds): a patch names two bodies and a range of rows that exist
      assert(p.a >= 0 && p.b >= 0 && std::size_t(p.a) < bodies.size() && std::size_t(p.b) < bodies.size());
      assert(p.first_row >= 0 && p.row_count >= 0 && std::size_t(p.first_row + p.row_count) <= rows.size());
      SolverBody& a = bodies[p.a];
      SolverBody& b = bodies[p.b];
      ContactRow* first = rows.data() + p.first_row;
      const bool alone = all_isolated || isolated(bodies, patches, std::size_t(&p - patches.data()));
      if (!alone || !solve_patch_exactly(a, b, first, p, PatchProblem::velocity, velocity_tolerance)) {
        sweep_patch(a, b, first, p);
        exact = false;
      }
    }
    result.iterations = iteration + 1;
    // isolated patches solved exactly are the whole problem solved: a second sweep would only repeat it
    if ((exact && all_isolated) || largest_motion_change(bodies, scratch, settings) <= 1.0) {
      result.converged = true;
      break;
    }
  }
  // invariant (debug builds): contacts push, never pull (Signorini: p_n >= 0)
  for ([[maybe_unused]] const auto& r : rows) assert(r.normal_impulse >= 0);
  return result;
}

SolverResult solve_correction(const std::vector<SolverBody>& bodies, std::vector<SolverBody>& pseudo,
                              std::vector<ContactRow>& rows, const std::vector<FrictionPatch>& patches,
                              const SolverSettings& settings, std::vector<SolverBody>& scratch) {
  pseudo.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    pseudo[i] = bodies[i];
    pseudo[i].velocity.setZero();
    pseudo[i].angular_velocity.setZero();
  }
  for (auto& r : rows) r.correction_impulse = 0;
  SolverResult result;
  const double velocity_tolerance = 1e-3 * settings.velocity_tolerance;
  bool all_isolated = true;
  for (std::size_t j = 0; j < patches.size() && all_isolated; ++j) all_isolated = isolated(bodies, patches, j);
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    scratch = pseudo;
    bool exact = true;
    for (const auto& p : patches) {
      SolverBody& a = pseudo[p.a];
      SolverBody& b = pseudo[p.b];
      ContactRow* first = rows.data() + p.first_row;
      FrictionPatch frictionless = p;
      const bool alone = all_isolated || isolated(bodies, patches, std::size_t(&p - patches.data()));
      if (alone && solve_patch_exactly(a, b, first, frictionless, PatchProblem::correction, velocity_tolerance))
        continue;
      exact = false;
      for (int k = 0; k < p.row_count; ++k) {
        ContactRow& r = first[k];
        const double un = normal_velocity(a, b, r);
        const double impulse = std::max(0.0, r.correction_impulse + r.normal_mass * (r.correction_velocity - un));
        const double change = impulse - r.correction_impulse;
        if (change == 0) continue;
        apply_normal(a, b, r, change);
        r.correction_impulse = impulse;
      }
    }
    result.iterations = iteration + 1;
    if ((exact && all_isolated) || largest_motion_change(pseudo, scratch, settings) <= 1.0) {
      result.converged = true;
      break;
    }
  }
  return result;
}

}  // namespace rigid::dynamics
