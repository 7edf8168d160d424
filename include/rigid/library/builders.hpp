#pragma once
/// Scenes built in code: boxes, rectangular blocks on pedestals, geodesic near-spheres. Used by
/// tests, benchmarks and the model generator, so that reference cases need no files.
#include <string>

#include "rigid/scenario/scene.hpp"

namespace rigid::library {

/// A block from a convex triangle soup placed where the soup's coordinates say.
dynamics::BodyDef body_from_soup(const std::string& name, const geometry::TriangleSoup& soup, double density,
                                 bool fixed);

/// An axis-aligned box [lo, hi] (unit: m).
dynamics::BodyDef box_body(const std::string& name, const Vec3& lo, const Vec3& hi, double density, bool fixed);

/// A rectangular block of width 2b (x), depth `depth` (y) and height 2h (z) standing on a fixed
/// pedestal whose top is z = 0, centred on the origin. The pedestal has the block's footprint
/// enlarged by `pedestal_margin` on every side and is `pedestal_height` tall, so a block that
/// topples falls off it (the study's validation set-up, physics.md §11).
scenario::Scene block_on_pedestal(double b, double h, double depth, const contact::ContactLaw& law = {},
                                  double density = 2600, double pedestal_margin = 0.02, double pedestal_height = 0.2);

/// The ground drive of a one-sine acceleration pulse along x, a(t) = A sin(2 pi t / T) for
/// 0 <= t <= T (unit: m/s^2, s): velocity A T / (2 pi) (1 - cos(2 pi t / T)) sampled every dt,
/// constant afterwards (Zhang & Makris 2001, physics.md §2).
scenario::GroundDrive one_sine_drive(double amplitude, double period, double dt = 1e-3);

/// The box [lo, hi] with each face cut into n x n squares of two triangles (12 n^2 triangles,
/// vertices inside its faces and edges): the same solid as box_soup, meshed finely, for checking
/// that answers do not depend on the tessellation.
geometry::TriangleSoup subdivided_box_soup(const Vec3& lo, const Vec3& hi, int n);

/// Convex hull of the vertices of an icosahedron subdivided `frequency` times, projected on the
/// sphere of `radius` (unit: m): a faceted near-sphere (the study's geode test).
geometry::TriangleSoup geodesic_sphere(double radius, int frequency);

}  // namespace rigid::library
