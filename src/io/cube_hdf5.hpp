#pragma once
// Private to io: the HDF5 plumbing that the cube's writer (cube_write.cpp) and reader
// (cube_read.cpp) share: an error context per file, the string type, dataspaces, file access.
#include <hdf5.h>

#include <cerrno>
#include <cstring>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "hdf5_handle.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/cube.hpp"

namespace rigid::io {

/// " (HDF5: outermost problem: innermost cause)", or "" when HDF5 recorded nothing.
std::string hdf5_explanation();

/// Error context of one file: every failure becomes InputError(path, 0, what + HDF5's reason).
class H5 {
 public:
  explicit H5(std::string path) : path_(std::move(path)) {}
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, 0, what + hdf5_explanation()); }
  [[noreturn]] void fail_errno(const std::string& what) const {
    throw InputError(path_, 0, what + ": " + std::strerror(errno));
  }
  template <class T>
  T check(T status, const std::string& what) const {
    if (status < 0) fail(what);
    return status;
  }
  Hid own(hid_t id, Hid::Closer close, const std::string& what) const { return Hid(check(id, what), close); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// A variable-length UTF-8 string type.
Hid string_type(const H5& h);

/// A simple dataspace of these dimensions, scalar when dims is empty.
Hid dataspace(const H5& h, const std::vector<hsize_t>& dims);

/// File access: the file is only ever written under a private PATH.tmp name and renamed into
/// place, so HDF5's file lock buys nothing; it fails on some Lustre/NFS mounts (style.md §5).
Hid file_access(const H5& h);

/// The failure messages as stored: the object's, or "" for every cell when it has none.
std::vector<std::string> stored_failure_messages(const Cube& cube, const ObjectCube& object);
/// The unconverged_steps a cube stores for an object: its own, or -1 (not recorded) for every cell.
std::vector<std::int32_t> stored_unconverged_steps(const Cube& cube, const ObjectCube& object);

/// The cells of one base object's variants end to end, as the [variant, record, scale, rotation]
/// datasets store them: each cell array is variant 0's, then variant 1's, ...; failure_message
/// holds "" for every cell of a variant that kept none. The other fields are left empty.
ObjectCube stacked_cells(const Cube& cube, std::span<const ObjectCube> variants);

/// The inverse of stacked_cells: `count` ObjectCubes holding only their cell arrays (an array
/// that is not count times as long as outcome, e.g. failure_message of an older cube, stays empty).
std::vector<ObjectCube> split_cells(const ObjectCube& stacked, std::size_t count);

/// What an object group's datasets_sha256 covers, in order (its attribute datasets_sha256_covers):
/// every cell dataset but wall_s, which differs from run to run and would make the checksum so.
inline constexpr const char* kChecksumCovers =
    "SHA-256 over outcome rotation_deg failure_time_s max_tilt_deg max_slip_m failure_reason "
    "failure_message, in this order: numbers as stored (little-endian), each string as its length "
    "(uint64 little-endian) and its UTF-8 bytes";

/// SHA-256 (hex) of an object's cell datasets as stored (kChecksumCovers), with `failure_message`
/// the stored messages: what datasets_sha256 records at write and read_cube checks.
std::string cell_datasets_sha256(const ObjectCube& object, const std::vector<std::string>& failure_message);

/// What the root attribute axes_sha256 covers, in order (its attribute axes_sha256_covers): the
/// datasets outside the object groups that a result depends on.
inline constexpr const char* kAxesChecksumCovers =
    "SHA-256 over /axes/record /axes/scale_g /axes/pgv_pga_edges_s /records/name /records/source "
    "/records/earthquake /records/alignment /records/inputs_sha256 /records/start_s /records/end_s "
    "/records/gmroti_pga_g /records/gmroti_pgv_cm_s /records/pgv_pga_s /records/listed_pga_g "
    "/records/listed_pgv_cm_s, then each /variants/<parameter> in the order of the attribute "
    "parameters of /variants, in this order: numbers as stored (little-endian), each string as its "
    "length (uint64 little-endian) and its UTF-8 bytes";

/// SHA-256 (hex) of a cube's axes, records and variant table as write_cube stores them
/// (kAxesChecksumCovers): what axes_sha256 records at write and read_cube checks.
std::string axes_sha256(const Cube& cube);

}  // namespace rigid::io
