// The rigid-statics toppling estimate of a library model that is a simple stack: the closed form
// the tilt test and the dynamic runs are checked against.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rigid/geometry/polygon2d.hpp"
#include "rigid/geometry/polyhedron.hpp"
#include "rigid/library/rock_library.hpp"
#include "rock_shapes.hpp"

namespace rigid::library {

// scenes, drives and the run are scenario's; this module builds on them
using namespace scenario;

using P2 = geometry::Point2;
using shapes::face_polygon;
using shapes::max_z;
using shapes::min_z;

double static_toppling(const LibraryModel& model, double azimuth, double density) {
  if (!model.simple_stack) throw std::invalid_argument("static_toppling: " + model.name + " is not a simple stack");
  std::size_t first_free = 0;
  while (first_free < model.pieces.size() && model.pieces[first_free].fixed) ++first_free;
  if (first_free == 0 || first_free == model.pieces.size()) {
    throw std::invalid_argument("static_toppling: " + model.name + " needs fixed pieces then free ones");
  }
  // mass and centroid of each free piece
  std::vector<double> mass(model.pieces.size(), 0);
  std::vector<Vec3> centroid(model.pieces.size(), Vec3::Zero());
  for (std::size_t k = first_free; k < model.pieces.size(); ++k) {
    const auto mesh = geometry::make_closed_mesh(model.pieces[k].soup, geometry::MeshOptions{}, model.pieces[k].name);
    const auto props = geometry::mass_properties(mesh, density);
    mass[k] = props.mass;
    centroid[k] = props.centroid;
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = first_free; k < model.pieces.size(); ++k) {
    const auto& upper = model.pieces[k].soup;
    const auto& lower = model.pieces[k - 1].soup;
    const double z = min_z(upper);
    if (std::abs(max_z(lower) - z) > 1e-9) {
      throw std::invalid_argument("static_toppling: " + model.pieces[k].name + " does not rest on the top of " +
                                  model.pieces[k - 1].name);
    }
    const auto contact = geometry::clip(face_polygon(upper, z, 1e-9), face_polygon(lower, z, 1e-9));
    double m = 0;
    Vec3 c = Vec3::Zero();
    for (std::size_t j = k; j < model.pieces.size(); ++j) {
      m += mass[j];
      c += mass[j] * centroid[j];
    }
    c /= m;
    const double h = c.z() - z;
    const P2 cxy(c.x(), c.y());
    double s = 0;
    if (contact.size() >= 3) {
      s = azimuth < 0 ? geometry::distance_to_boundary(contact, cxy)
                      : geometry::ray_to_boundary(contact, cxy, -P2(std::cos(azimuth), std::sin(azimuth)));
    }
    best = std::min(best, s / h);
  }
  return best;
}

}  // namespace rigid::library
