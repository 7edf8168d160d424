// The HDF5 plumbing shared by the cube's writer and reader (cube_hdf5.hpp).
#include "cube_hdf5.hpp"

namespace rigid::io {

namespace {

herr_t collect_error(unsigned, const H5E_error2_t* e, void* out) {
  if (e->desc != nullptr && e->desc[0] != '\0') static_cast<std::vector<std::string>*>(out)->push_back(e->desc);
  return 0;
}

}  // namespace

std::string hdf5_explanation() {
  std::vector<std::string> d;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_error, &d);
  if (d.empty()) return {};
  std::string s = " (HDF5: " + d.front();
  if (d.size() > 1 && d.back() != d.front()) s += ": " + d.back();
  for (char& c : s) {
    if (c == '\n') c = ' ';  // some descriptions span lines; ours is one
  }
  return s + ")";
}

Hid string_type(const H5& h) {
  Hid t = h.own(H5Tcopy(H5T_C_S1), H5Tclose, "copying the string type");
  h.check(H5Tset_size(t, H5T_VARIABLE), "making the string type variable-length");
  h.check(H5Tset_cset(t, H5T_CSET_UTF8), "setting the string type to UTF-8");
  return t;
}

Hid dataspace(const H5& h, const std::vector<hsize_t>& dims) {
  if (dims.empty()) return h.own(H5Screate(H5S_SCALAR), H5Sclose, "creating a scalar dataspace");
  return h.own(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, "creating a dataspace");
}

/// File access: the file is only ever written under a private PATH.tmp name and renamed into
/// place, so HDF5's file lock buys nothing; it fails on some Lustre/NFS mounts (style.md §5).
Hid file_access(const H5& h) {
  Hid fapl = h.own(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "creating a file access property list");
#if (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 10 && H5_VERS_RELEASE >= 7) || H5_VERSION_GE(1, 12, 1)
  h.check(H5Pset_file_locking(fapl, false, true), "disabling file locking");
#endif
  return fapl;
}

}  // namespace rigid::io
