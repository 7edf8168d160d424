// What one whole-cube rewrite costs (io::write_cube: the compaction of src/campaign/checkpointer.cpp,
// no longer the checkpoint itself, see checkpoint_bench.cpp): its time grows with the campaign's
// size (uncertainty campaigns reach 5e6 cells). Cubes of the study's layout (study_cube.hpp).
//
//   cmake --build build --target cube_write_bench && build/tests/cube_write_bench
//
// A benchmark, not a test: it prints medians of wall time per write and the file size.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "study_cube.hpp"

namespace {

using rigid_bench::kCellsPerObject;
using rigid_bench::study_layout_cube;

void WriteWholeCube(benchmark::State& state) {
  const std::int64_t cells = state.range(0);
  const rigid::io::Cube cube = study_layout_cube(cells);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("rigid_cube_bench_" + std::to_string(cells) + ".h5")).string();
  for (auto _ : state) rigid::io::write_cube(path, cube);
  state.counters["cells"] = double(cube.objects.size() * kCellsPerObject);
  state.counters["objects"] = double(cube.objects.size());
  state.counters["file_MB"] = double(std::filesystem::file_size(path)) / 1e6;
  std::filesystem::remove(path);
}
BENCHMARK(WriteWholeCube)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Arg(1'000'000)
    ->Arg(5'000'000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
