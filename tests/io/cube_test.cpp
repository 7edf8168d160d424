// The HDF5 fragility cube: round trip, derived products against hand-computed values, atomic
// replacement (also under SIGKILL), rejection of foreign files, dimension scales; the variant axis
// (schema_version 2): round trip, layout through the HDF5 C API, per-variant derived products,
// consistency checks and damaged files. CubeFixture.WritesThePythonFixture writes the file
// tests/python/test_cube.py checks with h5py, CubeFixture.WritesTheVariantFixture the one
// tests/python/test_variant_cube.py opens with h5py and xarray.
#include "rigid/io/cube.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

#include "rigid/core/error.hpp"
#include "rigid/io/cells_csv.hpp"

namespace fs = std::filesystem;

namespace rigid::io {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using O = CellOutcome;

/// A scratch directory per test, removed afterwards.
class CubeFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("rigid_cube_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

std::uint64_t bits(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

/// A NaN with a payload: the file must keep the exact bit pattern, not just "some NaN".
double payload_nan() {
  const std::uint64_t u = 0x7ff800000000beefULL;
  double x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

// 3 records, 4 scales, 2 rotations. Object "rock a" has a pattern whose probabilities are written
// down in ProbabilityCountsOverturnedAndInferredAndLeavesOutFailed; "rock_b" is half not run.
Cube synthetic() {
  Cube c;
  c.records = {
      {"rec one", "x=a b/one-X.AT2,y=a b/one-Y.AT2", "Duzce, Turkey", 1.5, 21.25, 0.3, 20.0, 0.068, 0.31, 21.5, "",
       "component y zero-padded by 3 samples (0.015 s)"},
      {"rec_two", "two-X.AT2", "", 0.0, kInf, 0.25, 17.0, 0.0693, 0.0, 0.0, "", ""},
      {"rec \"three\"", "three-X.AT2", "Chi-Chi, Taiwan", 2.0, 40.0, 0.1, 49.0, 0.5, 0.1, 49.0, "", ""},
  };
  c.scales_g = {0.1, 0.2, 0.30000000000000004, 0.4};
  c.rotations = 2;
  c.job_text = "# job\nname = \"demo run\"\nrecords = \"table.tsv\"\n";
  c.job_hash = "5e884898da28047151d0e56f8dc6292773603d0d6aabbdd62a11ef721d1542d8";
  c.software_version = "0.1.0 (abc1234)";
  c.physics_json = R"({"density": 2600, "friction": 0.6, "dt_s": null})";
  c.seed = 0xFEDCBA9876543210ULL;  // above INT64_MAX: must stay unsigned
  // provenance: sha256sum lines (any 64 hex digits will do here) and a combined digest
  c.job_inputs = std::string(64, 'a') + "  (settings)\n" + std::string(64, 'b') + "  jobs/demo run.toml\n";
  c.inputs_sha256 = std::string(64, 'c');
  c.records[0].inputs = std::string(64, 'd') + "  a b/one-X.AT2\n" + std::string(64, 'e') + "  a b/one-Y.AT2\n";
  c.records[2].inputs = std::string(64, 'f') + "  three-X.AT2\n";

  const std::size_t n = 3 * 4 * 2;
  ObjectCube a;
  a.name = "rock a";
  a.scene = "models/rock a/rock.toml";
  a.alpha_rad = 0.2;  // a single block; object b below is a stack without them
  a.p_rad_s = 2.3;
  a.inputs = std::string(64, '0') + "  models/rock a/rock.toml\n" + std::string(64, '1') + "  models/rock a/rock.stl\n";
  // [record][scale][rotation]
  const O pattern[3][4][2] = {
      {{O::survived, O::survived},
       {O::survived, O::overturned},
       {O::overturned, O::overturned},
       {O::inferred, O::inferred}},
      {{O::not_run, O::not_run}, {O::failed, O::survived}, {O::failed, O::overturned}, {O::failed, O::failed}},
      {{O::survived, O::not_run}, {O::overturned, O::inferred}, {O::survived, O::inferred}, {O::not_run, O::inferred}},
  };
  for (const auto& rec : pattern)
    for (const auto& sc : rec)
      for (const O o : sc) a.outcome.push_back(static_cast<std::int8_t>(o));
  for (std::size_t i = 0; i < n; ++i) {
    const auto o = static_cast<O>(a.outcome[i]);
    const bool ran = o == O::survived || o == O::overturned;
    a.rotation_deg.push_back(o == O::not_run || o == O::inferred ? kNaN : 17.25 * static_cast<double>(i));
    a.failure_time_s.push_back(o == O::overturned ? 3.0 + 0.125 * static_cast<double>(i) : kNaN);
    a.max_tilt_deg.push_back(ran ? 1.5 * static_cast<double>(i) : kNaN);
    a.max_slip_m.push_back(ran ? 1e-3 * static_cast<double>(i) : kNaN);
    a.wall_s.push_back(ran ? 0.01 * static_cast<double>(i + 1) : kNaN);
    a.failure_reason.push_back(o == O::failed ? 2 : 0);
    // text a CSV or HDF5 string must carry intact: commas, quotes, a line break, UTF-8
    a.failure_message.push_back(o == O::failed ? "cell " + std::to_string(i) + ": \"bad\" state, t = 1.5 s\nΔt → 0"
                                               : "");
    a.unconverged_steps.push_back(ran ? static_cast<std::int32_t>(i % 3) : -1);
  }
  a.max_tilt_deg[3] = payload_nan();

  ObjectCube b = a;
  b.name = "rock_b";
  b.scene = "models/rock_b.toml";
  for (std::size_t i = 0; i < n; i += 2) b.outcome[i] = static_cast<std::int8_t>(O::not_run);
  b.failure_reason[1] = -7;
  b.failure_message.clear();    // none stored: written as "" per cell
  b.unconverged_steps.clear();  // none stored: written as -1 (not recorded) per cell
  c.objects = {a, b};
  return c;
}

constexpr int kVariants = 3;

// synthetic() with a variant axis of 3: friction (numeric), contact (text), density. Each base
// object's variants differ in every per-variant field: cells shifted by 5 * v positions (so the
// probabilities differ), rocking parameters, physics, inputs; variant 1 of "rock a" kept no
// failure messages, and only "rock a" has rocking parameters (rock_b is a stack: NaN, none).
Cube variant_synthetic() {
  Cube c = synthetic();
  c.variants.method = "lhs";
  c.variants.seed = 0x8000000000000001ULL;  // above INT64_MAX: must stay unsigned
  c.variants.count = kVariants;
  c.objects[1].alpha_rad = c.objects[1].p_rad_s = kNaN;  // rock_b: a stack, no rocking parameters
  c.variants.parameters = {
      {"friction", "1", "Coulomb friction coefficient", {0.5, 0.6000000000000001, 0.75}, {}},
      {"contact", "", "contact model", {}, {"rigid", "penalty", "rigid"}},
      {"density_kg_m3", "kg m-3", "density of every block", {2400.0, 2650.5, 2900.25}, {}},
  };
  std::vector<ObjectCube> objects;
  for (const ObjectCube& base : c.objects) {
    for (int v = 0; v < kVariants; ++v) {
      ObjectCube o = base;
      o.variant = v;
      const std::size_t n = o.outcome.size(), shift = 5 * static_cast<std::size_t>(v);
      const auto rotate = [&](auto& a) {
        if (!a.empty()) std::rotate(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(shift % n), a.end());
      };
      rotate(o.outcome);
      rotate(o.rotation_deg);
      rotate(o.failure_time_s);
      rotate(o.max_tilt_deg);
      rotate(o.max_slip_m);
      rotate(o.wall_s);
      rotate(o.failure_reason);
      rotate(o.failure_message);
      rotate(o.unconverged_steps);
      o.physics_json = R"({"friction": )" + std::to_string(c.variants.parameters[0].values[v]) + "}";
      o.inputs = std::string(64, static_cast<char>('a' + v)) + "  " + base.scene + "\n";
      if (std::isfinite(base.alpha_rad)) {
        o.alpha_rad = base.alpha_rad + 0.01 * v;
        o.p_rad_s = base.p_rad_s - 0.1 * v;
        o.rocking_radius_m = 0.5 + v;
        o.weakest_azimuth_deg = 90.0 * v;
        o.alpha_by_azimuth_rad = {o.alpha_rad, 0.3 + v, 1.0 / 3.0, o.alpha_rad};
        o.support_polygon_m = {-0.1, -0.2, 0.1, -0.2, 0.1, 0.2 + v, -1.0 / 7.0, 0.2};
      }
      objects.push_back(std::move(o));
    }
  }
  c.objects = std::move(objects);
  c.objects[1].failure_message.clear();  // "rock a" variant 1: none kept, written as "" per cell
  return c;
}

void expect_same_doubles(const std::vector<double>& a, const std::vector<double>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(bits(a[i]), bits(b[i])) << what << "[" << i << "]";
}

void expect_same(const Cube& a, const Cube& b) {
  EXPECT_EQ(a.job_text, b.job_text);
  EXPECT_EQ(a.job_hash, b.job_hash);
  EXPECT_EQ(a.software_version, b.software_version);
  EXPECT_EQ(a.physics_json, b.physics_json);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.job_inputs, b.job_inputs);
  EXPECT_EQ(a.inputs_sha256, b.inputs_sha256);
  EXPECT_EQ(a.rotations, b.rotations);
  EXPECT_EQ(a.variants.count, b.variants.count);
  if (a.variants.count > 0) {  // a table without variants is not stored
    EXPECT_EQ(a.variants.method, b.variants.method);
    EXPECT_EQ(a.variants.seed, b.variants.seed);
    ASSERT_EQ(a.variants.parameters.size(), b.variants.parameters.size());
    for (std::size_t i = 0; i < a.variants.parameters.size(); ++i) {
      const VariantParameter &x = a.variants.parameters[i], &y = b.variants.parameters[i];
      EXPECT_EQ(x.name, y.name);
      EXPECT_EQ(x.units, y.units) << x.name;
      EXPECT_EQ(x.description, y.description) << x.name;
      expect_same_doubles(x.values, y.values, "variant parameter " + x.name);
      EXPECT_EQ(x.labels, y.labels) << x.name;
    }
  }
  expect_same_doubles(a.scales_g, b.scales_g, "scales_g");
  expect_same_doubles(pgv_pga_edges(a), b.pgv_pga_edges_s, "pgv_pga_edges_s");
  ASSERT_EQ(a.records.size(), b.records.size());
  for (std::size_t r = 0; r < a.records.size(); ++r) {
    const RecordMeta &x = a.records[r], &y = b.records[r];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.source, y.source);
    EXPECT_EQ(x.earthquake, y.earthquake);
    EXPECT_EQ(x.alignment, y.alignment);
    EXPECT_EQ(x.inputs, y.inputs);
    expect_same_doubles(
        {x.start_s, x.end_s, x.gmroti_pga_g, x.gmroti_pgv_cm_s, x.pgv_pga_s, x.listed_pga_g, x.listed_pgv_cm_s},
        {y.start_s, y.end_s, y.gmroti_pga_g, y.gmroti_pgv_cm_s, y.pgv_pga_s, y.listed_pga_g, y.listed_pgv_cm_s},
        "record " + x.name);
  }
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const ObjectCube &x = a.objects[i], &y = b.objects[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.variant, y.variant) << x.name;
    EXPECT_EQ(x.scene, y.scene);
    EXPECT_EQ(x.inputs, y.inputs);
    EXPECT_EQ(x.physics_json, y.physics_json) << x.name;
    // NaN (no rocking parameters) must come back NaN: compare the bits
    EXPECT_EQ(std::memcmp(&x.alpha_rad, &y.alpha_rad, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&x.p_rad_s, &y.p_rad_s, sizeof(double)), 0);
    EXPECT_EQ(bits(x.rocking_radius_m), bits(y.rocking_radius_m)) << x.name;
    EXPECT_EQ(bits(x.weakest_azimuth_deg), bits(y.weakest_azimuth_deg)) << x.name;
    expect_same_doubles(x.alpha_by_azimuth_rad, y.alpha_by_azimuth_rad, x.name + " alpha_by_azimuth_rad");
    expect_same_doubles(x.support_polygon_m, y.support_polygon_m, x.name + " support_polygon_m");
    EXPECT_EQ(x.outcome, y.outcome);
    expect_same_doubles(x.rotation_deg, y.rotation_deg, x.name + " rotation_deg");
    expect_same_doubles(x.failure_time_s, y.failure_time_s, x.name + " failure_time_s");
    expect_same_doubles(x.max_tilt_deg, y.max_tilt_deg, x.name + " max_tilt_deg");
    expect_same_doubles(x.max_slip_m, y.max_slip_m, x.name + " max_slip_m");
    expect_same_doubles(x.wall_s, y.wall_s, x.name + " wall_s");
    EXPECT_EQ(x.failure_reason, y.failure_reason);
    // an object without messages is stored with "" for every cell
    const std::vector<std::string> stored =
        x.failure_message.empty() ? std::vector<std::string>(x.outcome.size()) : x.failure_message;
    EXPECT_EQ(stored, y.failure_message) << x.name;
    const std::vector<std::int32_t> counts =
        x.unconverged_steps.empty() ? std::vector<std::int32_t>(x.outcome.size(), -1) : x.unconverged_steps;
    EXPECT_EQ(counts, y.unconverged_steps) << x.name;
  }
}

/// Expects `f` to throw InputError naming `path` with `needle` in its message.
template <class F>
void expect_input_error(F f, const std::string& path, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no InputError for " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The dimensions of a dataset, read with the HDF5 C API ({} when it cannot be opened).
std::vector<hsize_t> dataset_dims(hid_t file, const std::string& path) {
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (d < 0) return {};
  const hid_t space = H5Dget_space(d);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(d);
  return dims;
}

/// A whole dataset read as `mem_type` values.
template <class T>
std::vector<T> read_dataset(hid_t file, const std::string& path, hid_t mem_type) {
  hsize_t n = 1;
  for (const hsize_t x : dataset_dims(file, path)) n *= x;
  std::vector<T> v(n);
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(H5Dread(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0) << path;
  H5Dclose(d);
  return v;
}

/// A string attribute (variable-length, as the writer stores them).
std::string string_attribute(hid_t file, const std::string& object, const char* name) {
  if (H5Aexists_by_name(file, object.c_str(), name, H5P_DEFAULT) <= 0) return "(missing)";
  const hid_t a = H5Aopen_by_name(file, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0) return "(missing)";
  const hid_t type = H5Aget_type(a);
  char* p = nullptr;
  H5Aread(a, type, &p);
  std::string s = p != nullptr ? p : "";
  H5free_memory(p);
  H5Tclose(type);
  H5Aclose(a);
  return s;
}

template <class T>
T number_attribute(hid_t file, const std::string& object, const char* name, hid_t mem_type) {
  T v{};
  const hid_t a = H5Aopen_by_name(file, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(a, 0) << object << " " << name;
  if (a >= 0) {
    H5Aread(a, mem_type, &v);
    H5Aclose(a);
  }
  return v;
}

/// Replaces an int32 attribute by one of another value (deleted and created again: HDF5 1.10's
/// H5Awrite refuses an attribute opened by name on a group of a cube).
void replace_int32_attribute(hid_t file, const std::string& object, const char* name, std::int32_t value) {
  ASSERT_GE(H5Adelete_by_name(file, object.c_str(), name, H5P_DEFAULT), 0) << object << " " << name;
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a =
      H5Acreate_by_name(file, object.c_str(), name, H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(H5Awrite(a, H5T_NATIVE_INT32, &value), 0) << object << " " << name;
  H5Aclose(a);
  H5Sclose(space);
}

/// Equal arrays, a NaN matching a NaN.
void expect_equal_or_both_nan(const std::vector<double>& got, const std::vector<double>& want,
                              const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (std::isnan(want[i]))
      EXPECT_TRUE(std::isnan(got[i])) << what << "[" << i << "]";
    else
      EXPECT_EQ(got[i], want[i]) << what << "[" << i << "]";
  }
}

TEST(CubeDerived, ProbabilityCountsOverturnedAndInferredAndLeavesOutFailed) {
  const Cube c = synthetic();
  const std::vector<double> p = overturn_probability(c, c.objects[0]);
  const double want[3][4] = {
      {0.0, 0.5, 1.0, 1.0},    // survived x2; one of two; both; inferred counts as overturned
      {kNaN, 0.0, 1.0, kNaN},  // nothing run; failed left out (twice); only failed
      {0.0, 1.0, 0.5, 1.0},    // not run left out; overturned + inferred; survived + inferred; inferred
  };
  ASSERT_EQ(p.size(), 12u);
  for (int r = 0; r < 3; ++r)
    for (int s = 0; s < 4; ++s) {
      if (std::isnan(want[r][s]))
        EXPECT_TRUE(std::isnan(p[r * 4 + s])) << r << "," << s;
      else
        EXPECT_EQ(p[r * 4 + s], want[r][s]) << r << "," << s;
    }
}

TEST(CubeDerived, MeanProbabilityPerScaleAveragesKnownRecords) {
  const Cube c = synthetic();
  const std::vector<double> m = mean_overturn_probability(c, c.objects[0]);
  ASSERT_EQ(m.size(), 4u);
  // the per-record values of ProbabilityCountsOverturnedAndInferredAndLeavesOutFailed by column
  EXPECT_EQ(m[0], 0.0);  // 0, NaN, 0
  EXPECT_EQ(m[1], (0.5 + 0.0 + 1.0) / 3);
  EXPECT_EQ(m[2], (1.0 + 1.0 + 0.5) / 3);
  EXPECT_EQ(m[3], 1.0);  // 1, NaN, 1
  Cube bad = c;
  bad.objects[1].wall_s.pop_back();
  EXPECT_THROW(mean_overturn_probability(bad, bad.objects[1]), std::invalid_argument);
}

TEST(CubeDerived, FragilityAveragesKnownRecordsPerBin) {
  const Cube c = synthetic();  // pgv_pga_s 0.068, 0.0693 (default bin 1) and 0.5 (bin 8)
  const FragilitySurface f = fragility_surface(c, c.objects[0]);
  ASSERT_EQ(f.bins(), 9u);
  ASSERT_EQ(f.probability.size(), 4u * 9u);
  const double bin1[4] = {0.0, 0.25, 1.0, 1.0};  // record 1 unknown at scales 0 and 3
  const int count1[4] = {1, 2, 2, 1};
  const double bin8[4] = {0.0, 1.0, 0.5, 1.0};
  for (int s = 0; s < 4; ++s) {
    for (int b = 0; b < 9; ++b) {
      const double p = f.probability[s * 9 + b];
      const int n = f.count[s * 9 + b];
      if (b == 1) {
        EXPECT_EQ(p, bin1[s]) << s;
        EXPECT_EQ(n, count1[s]) << s;
      } else if (b == 8) {
        EXPECT_EQ(p, bin8[s]) << s;
        EXPECT_EQ(n, 1) << s;
      } else {
        EXPECT_TRUE(std::isnan(p)) << s << "," << b;
        EXPECT_EQ(n, 0) << s << "," << b;
      }
    }
  }

  Cube two = c;
  two.pgv_pga_edges_s = {0.0, 0.1, 0.4};  // record 2 (0.5 s) falls outside: left out
  const FragilitySurface g = fragility_surface(two, two.objects[0]);
  ASSERT_EQ(g.bins(), 2u);
  EXPECT_EQ(g.probability[0 * 2 + 0], 0.0);
  EXPECT_EQ(g.probability[1 * 2 + 0], 0.25);
  EXPECT_EQ(g.probability[2 * 2 + 0], 1.0);
  EXPECT_EQ(g.probability[3 * 2 + 0], 1.0);
  for (int s = 0; s < 4; ++s) {
    EXPECT_TRUE(std::isnan(g.probability[s * 2 + 1]));
    EXPECT_EQ(g.count[s * 2 + 1], 0);
  }
}

TEST(CubeDerived, InconsistentCubesAreRejected) {
  Cube c = synthetic();
  c.objects[1].wall_s.pop_back();
  EXPECT_THROW(overturn_probability(c, c.objects[1]), std::invalid_argument);
  EXPECT_NE(cube_problem(c).find("wall_s has 23 values, expected 24"), std::string::npos) << cube_problem(c);
  c = synthetic();
  c.objects[1].name = "rock a";
  EXPECT_NE(cube_problem(c).find("two objects are named 'rock a'"), std::string::npos);
  c = synthetic();
  c.objects[0].name = "a/b";
  EXPECT_NE(cube_problem(c).find("not a valid group name"), std::string::npos);
  c = synthetic();
  c.objects[0].outcome[5] = 5;
  EXPECT_NE(cube_problem(c).find("outcome[5] = 5"), std::string::npos);
  c = synthetic();
  c.pgv_pga_edges_s = {0.0, 0.2, 0.1};
  EXPECT_NE(cube_problem(c).find("increase strictly"), std::string::npos);
  c = synthetic();
  c.job_text += std::string(1, '\0');
  EXPECT_NE(cube_problem(c).find("NUL"), std::string::npos);
  EXPECT_EQ(cube_problem(synthetic()), "");
}

TEST_F(CubeFile, RoundTripKeepsEveryValueBitForBit) {
  Cube c = synthetic();
  c.job_text += std::string(100000, 'x') + "\n";  // beyond HDF5's 64 KiB compact attribute limit
  const std::string p = path("cube.h5");
  write_cube(p, c);
  const Cube back = read_cube(p);
  expect_same(c, back);
  EXPECT_EQ(back.pgv_pga_edges_s, statistics::default_pgv_pga_edges());  // none given: the defaults were stored

  c.pgv_pga_edges_s = {0.01, 0.1, kInf};
  write_cube(p, c);
  expect_same(c, read_cube(p));
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);  // every HDF5 handle closed
}

TEST_F(CubeFile, EmptyCubeRoundTrips) {
  Cube c;
  c.rotations = 3;
  const std::string p = path("empty.h5");
  write_cube(p, c);
  const Cube back = read_cube(p);
  expect_same(c, back);
  EXPECT_EQ(back.rotations, 3);
}

TEST_F(CubeFile, WritesOverAnExistingFileAndLeavesNoTemporary) {
  const std::string p = path("cube.h5");
  std::ofstream(p + ".tmp") << "stale temporary of a killed writer";
  write_cube(p, synthetic());
  EXPECT_FALSE(fs::exists(p + ".tmp"));
  Cube c = synthetic();
  c.records.pop_back();
  for (ObjectCube& o : c.objects) {
    for (auto* v : {&o.rotation_deg, &o.failure_time_s, &o.max_tilt_deg, &o.max_slip_m, &o.wall_s}) v->resize(16);
    o.outcome.resize(16);
    o.failure_reason.resize(16);
    if (!o.failure_message.empty()) o.failure_message.resize(16);
    if (!o.unconverged_steps.empty()) o.unconverged_steps.resize(16);
  }
  c.objects.pop_back();
  write_cube(p, c);
  EXPECT_FALSE(fs::exists(p + ".tmp"));
  expect_same(c, read_cube(p));
}

TEST_F(CubeFile, APathWithoutADirectoryIsWrittenInTheWorkingDirectory) {
  const fs::path before = fs::current_path();
  fs::current_path(dir_);  // write_cube then syncs "." after the rename
  write_cube("relative.h5", synthetic());
  const Cube back = read_cube("relative.h5");
  fs::current_path(before);
  expect_same(synthetic(), back);
  EXPECT_FALSE(fs::exists(dir_ / "relative.h5.tmp"));
}

TEST_F(CubeFile, AnInvalidCubeLeavesTheOldFileAlone) {
  const std::string p = path("cube.h5");
  write_cube(p, synthetic());
  const std::string before = slurp(p);
  Cube bad = synthetic();
  bad.objects[0].outcome.pop_back();
  expect_input_error([&] { write_cube(p, bad); }, p, "outcome has 23 values");
  EXPECT_EQ(slurp(p), before);
  EXPECT_FALSE(fs::exists(p + ".tmp"));
  expect_input_error([&] { write_cube(path("no/such/dir/cube.h5"), synthetic()); }, path("no/such/dir/cube.h5"),
                     "creating");
}

TEST_F(CubeFile, TheSameCubeGivesTheSameBytes) {
  // No time stamps anywhere: two writes of one cube are identical files (with one HDF5 version;
  // comparisons across versions go dataset by dataset, tests/python/compare_cubes.py).
  const std::string a = path("a.h5"), b = path("b.h5");
  write_cube(a, synthetic());
  ::sleep(1);  // a time stamp, if one were written, would differ
  write_cube(b, synthetic());
  EXPECT_TRUE(slurp(a) == slurp(b));
}

TEST_F(CubeFile, ForeignFilesAreRejected) {
  expect_input_error([&] { read_cube(path("missing.h5")); }, path("missing.h5"), "no such file");

  const std::string garbage = path("garbage.h5");
  std::ofstream(garbage) << "this is not HDF5\n";
  expect_input_error([&] { read_cube(garbage); }, garbage, "not a Rigid fragility cube");

  const std::string empty = path("empty.h5");
  std::ofstream{empty};
  expect_input_error([&] { read_cube(empty); }, empty, "not a Rigid fragility cube");

  const std::string good = path("good.h5");
  write_cube(good, synthetic());
  const std::string bytes = slurp(good);
  for (const std::size_t keep : {bytes.size() / 2, bytes.size() - 100, std::size_t{512}}) {
    const std::string truncated = path("truncated_" + std::to_string(keep) + ".h5");
    std::ofstream(truncated, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(keep));
    expect_input_error([&] { read_cube(truncated); }, truncated, "");
  }

  const std::string other = path("other.h5");  // valid HDF5, but not ours
  const hid_t f = H5Fcreate(other.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  H5Fclose(f);
  expect_input_error([&] { read_cube(other); }, other, "not a Rigid fragility cube (no schema_version)");
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);  // failures close their handles too
}

TEST_F(CubeFile, DamagedOrNewerCubesAreRejected) {
  const std::string p = path("cube.h5");
  write_cube(p, synthetic());
  hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  ASSERT_GE(H5Ldelete(f, "/objects/rock_b/max_slip_m", H5P_DEFAULT), 0);
  H5Fclose(f);
  expect_input_error([&] { read_cube(p); }, p, "reading dataset /objects/rock_b/max_slip_m");

  write_cube(p, synthetic());
  f = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t a = H5Aopen(f, "schema_version", H5P_DEFAULT);
  const int future = kCubeSchemaVersion + 1;
  ASSERT_EQ(future, 4);  // 3, the checksummed layout, is read
  ASSERT_GE(H5Awrite(a, H5T_NATIVE_INT, &future), 0);
  H5Aclose(a);
  H5Fclose(f);
  expect_input_error([&] { read_cube(p); }, p, "schema_version 4 is not one this Rigid reads (1 to 3)");
}

TEST_F(CubeFile, DimensionScalesAreAttached) {
  const std::string p = path("cube.h5");
  write_cube(p, synthetic());
  const hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const auto open = [&](const std::string& name) { return H5Dopen2(f, name.c_str(), H5P_DEFAULT); };
  for (const char* axis : {"/axes/record", "/axes/scale_g", "/axes/rotation", "/axes/pgv_pga_bin"}) {
    const hid_t s = open(axis);
    EXPECT_GT(H5DSis_scale(s), 0) << axis;
    H5Dclose(s);
  }
  const auto expect_scales = [&](const std::string& name, std::vector<hid_t> scales) {
    const hid_t d = open(name);
    ASSERT_GE(d, 0) << name;
    for (unsigned i = 0; i < scales.size(); ++i) {
      EXPECT_GT(H5DSis_attached(d, scales[i], i), 0) << name << " dim " << i;
      EXPECT_EQ(H5DSget_num_scales(d, i), 1) << name << " dim " << i;  // netCDF-4 wants exactly one
    }
    char label[32] = {};
    EXPECT_GT(H5DSget_label(d, 0, label, sizeof label), 0);
    EXPECT_STRNE(label, "");
    H5Dclose(d);
  };
  // netCDF-4 sees a dimension scale only in the variable's own group or an ancestor
  for (const std::string obj : {"/objects/rock a/", "/objects/rock_b/"}) {
    const hid_t record = open(obj + "record"), scale = open(obj + "scale"), rotation = open(obj + "rotation"),
                bin = open(obj + "pgv_pga_bin");
    for (hid_t s : {record, scale, rotation, bin}) EXPECT_GT(H5DSis_scale(s), 0) << obj;
    for (const char* ds : {"outcome", "rotation_deg", "failure_time_s", "max_tilt_deg", "max_slip_m", "wall_s",
                           "failure_reason", "failure_message", "unconverged_steps"})
      expect_scales(obj + ds, {record, scale, rotation});
    expect_scales(obj + "probability", {record, scale});
    expect_scales(obj + "fragility", {scale, bin});
    expect_scales(obj + "fragility_count", {scale, bin});
    expect_scales(obj + "target_pga", {scale});
    for (hid_t s : {record, scale, rotation, bin}) H5Dclose(s);
  }
  const hid_t record = open("/records/record");
  expect_scales("/records/pgv_pga_s", {record});
  H5Dclose(record);
  H5Fclose(f);
}

TEST(CubeVariants, ConsistentVariantCubeHasNoProblem) {
  EXPECT_EQ(cube_problem(variant_synthetic()), "");
  EXPECT_EQ(object_label(variant_synthetic().objects[4]), "rock_b [v1]");
  EXPECT_EQ(object_label(synthetic().objects[1]), "rock_b");
}

TEST(CubeVariants, ProblemsOfTheVariantAxisAreCaught) {
  const auto problem_of = [](auto change) {
    Cube c = variant_synthetic();
    change(c);
    return cube_problem(c);
  };
  const auto expect_problem = [](const std::string& problem, const std::string& needle) {
    EXPECT_NE(problem.find(needle), std::string::npos) << "problem: '" << problem << "', expected: " << needle;
  };
  // a missing variant: rock a's variant 1 gone, so its variant 2 sits where 1 belongs
  expect_problem(problem_of([](Cube& c) { c.objects.erase(c.objects.begin() + 1); }),
                 "object 1 ('rock a'): variant 2, expected 1");
  // the last base object one variant short
  expect_problem(problem_of([](Cube& c) { c.objects.pop_back(); }), "'rock_b' has 2 of the 3 variants");
  // variants out of order
  expect_problem(problem_of([](Cube& c) { std::swap(c.objects[0].variant, c.objects[1].variant); }),
                 "object 0 ('rock a'): variant 1, expected 0");
  // one base object's variants under two names
  expect_problem(problem_of([](Cube& c) { c.objects[2].name = "rock c"; }), "has another name or scene");
  // two base objects of one name
  expect_problem(problem_of([](Cube& c) {
                   for (int v = 0; v < kVariants; ++v) c.objects[kVariants + v].name = "rock a";
                 }),
                 "two objects are named 'rock a'");
  // a parameter with fewer values (or labels) than variants
  expect_problem(problem_of([](Cube& c) { c.variants.parameters[0].values.pop_back(); }),
                 "variant parameter 'friction': has 2 values, expected 3");
  expect_problem(problem_of([](Cube& c) { c.variants.parameters[1].labels.push_back("rigid"); }),
                 "variant parameter 'contact': has 4 labels, expected 3");
  expect_problem(problem_of([](Cube& c) { c.variants.count = 2; }), "has 3 values, expected 2");
  expect_problem(problem_of([](Cube& c) {
                   c.variants.parameters[0].labels = {"a", "b", "c"};
                 }),
                 "has both numbers and labels");
  // a duplicate parameter, and names that cannot be HDF5 dataset names
  expect_problem(problem_of([](Cube& c) { c.variants.parameters[2].name = "friction"; }),
                 "two variant parameters are named 'friction'");
  for (const char* bad : {"", ".", "a/b", "variant"})
    expect_problem(problem_of([&](Cube& c) { c.variants.parameters[0].name = bad; }), "not a valid dataset name");
  expect_problem(problem_of([](Cube& c) { c.variants.parameters[0].name = "static friction"; }), "white space");
  // without variants, no object may claim one
  Cube plain = synthetic();
  plain.objects[1].variant = 0;
  expect_problem(cube_problem(plain), "object 'rock_b': variant 0 in a cube without variants");
  plain = synthetic();
  plain.variants.parameters = variant_synthetic().variants.parameters;
  expect_problem(cube_problem(plain), "parameters given but count is 0");
}

TEST_F(CubeFile, VariantCubeRoundTripsFieldByField) {
  const Cube c = variant_synthetic();
  const std::string p = path("variants.h5");
  write_cube(p, c);
  const Cube back = read_cube(p);
  ASSERT_EQ(back.objects.size(), 2u * kVariants);
  expect_same(c, back);
  for (std::size_t i = 0; i < back.objects.size(); ++i) {
    EXPECT_EQ(back.objects[i].variant, static_cast<int>(i % kVariants));
    EXPECT_EQ(back.objects[i].name, i < kVariants ? "rock a" : "rock_b");
  }
  // the variants' cells really differ, so a mix-up would show
  EXPECT_NE(back.objects[0].outcome, back.objects[1].outcome);
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);  // every HDF5 handle closed
}

TEST_F(CubeFile, VariantLayoutAsTheSpecificationSaysThroughTheHdf5CApi) {
  const Cube c = variant_synthetic();
  const std::string p = path("variants.h5");
  write_cube(p, c);
  const hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(number_attribute<std::int32_t>(f, "/", "schema_version", H5T_NATIVE_INT32), kCubeSchemaVersion);
  // the table
  EXPECT_EQ(string_attribute(f, "/variants", "method"), "lhs");
  EXPECT_EQ(number_attribute<std::uint64_t>(f, "/variants", "seed", H5T_NATIVE_UINT64), 0x8000000000000001ULL);
  EXPECT_EQ(number_attribute<std::int32_t>(f, "/variants", "count", H5T_NATIVE_INT32), 3);
  EXPECT_EQ(string_attribute(f, "/variants", "parameters"), "friction contact density_kg_m3");
  EXPECT_EQ(read_dataset<std::int32_t>(f, "/variants/variant", H5T_NATIVE_INT32), (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(read_dataset<double>(f, "/variants/friction", H5T_NATIVE_DOUBLE),
            (std::vector<double>{0.5, 0.6000000000000001, 0.75}));
  EXPECT_EQ(string_attribute(f, "/variants/friction", "units"), "1");
  EXPECT_EQ(string_attribute(f, "/variants/density_kg_m3", "units"), "kg m-3");
  EXPECT_EQ(string_attribute(f, "/variants/density_kg_m3", "description"), "density of every block");
  EXPECT_EQ(string_attribute(f, "/variants/contact", "units"), "(missing)");  // text: no units (CF)
  EXPECT_EQ(string_attribute(f, "/variants/contact", "long_name"), "contact");
  const hid_t table_scale = H5Dopen2(f, "/variants/variant", H5P_DEFAULT);
  EXPECT_GT(H5DSis_scale(table_scale), 0);
  for (const char* param : {"/variants/friction", "/variants/contact", "/variants/density_kg_m3"}) {
    const hid_t d = H5Dopen2(f, param, H5P_DEFAULT);
    EXPECT_GT(H5DSis_attached(d, table_scale, 0), 0) << param;
    H5Dclose(d);
  }
  H5Dclose(table_scale);

  // one group per base object, its cells led by the variant dimension
  const std::string g = "/objects/rock a/";
  EXPECT_EQ(number_attribute<std::int32_t>(f, "/objects/rock a", "variants", H5T_NATIVE_INT32), 3);
  EXPECT_EQ(number_attribute<std::int32_t>(f, "/objects/rock_b", "index", H5T_NATIVE_INT32), 1);
  EXPECT_EQ(string_attribute(f, "/objects/rock_b", "scene"), "models/rock_b.toml");
  EXPECT_EQ(dataset_dims(f, g + "outcome"), (std::vector<hsize_t>{3, 3, 4, 2}));  // [V, R, S, A]
  EXPECT_EQ(dataset_dims(f, g + "failure_message"), (std::vector<hsize_t>{3, 3, 4, 2}));
  EXPECT_EQ(dataset_dims(f, g + "probability"), (std::vector<hsize_t>{3, 3, 4}));
  EXPECT_EQ(dataset_dims(f, g + "fragility"), (std::vector<hsize_t>{3, 4, 9}));
  EXPECT_EQ(dataset_dims(f, g + "fragility_count"), (std::vector<hsize_t>{3, 4, 9}));
  EXPECT_EQ(dataset_dims(f, g + "alpha_by_azimuth_rad"), (std::vector<hsize_t>{3, 4}));
  EXPECT_EQ(H5Lexists(f, "/objects/rock_b/alpha_by_azimuth_rad", H5P_DEFAULT), 0);  // none to store
  const std::vector<double> alpha = read_dataset<double>(f, g + "alpha_rad", H5T_NATIVE_DOUBLE);
  EXPECT_EQ(alpha, (std::vector<double>{0.2, 0.2 + 0.01, 0.2 + 0.02}));
  EXPECT_EQ(string_attribute(f, g + "alpha_rad", "units"), "rad");
  for (const double a : read_dataset<double>(f, "/objects/rock_b/alpha_rad", H5T_NATIVE_DOUBLE))
    EXPECT_TRUE(std::isnan(a));

  const hid_t scale = H5Dopen2(f, (g + "variant").c_str(), H5P_DEFAULT);
  EXPECT_GT(H5DSis_scale(scale), 0);
  EXPECT_EQ(read_dataset<std::int32_t>(f, g + "variant", H5T_NATIVE_INT32), (std::vector<std::int32_t>{0, 1, 2}));
  for (const char* ds : {"outcome",           "rotation_deg",  "failure_time_s",    "max_tilt_deg",
                         "max_slip_m",        "wall_s",        "failure_reason",    "failure_message",
                         "unconverged_steps", "probability",   "fragility",         "fragility_count",
                         "alpha_rad",         "p_rad_s",       "rocking_radius_m",  "weakest_azimuth_deg",
                         "physics_json",      "inputs_sha256", "support_polygon_m", "alpha_by_azimuth_rad"}) {
    const hid_t d = H5Dopen2(f, (g + ds).c_str(), H5P_DEFAULT);
    ASSERT_GE(d, 0) << ds;
    EXPECT_GT(H5DSis_attached(d, scale, 0), 0) << ds;
    EXPECT_EQ(H5DSget_num_scales(d, 0), 1) << ds;  // netCDF-4 wants exactly one
    char label[32] = {};
    H5DSget_label(d, 0, label, sizeof label);
    EXPECT_STREQ(label, "variant") << ds;
    EXPECT_NE(string_attribute(f, g + ds, "long_name"), "(missing)") << ds;
    EXPECT_NE(string_attribute(f, g + ds, "description"), "(missing)") << ds;
    H5Dclose(d);
  }
  H5Dclose(scale);
  EXPECT_EQ(H5Lexists(f, "/objects/rock a/rock a", H5P_DEFAULT), 0);  // one group, not one per variant
  H5Fclose(f);
}

TEST_F(CubeFile, EachVariantsDerivedProductsAreThoseOfItsObjectCube) {
  const Cube c = variant_synthetic();
  const std::string p = path("variants.h5");
  write_cube(p, c);
  const hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  for (std::size_t base = 0; base < 2; ++base) {
    const std::string g = "/objects/" + c.objects[base * kVariants].name + "/";
    const std::vector<double> p_all = read_dataset<double>(f, g + "probability", H5T_NATIVE_DOUBLE);
    const std::vector<double> frag_all = read_dataset<double>(f, g + "fragility", H5T_NATIVE_DOUBLE);
    const std::vector<std::int32_t> count_all = read_dataset<std::int32_t>(f, g + "fragility_count", H5T_NATIVE_INT32);
    const std::size_t RS = 3 * 4, SB = 4 * 9;
    ASSERT_EQ(p_all.size(), kVariants * RS);
    ASSERT_EQ(frag_all.size(), kVariants * SB);
    for (std::size_t v = 0; v < kVariants; ++v) {
      const ObjectCube& o = c.objects[base * kVariants + v];
      const std::string what = g + " variant " + std::to_string(v);
      expect_equal_or_both_nan({p_all.begin() + v * RS, p_all.begin() + (v + 1) * RS}, overturn_probability(c, o),
                               what + " probability");
      const FragilitySurface s = fragility_surface(c, o);
      expect_equal_or_both_nan({frag_all.begin() + v * SB, frag_all.begin() + (v + 1) * SB}, s.probability,
                               what + " fragility");
      EXPECT_EQ(std::vector<std::int32_t>(count_all.begin() + v * SB, count_all.begin() + (v + 1) * SB), s.count)
          << what;
    }
  }
  H5Fclose(f);
}

TEST_F(CubeFile, ACubeWithoutVariantsKeepsTheFirstLayout) {
  const std::string p = path("plain.h5");
  write_cube(p, synthetic());
  const hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(number_attribute<std::int32_t>(f, "/", "schema_version", H5T_NATIVE_INT32), kCubeSchemaVersion);
  EXPECT_EQ(H5Lexists(f, "/variants", H5P_DEFAULT), 0);
  EXPECT_EQ(H5Lexists(f, "/objects/rock a/variant", H5P_DEFAULT), 0);
  EXPECT_EQ(H5Aexists_by_name(f, "/objects/rock a", "variants", H5P_DEFAULT), 0);
  EXPECT_EQ(dataset_dims(f, "/objects/rock a/outcome"), (std::vector<hsize_t>{3, 4, 2}));
  EXPECT_EQ(dataset_dims(f, "/objects/rock a/probability"), (std::vector<hsize_t>{3, 4}));
  H5Fclose(f);
  for (const ObjectCube& o : read_cube(p).objects) EXPECT_EQ(o.variant, -1);
}

TEST(CubeVariants, CellsTableHasAVariantColumnOnlyWithVariants) {
  std::ostringstream plain, varied;
  write_cells_csv(plain, synthetic());
  write_cells_csv(varied, variant_synthetic());
  const auto lines = [](const std::string& text) {
    std::vector<std::string> v;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line, '\n');) v.push_back(line);
    return v;
  };
  const std::vector<std::string> p = lines(plain.str()), v = lines(varied.str());
  EXPECT_EQ(p.front(),
            "object,record,scale_g,rotation,rotation_deg,outcome,failure_time_s,max_tilt_deg,max_slip_m,"
            "failure_reason,failure_message,unconverged_steps\r");
  EXPECT_EQ(v.front(),
            "object,variant,record,scale_g,rotation,rotation_deg,outcome,failure_time_s,max_tilt_deg,"
            "max_slip_m,failure_reason,failure_message,unconverged_steps\r");
  // rock_b's variant 2 starts after 5 object-variants of 24 cells (messages of rock a hold line
  // breaks, so count rows by their first field instead of by line)
  std::size_t rows_of_rock_b_v2 = 0;
  for (const std::string& line : v) rows_of_rock_b_v2 += line.rfind("rock_b,2,", 0) == 0;
  EXPECT_EQ(rows_of_rock_b_v2, 24u);
}

TEST_F(CubeFile, DamagedVariantCubesAreRejected) {
  const std::string p = path("variants.h5");
  const auto damage = [&](auto change) {
    write_cube(p, variant_synthetic());
    const hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    change(f);
    H5Fclose(f);
  };
  // outcome with the wrong number of variants
  damage([](hid_t f) {
    ASSERT_GE(H5Ldelete(f, "/objects/rock a/outcome", H5P_DEFAULT), 0);
    const hsize_t dims[4] = {2, 3, 4, 2};
    const hid_t space = H5Screate_simple(4, dims, nullptr);
    const hid_t d =
        H5Dcreate2(f, "/objects/rock a/outcome", H5T_STD_I8LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(d, 0);
    H5Dclose(d);
    H5Sclose(space);
  });
  expect_input_error([&] { read_cube(p); }, p,
                     "reading dataset /objects/rock a/outcome: shape [2, 3, 4, 2], expected [3, 3, 4, 2]");
  // no table: in schema 3 the table's presence says the cube has variants, and its checksum
  // says the table was there
  damage([](hid_t f) { ASSERT_GE(H5Ldelete(f, "/variants", H5P_DEFAULT), 0); });
  expect_input_error([&] { read_cube(p); }, p, "axes, records or variant table changed since written");
  // a schema 2 cube (variants by its version) without its table
  damage([](hid_t f) {
    ASSERT_GE(H5Ldelete(f, "/variants", H5P_DEFAULT), 0);
    replace_int32_attribute(f, "/", "schema_version", kCubeSchemaVersionWithVariants);
  });
  expect_input_error([&] { read_cube(p); }, p, "without its variant table /variants");
  // a table whose count disagrees with its axis
  damage([](hid_t f) { replace_int32_attribute(f, "/variants", "count", 4); });
  expect_input_error([&] { read_cube(p); }, p, "/variants: count 4 does not match /variants/variant (3 values)");
  // a parameter named but not stored
  damage([](hid_t f) { ASSERT_GE(H5Ldelete(f, "/variants/contact", H5P_DEFAULT), 0); });
  expect_input_error([&] { read_cube(p); }, p, "parameter contact has no dataset /variants/contact");
  // a group that claims another number of variants than the table
  damage([](hid_t f) { replace_int32_attribute(f, "/objects/rock_b", "variants", 2); });
  expect_input_error([&] { read_cube(p); }, p, "/objects/rock_b: attribute variants 2 does not match");
  // a per-variant dataset missing
  damage([](hid_t f) { ASSERT_GE(H5Ldelete(f, "/objects/rock_b/p_rad_s", H5P_DEFAULT), 0); });
  expect_input_error([&] { read_cube(p); }, p, "reading dataset /objects/rock_b/p_rad_s");
  // a flipped outcome byte of one variant fails the group's checksum
  damage([](hid_t f) {
    const hid_t d = H5Dopen2(f, "/objects/rock_b/outcome", H5P_DEFAULT);
    const hid_t space = H5Dget_space(d);
    const hsize_t cell[4] = {2, 1, 1, 0}, one[4] = {1, 1, 1, 1};
    H5Sselect_hyperslab(space, H5S_SELECT_SET, cell, nullptr, one, nullptr);
    const hid_t mem = H5Screate_simple(4, one, nullptr);
    std::int8_t value = 0;
    H5Dread(d, H5T_NATIVE_INT8, mem, space, H5P_DEFAULT, &value);
    value = static_cast<std::int8_t>(value ^ 1);
    ASSERT_GE(H5Dwrite(d, H5T_NATIVE_INT8, mem, space, H5P_DEFAULT, &value), 0);
    H5Sclose(mem);
    H5Sclose(space);
    H5Dclose(d);
  });
  expect_input_error([&] { read_cube(p); }, p, "/objects/rock_b: datasets changed since written (checksum mismatch)");
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);  // failures close their handles too
}

/// Overwrites one cell of an int8 dataset in place, as a damaged or tampered file would have it.
void overwrite_cell(const std::string& file, const char* dataset, std::int8_t value) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
  ASSERT_GE(d, 0);
  const hid_t space = H5Dget_space(d);
  const hsize_t cell[3] = {1, 2, 1}, one[3] = {1, 1, 1};
  ASSERT_GE(H5Sselect_hyperslab(space, H5S_SELECT_SET, cell, nullptr, one, nullptr), 0);
  const hid_t mem = H5Screate_simple(3, one, nullptr);
  ASSERT_GE(H5Dwrite(d, H5T_NATIVE_INT8, mem, space, H5P_DEFAULT, &value), 0);
  H5Sclose(mem);
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
}

/// Overwrites the first value of a one-dimensional float64 dataset in place.
void overwrite_first_number(const std::string& file, const char* dataset, double value) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
  ASSERT_GE(d, 0);
  const hid_t space = H5Dget_space(d);
  const hsize_t first[1] = {0}, one[1] = {1};
  ASSERT_GE(H5Sselect_hyperslab(space, H5S_SELECT_SET, first, nullptr, one, nullptr), 0);
  const hid_t mem = H5Screate_simple(1, one, nullptr);
  ASSERT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, &value), 0);
  H5Sclose(mem);
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
}

TEST_F(CubeFile, AChangedOutcomeFailsTheChecksum) {
  const std::string p = path("cube.h5");
  const Cube c = synthetic();
  write_cube(p, c);
  const std::int8_t was = c.objects[1].outcome[(1 * 4 + 2) * 2 + 1];
  overwrite_cell(p, "/objects/rock_b/outcome", static_cast<std::int8_t>(was ^ 1));  // one bit
  expect_input_error([&] { read_cube(p); }, p, "/objects/rock_b: datasets changed since written (checksum mismatch)");
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);

  overwrite_cell(p, "/objects/rock_b/outcome", was);  // restored: reads again
  expect_same(c, read_cube(p));
}

TEST_F(CubeFile, CubesFromBeforeMessagesAndChecksumsStillRead) {
  const std::string p = path("cube.h5");
  write_cube(p, synthetic());
  const hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  for (const char* g : {"/objects/rock a", "/objects/rock_b"}) {
    ASSERT_GE(H5Ldelete(f, (std::string(g) + "/failure_message").c_str(), H5P_DEFAULT), 0);
    ASSERT_GE(H5Ldelete(f, (std::string(g) + "/unconverged_steps").c_str(), H5P_DEFAULT), 0);
    ASSERT_GE(H5Adelete_by_name(f, g, "datasets_sha256", H5P_DEFAULT), 0);
  }
  // what a cube of schema 1 had: no axes checksum either
  ASSERT_GE(H5Adelete_by_name(f, "/", "axes_sha256", H5P_DEFAULT), 0);
  replace_int32_attribute(f, "/", "schema_version", kCubeSchemaVersionWithoutVariants);
  H5Fclose(f);
  const Cube back = read_cube(p);
  for (const ObjectCube& o : back.objects) {
    EXPECT_TRUE(o.failure_message.empty()) << o.name;
    EXPECT_TRUE(o.unconverged_steps.empty()) << o.name;
  }
  EXPECT_EQ(back.objects[0].outcome, synthetic().objects[0].outcome);
  EXPECT_NE(old_cube_warning(p, back).find("schema_version 1 cube, written before checksums"), std::string::npos);
  write_cube(p, back);  // a rewrite (a resume) makes it a cube of the current schema
  EXPECT_EQ(old_cube_warning(p, read_cube(p)), "");
}

TEST_F(CubeFile, ADeletedChecksumIsNoOldCube) {
  const std::string p = path("cube.h5");
  write_cube(p, synthetic());
  hid_t f = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  ASSERT_GE(H5Adelete_by_name(f, "/objects/rock_b", "datasets_sha256", H5P_DEFAULT), 0);
  H5Fclose(f);
  expect_input_error([&] { read_cube(p); }, p, "/objects/rock_b: no datasets_sha256");

  write_cube(p, synthetic());
  f = H5Fopen(p.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  ASSERT_GE(H5Adelete_by_name(f, "/", "axes_sha256", H5P_DEFAULT), 0);
  H5Fclose(f);
  expect_input_error([&] { read_cube(p); }, p, "no axes_sha256");
}

TEST_F(CubeFile, AChangedScaleOrRecordFailsTheAxesChecksum) {
  const std::string p = path("cube.h5");
  const Cube c = synthetic();
  for (const char* dataset : {"/axes/scale_g", "/records/pgv_pga_s"}) {
    write_cube(p, c);
    overwrite_first_number(p, dataset, 1.2345);
    expect_input_error([&] { read_cube(p); }, p, "axes, records or variant table changed since written");
  }
}

TEST_F(CubeFile, AKillAtAnyInstantLeavesAValidFile) {
  // A child rewrites the cube in a loop (alternating two contents) and is SIGKILLed at varying
  // moments; the file must always read back as one of the two complete cubes.
  const std::string p = path("cube.h5");
  const Cube small = synthetic();
  Cube big = synthetic();
  // large enough (a few MB) that writing and syncing PATH.tmp, after the in-memory build, takes a
  // good part of each rewrite
  for (int k = 0; k < 3000; ++k) {
    RecordMeta m = small.records[k % 3];
    m.name += " " + std::to_string(k);
    big.records.push_back(m);
  }
  for (ObjectCube& o : big.objects) {
    const std::size_t n = big.records.size() * 4 * 2;
    for (auto* v : {&o.rotation_deg, &o.failure_time_s, &o.max_tilt_deg, &o.max_slip_m, &o.wall_s}) v->resize(n, 1.0);
    o.outcome.resize(n, static_cast<std::int8_t>(O::survived));
    if (!o.failure_message.empty()) o.failure_message.resize(n);
    if (!o.unconverged_steps.empty()) o.unconverged_steps.resize(n, 0);
    o.failure_reason.resize(n, 0);
  }
  write_cube(p, small);
  int mid_write = 0;  // kills that caught the child with PATH.tmp on disk
  for (int round = 0; round < 16; ++round) {
    fs::remove(p + ".tmp");  // left by the last kill: a PATH.tmp seen below is this child's
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      for (int i = 0;; ++i) {
        try {
          write_cube(p, i % 2 ? big : small);
        } catch (...) {
          ::_exit(3);
        }
      }
    }
    if (round % 2 == 0) {
      ::usleep(static_cast<useconds_t>(20000 + 7000 * round));  // any instant
    } else {
      // the instant that matters: PATH.tmp being written (the cube is built in memory before)
      for (int k = 0; k < 40000 && !fs::exists(p + ".tmp"); ++k) ::usleep(50);
    }
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the writer child exited by itself: " << status;
    mid_write += fs::exists(p + ".tmp");
    Cube got;
    ASSERT_NO_THROW(got = read_cube(p)) << "round " << round;
    EXPECT_TRUE(got.records.size() == small.records.size() || got.records.size() == big.records.size());
  }
  // some kills must have landed between creating PATH.tmp and renaming it, or the test proved
  // nothing
  EXPECT_GT(mid_write, 0);
  write_cube(p, small);
  EXPECT_FALSE(fs::exists(p + ".tmp"));
  expect_same(small, read_cube(p));
}

// Writes the fixture of tests/python/test_cube.py (ctest fixture cube_fixture) to the path in
// RIGID_CUBE_FIXTURE; skipped when that is not set, so plain test runs do not race on one file.
TEST(CubeFixture, WritesThePythonFixture) {
  const char* p = std::getenv("RIGID_CUBE_FIXTURE");
  if (p == nullptr || *p == '\0') GTEST_SKIP() << "RIGID_CUBE_FIXTURE not set (ctest sets it for cube_fixture)";
  fs::create_directories(fs::path(p).parent_path());
  write_cube(p, synthetic());
  expect_same(synthetic(), read_cube(p));
}

// The variant cube of tests/python/test_variant_cube.py (ctest fixture variant_cube_fixture), at
// the path in RIGID_VARIANT_CUBE_FIXTURE; skipped when that is not set.
TEST(CubeFixture, WritesTheVariantFixture) {
  const char* p = std::getenv("RIGID_VARIANT_CUBE_FIXTURE");
  if (p == nullptr || *p == '\0')
    GTEST_SKIP() << "RIGID_VARIANT_CUBE_FIXTURE not set (ctest sets it for variant_cube_fixture)";
  fs::create_directories(fs::path(p).parent_path());
  write_cube(p, variant_synthetic());
  expect_same(variant_synthetic(), read_cube(p));
}

}  // namespace
}  // namespace rigid::io
