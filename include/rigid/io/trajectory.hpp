#pragma once
/// Block trajectories for viewing a run: XDMF (XML) beside an HDF5 file holding each block's
/// triangles once and its world vertex positions per frame. ParaView opens the .xdmf; h5py reads
/// the .h5 directly.
#include <string>
#include <vector>

#include "rigid/dynamics/world.hpp"

namespace rigid::io {

class TrajectoryRecorder {
 public:
  /// Records frames of `world`'s blocks (triangulated faces, world vertices).
  void record(const dynamics::World& world);
  std::size_t frames() const { return times_.size(); }

  /// Writes PATH (the .xdmf, any name) and PATH without extension + ".h5". Throws
  /// rigid::InputError on failure.
  void write(const std::string& xdmf_path) const;

 private:
  std::vector<std::string> names_;
  std::vector<std::vector<int>> triangles_;  // per block, 3 indices per triangle
  std::vector<double> times_;
  std::vector<std::vector<std::vector<double>>> xyz_;  // [frame][block] -> 3 V doubles
};

}  // namespace rigid::io
