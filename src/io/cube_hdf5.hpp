#pragma once
// Private to io: the HDF5 plumbing that the cube's writer (cube_write.cpp) and reader
// (cube_read.cpp) share: an error context per file, the string type, dataspaces, file access.
#include <hdf5.h>

#include <cerrno>
#include <cstring>
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
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_, 0, what + hdf5_explanation());
  }
  [[noreturn]] void fail_errno(const std::string& what) const {
    throw InputError(path_, 0, what + ": " + std::strerror(errno));
  }
  template <class T>
  T check(T status, const std::string& what) const {
    if (status < 0) fail(what);
    return status;
  }
  Hid own(hid_t id, Hid::Closer close, const std::string& what) const { return Hid(check(id, what), close); }

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

/// Why these PGV/PGA bin edges are unusable (fewer than 2, NaN, not increasing); empty if usable.
std::string edges_problem(const std::vector<double>& edges_s);

}  // namespace rigid::io
