#include "rigid/rocking/newmark.hpp"

#include <algorithm>
#include <cmath>

#include "rigid/core/types.hpp"

namespace rigid::rocking {

double newmark_displacement(const std::vector<double>& a, double dt, double mu) {
  const double h = 1e-5;
  const double fr = mu * kGravity;
  const double end = dt * double(a.size() - 1);
  auto acc = [&](double t) {
    if (t >= end) return 0.0;
    const double x = t / dt;
    const std::size_t k = static_cast<std::size_t>(x);
    const double f = x - double(k);
    return (1 - f) * a[k] + f * a[std::min(k + 1, a.size() - 1)];
  };
  double u = 0, v = 0;
  for (long i = 0;; ++i) {
    const double t = double(i) * h;
    if (t > end && v == 0) break;
    const double ag = acc(t + 0.5 * h);
    double s = v > 0 ? 1 : v < 0 ? -1 : 0;
    if (s == 0) {
      if (std::abs(ag) <= fr) continue;
      s = ag > 0 ? -1 : 1;  // the block lags behind the base
    }
    const double rel = -ag - s * fr;
    const double vn = v + rel * h;
    if (vn * s <= 0) {  // stops within the step
      const double tau = -v / rel;
      u += v * tau + 0.5 * rel * tau * tau;
      v = 0;
    } else {
      u += 0.5 * (v + vn) * h;
      v = vn;
    }
  }
  return u;
}

}  // namespace rigid::rocking
