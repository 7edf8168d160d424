#include "rigid/motion/strong_motion.hpp"

#include <algorithm>
#include <cmath>

#include "rigid/core/types.hpp"

namespace rigid::motion {

TimeWindow strong_motion_window(const GroundMotion& m, double level_g) {
  TimeWindow w{0, m.duration()};
  if (!(level_g > 0)) return w;
  const double level = level_g * kGravity;
  long first = -1, last = -1;
  for (std::size_t i = 0; i < m.x.size(); ++i) {
    if (std::abs(m.x[i]) > level) {
      if (first < 0) first = long(i);
      last = long(i);
    }
  }
  if (first < 0) {
    w.end_s = std::min(2.0, m.duration());
  } else {
    w.start_s = std::max(0.0, double(first) * m.dt - 1.0);
    w.end_s = std::min(m.duration(), double(last) * m.dt + 1.0);
  }
  return w;
}

}  // namespace rigid::motion
