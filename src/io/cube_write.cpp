// Writing the fragility cube (layout: the top of cube.cpp): built in memory with HDF5's core
// driver, then written to PATH.tmp, fsynced and renamed over PATH.
#include <fcntl.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <utility>

#include "cube_hdf5.hpp"
#include "cube_writer.hpp"
#include "rigid/core/types.hpp"

namespace rigid::io {

namespace fs = std::filesystem;

namespace {

void write_root_attributes(Writer& w, const Cube& c) {
  w.attribute("/", "schema_version", std::int32_t{kCubeSchemaVersion});
  w.attribute("/", "software_version", c.software_version);
  w.attribute("/", "job_text", c.job_text);
  w.attribute("/", "job_hash", c.job_hash);
  w.attribute("/", "physics_json", c.physics_json);
  w.attribute("/", "seed", std::uint64_t{c.seed});
  w.attribute("/", "units", std::string("SI unless the name says otherwise"));
  w.attribute("/", "job_inputs_sha256", c.job_inputs);
  w.attribute("/", "inputs_sha256", c.inputs_sha256);
  w.attribute("/", "axes_sha256", axes_sha256(c));
  w.attribute("/", "axes_sha256_covers", std::string(kAxesChecksumCovers));
}

// The legacy shared axes (/axes, read by h5py users by path) and the per-record table (/records).
void write_axes_and_records(Writer& w, const Cube& c) {
  const std::vector<double> edges = pgv_pga_edges(c);
  const hsize_t R = c.records.size(), S = c.scales_g.size(), A = static_cast<hsize_t>(c.rotations);
  const hsize_t B = edges.size() - 1;

  w.group("/axes");
  Hid record = w.strings("/axes/record", record_names(c), "record (set) names, in job order");
  w.make_scale(record, "/axes/record", "record");
  Hid scale =
      w.doubles("/axes/scale_g", c.scales_g, {S}, "g", scale_description(c, "target GMRotI50 PGA of each scale"));
  w.make_scale(scale, "/axes/scale_g", "scale_g");
  Hid rotation =
      w.ints("/axes/rotation", iota32(A), {A}, "none", "rotation index; the angle of each cell is in rotation_deg");
  w.make_scale(rotation, "/axes/rotation", "rotation");
  Hid bin = w.ints("/axes/pgv_pga_bin", iota32(B), {B}, "none",
                   "PGV/PGA bin index; bin i holds pgv_pga_edges_s[i] <= PGV/PGA < pgv_pga_edges_s[i+1] "
                   "(the last bin also holds its upper edge)");
  w.make_scale(bin, "/axes/pgv_pga_bin", "pgv_pga_bin");
  // its own dimension (E = B + 1 values), of which it is the coordinate: netCDF-4 readers see no
  // dimension without a scale
  Hid edge =
      w.doubles("/axes/pgv_pga_edges_s", edges, {B + 1}, "s", "edges of the PGV/PGA bins of the fragility surface");
  w.make_scale(edge, "/axes/pgv_pga_edges_s", "pgv_pga_edges_s");

  w.group("/records");
  // its own dimension scale: netCDF-4 cannot see one in the sibling group /axes
  const Hid own_record = w.strings("/records/record", record_names(c), "record (set) names, in job order");
  w.long_name("/records/record", "record (set) name");
  w.make_scale(own_record, "/records/record", "record");
  const auto text = [&](const char* name, auto field, const char* description) {
    const std::string path = std::string("/records/") + name;
    Hid d = w.strings(path, column<std::string>(c.records, field), description);
    w.attach(d, path, 0, own_record, "record");
  };
  const auto number = [&](const char* name, auto field, const char* units, const char* description) {
    const std::string path = std::string("/records/") + name;
    Hid d = w.doubles(path, column<double>(c.records, field), {R}, units, description);
    w.attach(d, path, 0, own_record, "record");
  };
  text(
      "name", [](const RecordMeta& m) { return m.name; }, "record (set) name");
  text(
      "source", [](const RecordMeta& m) { return m.source; }, "motion-set spec the record was read from");
  text(
      "earthquake", [](const RecordMeta& m) { return m.earthquake; },
      "earthquake, from the record list (may be empty)");
  text(
      "alignment", [](const RecordMeta& m) { return m.alignment; },
      "how the components were aligned to one length (zero-padding, resampling); empty if they matched");
  text(
      "inputs_sha256", [](const RecordMeta& m) { return m.inputs; },
      "SHA-256 of the record's motion files, sha256sum lines (HEX  PATH)");
  number(
      "start_s", [](const RecordMeta& m) { return m.start_s; }, "s", "start of the time window");
  number(
      "end_s", [](const RecordMeta& m) { return m.end_s; }, "s", "end of the time window");
  number(
      "gmroti_pga_g", [](const RecordMeta& m) { return m.gmroti_pga_g; }, "g",
      "GMRotI50 PGA of the windowed record, as computed");
  number(
      "gmroti_pgv_cm_s", [](const RecordMeta& m) { return m.gmroti_pgv_cm_s; }, "cm/s",
      "GMRotI50 PGV of the windowed record, as computed");
  number(
      "pgv_pga_s", [](const RecordMeta& m) { return m.pgv_pga_s; }, "s",
      "PGV/PGA of the record (bins the fragility surface)");
  number(
      "listed_pga_g", [](const RecordMeta& m) { return m.listed_pga_g; }, "g",
      "GMRotI PGA given by the record list, 0 if none");
  number(
      "listed_pgv_cm_s", [](const RecordMeta& m) { return m.listed_pgv_cm_s; }, "cm/s",
      "GMRotI PGV given by the record list, 0 if none");
}
void write_contents(const H5& h, hid_t file, const Cube& c) {
  Writer w(h, file);
  write_root_attributes(w, c);
  write_axes_and_records(w, c);
  write_objects(w, c);
}

// A string attribute, or "" when absent or unreadable.
std::string string_attribute_or_empty(hid_t loc, const char* object, const char* name) {
  if (H5Aexists_by_name(loc, object, name, H5P_DEFAULT) <= 0) return "";
  const Hid a(H5Aopen_by_name(loc, object, name, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const Hid type(H5Aget_type(a), H5Tclose);
  if (a < 0 || type < 0 || H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) <= 0) return "";
  const Hid mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mem, H5T_VARIABLE);
  H5Tset_cset(mem, H5T_CSET_UTF8);
  char* p = nullptr;
  if (H5Aread(a, mem, &p) < 0) return "";
  std::string v = p != nullptr ? p : "";
  H5free_memory(p);
  return v;
}

// The fits `rigid fragility` stored in the cube being replaced (its /fragility group) stay with
// it while they still describe it: when the axes and every object's cells hash as before (a
// finished campaign run again). Cells added by a resume make them stale, and they are dropped.
void carry_stored_fits(const H5& h, hid_t file, const std::string& path, const Cube& c) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return;
#if H5_VERSION_GE(1, 12, 0)
  if (H5Fis_accessible(path.c_str(), H5P_DEFAULT) <= 0) return;
#else
  if (H5Fis_hdf5(path.c_str()) <= 0) return;
#endif
  const Hid fapl = file_access(h);
  const Hid old(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl), H5Fclose);
  if (old < 0 || H5Lexists(old, "/fragility", H5P_DEFAULT) <= 0) return;
  if (string_attribute_or_empty(old, "/", "axes_sha256") != string_attribute_or_empty(file, "/", "axes_sha256")) return;
  std::vector<std::string> groups;
  if (c.variants.count > 0) {
    for (std::size_t i = 0; i < c.objects.size(); i += static_cast<std::size_t>(c.variants.count))
      groups.push_back("/objects/" + c.objects[i].name);
  } else {
    for (const ObjectCube& o : c.objects) groups.push_back("/objects/" + o.name);
  }
  for (const std::string& g : groups) {
    if (H5Lexists(old, "/objects", H5P_DEFAULT) <= 0 || H5Lexists(old, g.c_str(), H5P_DEFAULT) <= 0) return;
    const std::string before = string_attribute_or_empty(old, g.c_str(), "datasets_sha256");
    if (before.empty() || before != string_attribute_or_empty(file, g.c_str(), "datasets_sha256")) return;
  }
  H5Ocopy(old, "/fragility", file, "/fragility", H5P_DEFAULT, H5P_DEFAULT);
}

// Writes bytes to a new file and fsyncs it; errors name the file and errno.
void write_file(const H5& h, const std::string& p, const std::vector<unsigned char>& bytes) {
  const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) h.fail_errno("creating " + p);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      ::close(fd);
      errno = err;
      h.fail_errno("writing " + p);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    errno = err;
    h.fail_errno("syncing " + p);
  }
  if (::close(fd) != 0) h.fail_errno("closing " + p);
}

void fsync_path(const H5& h, const std::string& p, bool directory) {
  const int fd = ::open(p.c_str(), O_RDONLY | (directory ? O_DIRECTORY : 0));
  if (fd < 0) h.fail_errno("opening " + p + " to sync it");
  const int status = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  // some file systems cannot sync a directory; the rename has happened all the same
  if (status != 0 && !(directory && (err == EINVAL || err == ENOTSUP))) {
    errno = err;
    h.fail_errno("syncing " + p);
  }
}

}  // namespace

void write_cube(const std::string& path, const Cube& cube) {
  if (std::string p = cube_problem(cube); !p.empty()) throw InputError(path, 0, "cannot write the cube: " + p);
  const QuietErrors quiet;
  const H5 h(path);
  const std::string tmp = path + ".tmp";
  // Built in memory (HDF5's core driver, no backing store) and written out here: HDF5 never
  // meets a disk error, which it reports as a multi-line stack and, in 1.10, follows with a crash
  // at exit while closing the file it could not write; ours is one errno line.
  std::vector<unsigned char> image;
  {
    Hid fcpl = h.own(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "creating a file creation property list");
    h.check(H5Pset_obj_track_times(fcpl, false), "switching off root group time stamps");
    Hid fapl = file_access(h);
    h.check(H5Pset_fapl_core(fapl, 1 << 20, false), "selecting the in-memory file driver");
    // SEMI: closing the file fails rather than lingers if a handle were still open
    h.check(H5Pset_fclose_degree(fapl, H5F_CLOSE_SEMI), "setting the file close degree");
    Hid file = h.own(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl, fapl), H5Fclose, "creating the cube in memory");
    write_contents(h, file, cube);
    carry_stored_fits(h, file, path, cube);
    h.check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flushing the cube in memory");
    const ssize_t size = h.check(H5Fget_file_image(file, nullptr, 0), "sizing the cube's file image");
    image.resize(static_cast<std::size_t>(size));
    h.check(H5Fget_file_image(file, image.data(), image.size()), "copying the cube's file image");
    h.check(file.close(), "closing the cube in memory");
  }
  try {
    write_file(h, tmp, image);
    if (std::rename(tmp.c_str(), path.c_str()) != 0) h.fail_errno("renaming " + tmp + " over " + path);
    const fs::path dir = fs::path(path).parent_path();
    fsync_path(h, dir.empty() ? std::string(".") : dir.string(), true);
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);  // a partial PATH.tmp is useless; PATH is untouched
    throw;
  }
}

void silence_hdf5_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

}  // namespace rigid::io
