// What geometry::convex_hull costs: a mesh's pieces and every contact query's support shapes
// come from it, so its time against the point count shows whether scans with thousands of
// vertices stay cheap to load. Random points in a ball (few extreme) and on a sphere (all
// extreme: the incremental hull's worst case).
//
//   cmake --build build --target hull_bench && build/tests/hull_bench
//
// A benchmark, not a test: it prints medians of wall time per hull and the hull's triangles.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "rigid/geometry/polyhedron.hpp"
#include "support/rng.hpp"

namespace {

using rigid::Vec3;

std::vector<Vec3> points(std::int64_t n, bool on_sphere) {
  std::vector<Vec3> pts = rigid::test::unit_ball_points(7, static_cast<int>(n));
  if (on_sphere) {
    for (Vec3& p : pts) p.normalize();
  }
  return pts;
}

void Hull(benchmark::State& state, bool on_sphere) {
  const std::vector<Vec3> pts = points(state.range(0), on_sphere);
  std::size_t triangles = 0;
  for (auto _ : state) {
    const rigid::geometry::TriangleSoup hull = rigid::geometry::convex_hull(pts);
    triangles = hull.size();
    benchmark::DoNotOptimize(hull.data());
  }
  state.counters["triangles"] = double(triangles);
}

void HullOfPointsInABall(benchmark::State& state) { Hull(state, false); }
void HullOfPointsOnASphere(benchmark::State& state) { Hull(state, true); }

BENCHMARK(HullOfPointsInABall)->RangeMultiplier(4)->Range(128, 8192)->Unit(benchmark::kMillisecond);
BENCHMARK(HullOfPointsOnASphere)->RangeMultiplier(4)->Range(128, 8192)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
