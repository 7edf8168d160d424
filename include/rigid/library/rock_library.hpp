#pragma once
/// The rock library (models/library): the study's rectangular validation blocks, the geode, and
/// nine synthetic analogues of its Yucca Mountain objects, every piece a convex hull of a seeded,
/// shaped point cloud (tilt_test.hpp gives each model its toppling acceleration). Pure functions:
/// no I/O (`rigid model library` writes the files).
#include <string>
#include <vector>

#include "rigid/scenario/scene.hpp"

namespace rigid::library {

/// One block of a library model, in its place (world coordinates at build time, unit: m).
struct LibraryPiece {
  std::string name;             ///< block name, also the STL file stem
  geometry::TriangleSoup soup;  ///< closed, convex, outward triangles
  bool fixed = false;           ///< true: driven by the ground (pedestal, base, wall, rock face)
};

/// A library model: pieces listed fixed ones first, free ones bottom to top.
struct LibraryModel {
  std::string name;         ///< directory and file stem, e.g. "single_rock_050"
  std::string description;  ///< one line: what it is an analogue of
  std::vector<LibraryPiece> pieces;
  scenario::FailureRule failure;  ///< the rule that suits the model
  std::string failure_note;       ///< why that rule
  /// The free pieces form one vertical stack with horizontal interfaces, each resting only on the
  /// piece listed before it (the first free piece on the last fixed one), so the rigid-statics
  /// toppling estimate (static_toppling) applies.
  bool simple_stack = false;
};

/// Every model of the library, in card order: block_a01..a04, geode, the nine analogues. Built
/// from fixed seeds, so the result is the same on every call.
std::vector<LibraryModel> rock_library();

/// The scene of a model at build time (not yet settled), with the study's contact law and
/// density (physics.md §11) unless given. Block names are the piece names.
scenario::Scene library_scene(const LibraryModel& model, const contact::ContactLaw& law = {}, double density = 2600);

/// Rigid-statics toppling acceleration of a simple stack (LibraryModel::simple_stack) at build
/// time, an independent estimate: for every interface, the free pieces above it rock as one rigid
/// body about the edge of the contact polygon (the intersection of the two touching faces), and
/// topple when the resultant of gravity and the inertial force leaves the polygon. In direction
/// `azimuth` of the ground acceleration that is a/g = s / h, with h the height of the combined
/// centroid above the interface and s the distance from its projection to the polygon edge along
/// -azimuth. Returns the minimum over the interfaces (unit: g); azimuth < 0 means the minimum over
/// all directions. Throws std::invalid_argument for a model that is not a simple stack.
double static_toppling(const LibraryModel& model, double azimuth, double density = 2600);

}  // namespace rigid::library
