// The rock library's models: the study's rectangular blocks, the geode, and nine synthetic
// analogues of its Yucca Mountain objects, each piece a convex hull of a shaped, seeded cloud.
#include "rigid/library/rock_library.hpp"

#include <cmath>
#include <cstdio>

#include "rigid/library/builders.hpp"
#include "rock_shapes.hpp"

namespace rigid::library {

// scenes, drives and the run are scenario's; this module builds on them
using namespace scenario;
namespace {

using geometry::TriangleSoup;
using namespace shapes;

// The models

constexpr double kMargin = 0.03;  // pedestal top beyond the rock's base outline (m)

LibraryModel rectangular_block(double alpha, const std::string& name) {
  // the study's validation blocks (physics.md §11), as `rigid model block` and block_on_pedestal
  const double h = 0.5, b = h * std::tan(alpha), depth = 0.5, m = 0.02;
  LibraryModel model;
  model.name = name;
  char text[160];
  std::snprintf(text, sizeof text,
                "Rectangular block 1 m tall, alpha %.1f rad (width %.4f m), 0.5 m deep, on a pedestal "
                "0.02 m wider on every side (the study's validation set, physics.md 11)",
                alpha, 2 * b);
  model.description = text;
  model.pieces.push_back(
      {"pedestal", geometry::box_soup(Vec3(-b - m, -0.5 * depth - m, -0.2), Vec3(b + m, 0.5 * depth + m, 0)), true});
  model.pieces.push_back({"block", geometry::box_soup(Vec3(-b, -0.5 * depth, 0), Vec3(b, 0.5 * depth, 1.0)), false});
  model.failure_note = "below: a toppled block falls off the pedestal";
  model.simple_stack = true;
  return model;
}

LibraryModel geode() {
  LibraryModel model;
  model.name = "geode";
  model.description =
      "Geode: 320-facet geodesic near-sphere, radius 0.15 m, resting on a facet on a 2 m x 2 m plane "
      "(the study's speed test object, physics.md 11)";
  TriangleSoup g = geodesic_sphere(0.15, 2);
  // turn the facet that faces most downwards to face straight down, so it rests on it
  Vec3 down_normal(0, 0, 1);
  for (const auto& t : g) {
    const Vec3 n = (t.b - t.a).cross(t.c - t.a).normalized();
    if (n.z() < down_normal.z()) down_normal = n;
  }
  g = rotated(g, Quat::FromTwoVectors(down_normal, -Vec3::UnitZ()).toRotationMatrix());
  // rounding leaves the three bottom vertices ~1e-17 m apart in z: snap them onto z = 0 exactly
  const double bottom = min_z(g);
  for (auto& t : g) {
    for (Vec3* v : {&t.a, &t.b, &t.c}) {
      v->z() = std::abs(v->z() - bottom) < 1e-12 ? 0.0 : v->z() - bottom;
    }
  }
  model.pieces.push_back({"plane", geometry::box_soup(Vec3(-1, -1, -0.2), Vec3(1, 1, 0)), true});
  model.pieces.push_back({"geode", g, false});
  model.failure_note = "below: once it rolls it rolls off the plane";
  model.simple_stack = true;
  return model;
}

// A single PBR on a pedestal: a flattened, top-heavy boulder (wider at the top, cut flat at a
// narrow base). `height` sizes the smooth shape (the jittered hull comes out within a few per cent
// of it); `cut` is the fraction of the vertical semi-axis below the centre where the base is cut:
// the deeper the cut, the narrower the base and the more fragile the rock.
LibraryModel single_rock(const std::string& name, double height, double cut, double lean, double yaw,
                         std::uint64_t seed) {
  LibraryModel model;
  model.name = name;
  RockSpec rock;
  rock.semi = Vec3(0.46 * height, 0.33 * height, 0);
  rock.exponent = 2.2;
  rock.taper = 0.25;
  rock.lean_x = lean;
  rock.lean_y = 0.5 * lean;
  rock.yaw = yaw;
  rock.seed = seed;
  rock.points = 64;
  fit_on(rock, 0.0, height, cut);
  const TriangleSoup r = shaped_rock(rock);
  char text[200];
  std::snprintf(text, sizeof text,
                "Single rock %.2f m tall: flattened top-heavy boulder on a narrow flat base, on a rock "
                "pedestal (analogue of the study's single Yucca Mountain rocks, 0.5-0.9 m)",
                max_z(r));
  model.description = text;
  const TriangleSoup pedestal = support_under(vertices_on(r, {0, 0, 0}), {0, 0, 0}, kMargin, 0.3, 0.8, seed + 1000);
  model.pieces.push_back({"pedestal", pedestal, true});
  model.pieces.push_back({"rock", r, false});
  model.failure_note = "below: a toppled rock falls off its pedestal";
  model.simple_stack = true;
  return model;
}

LibraryModel two_piece_rock() {
  LibraryModel model;
  model.name = "two_piece_rock";
  model.description =
      "Two-piece rock, 1.2 m: a boulder split along a flat horizontal joint, both pieces on a rock "
      "pedestal (analogue of the study's two-piece Yucca Mountain rock)";
  RockSpec lower;
  lower.semi = Vec3(0.42, 0.34, 0);
  lower.center.head<2>() = Eigen::Vector2d(0, 0);
  lower.exponent = 2.3;
  lower.taper = 0.15;
  lower.lean_x = 0.04;
  lower.seed = 201;
  fit_between(lower, 0.0, 0.62, 0.78, 0.55);
  const TriangleSoup lo = shaped_rock(lower);
  RockSpec upper;
  upper.semi = Vec3(0.34, 0.27, 0);
  upper.center.head<2>() = Eigen::Vector2d(0.03, -0.02);
  upper.exponent = 2.1;
  upper.taper = 0.1;
  upper.lean_y = 0.05;
  upper.yaw = 0.6;
  upper.seed = 202;
  upper.seats.push_back(seat_on(lo));
  fit_on(upper, max_z(lo), 0.58, 0.6);
  const TriangleSoup up = shaped_rock(upper);
  model.pieces.push_back(
      {"pedestal", support_under(vertices_on(lo, {0, 0, 0}), {0, 0, 0}, kMargin, 0.3, 0.8, 203), true});
  model.pieces.push_back({"lower", lo, false});
  model.pieces.push_back({"upper", up, false});
  model.failure_note = "below: a toppled piece falls off the pedestal";
  model.simple_stack = true;
  return model;
}

// Stacks against a wall or rock face are built upright in a local frame (base top z = 0, wall
// face x = 0, pieces on x <= 0 cut flat where they touch the wall) and then the whole model is
// leaned by `lean` towards the wall, so gravity presses the free pieces against it.
LibraryModel five_stack_wall() {
  LibraryModel model;
  model.name = "five_stack_wall";
  model.description =
      "Five-piece stack, 1.6 m, of flat slabs leaning 7 degrees against a rock wall (analogue of the "
      "study's five-piece stack against a wall)";
  const double lean = 0.12;
  std::vector<TriangleSoup> free;
  double z = 0;
  const double thickness[5] = {0.36, 0.34, 0.32, 0.31, 0.3};
  for (int i = 0; i < 5; ++i) {
    RockSpec s;
    s.semi = Vec3(0.36 - 0.015 * i, 0.32 - 0.01 * i, 0);
    s.center.head<2>() = Eigen::Vector2d(-0.24 + 0.01 * i, 0.02 * ((i % 2) ? 1 : -1));
    s.exponent = 2.6;
    s.yaw = 0.3 * i;
    s.jitter = 0.06;
    s.seed = 301 + std::uint64_t(i);
    s.points = 40;
    s.sides.push_back({1, 0, 0});  // x <= 0: flat against the wall
    if (i > 0) s.seats.push_back(seat_on(free.back()));
    if (i < 4) {
      fit_between(s, z, z + thickness[i], 0.7, 0.7);
    } else {
      fit_on(s, z, thickness[i], 0.7);
    }
    free.push_back(shaped_rock(s));
    z = max_z(free.back());
  }
  RockSpec wall;
  wall.center = Vec3(0.25, 0, 0.8);
  wall.semi = Vec3(0.32, 0.75, 1.3);
  wall.exponent = 4;
  wall.jitter = 0.03;
  wall.seed = 310;
  wall.sides.push_back({-1, 0, 0});  // x >= 0: the wall face
  RockSpec base;
  base.center = Vec3(-0.3, 0, -0.2);
  base.semi = Vec3(0.55, 0.6, 0.3);
  base.exponent = 4;
  base.jitter = 0.03;
  base.seed = 311;
  base.ceilings.push_back({0, 0, 0});  // runs on under the wall, so the corner is inside its top
  const Mat3 r = Eigen::AngleAxisd(lean, Vec3::UnitY()).toRotationMatrix();
  model.pieces.push_back({"base", rotated(shaped_rock(base), r), true});
  model.pieces.push_back({"wall", rotated(shaped_rock(wall), r), true});
  for (int i = 0; i < 5; ++i) {
    model.pieces.push_back({"slab" + std::to_string(i + 1), rotated(free[i], r), false});
  }
  model.failure = {FailureRule::Kind::tilt, 45.0 * kPi / 180.0};
  model.failure_note =
      "tilt 45 deg: pieces toppling away from the wall land on the base, so they "
      "never fall below the fixed blocks";
  return model;
}

LibraryModel block_against_face() {
  LibraryModel model;
  model.name = "block_against_face";
  model.description =
      "1 m blocky rock standing on a ledge and leaning 6 degrees against a rock face (analogue of the "
      "study's 1 m block against a rock face)";
  const double lean = 0.1;
  RockSpec s;
  s.semi = Vec3(0.3, 0.26, 0);
  s.center.head<2>() = Eigen::Vector2d(-0.2, 0);
  s.exponent = 3.2;
  s.taper = 0.08;
  s.yaw = 0.2;
  s.jitter = 0.04;
  s.seed = 401;
  s.points = 64;
  s.sides.push_back({1, 0, 0});
  fit_on(s, 0.0, 1.0, 0.85);
  RockSpec face;
  face.center = Vec3(0.25, 0, 0.5);
  face.semi = Vec3(0.32, 0.7, 1.0);
  face.exponent = 4;
  face.jitter = 0.03;
  face.seed = 402;
  face.sides.push_back({-1, 0, 0});
  RockSpec ledge;
  ledge.center = Vec3(-0.25, 0, -0.2);
  ledge.semi = Vec3(0.45, 0.5, 0.3);
  ledge.exponent = 4;
  ledge.jitter = 0.03;
  ledge.seed = 403;
  ledge.ceilings.push_back({0, 0, 0});  // runs on under the face, so the corner is inside its top
  const Mat3 r = Eigen::AngleAxisd(lean, Vec3::UnitY()).toRotationMatrix();
  model.pieces.push_back({"ledge", rotated(shaped_rock(ledge), r), true});
  model.pieces.push_back({"face", rotated(shaped_rock(face), r), true});
  model.pieces.push_back({"block", rotated(shaped_rock(s), r), false});
  model.failure = {FailureRule::Kind::tilt, 45.0 * kPi / 180.0};
  model.failure_note =
      "tilt 45 deg: leaning on the face, the block cannot fall below the ledge in "
      "most directions";
  return model;
}

LibraryModel four_stack_unstable_pedestal() {
  LibraryModel model;
  model.name = "four_stack_unstable_pedestal";
  model.description =
      "Four-rock stack, 1.6 m in all, on an unstable pedestal: the pedestal is itself a free rock "
      "on a narrow base, sitting on fixed bedrock (analogue of the study's four-rock stack)";
  RockSpec ped;
  ped.semi = Vec3(0.36, 0.3, 0);
  ped.exponent = 2.2;
  ped.taper = 0.2;
  ped.lean_x = 0.03;
  ped.seed = 501;
  ped.points = 56;
  fit_between(ped, 0.0, 0.42, 0.8, 0.5);
  std::vector<TriangleSoup> free{shaped_rock(ped)};
  const double thickness[4] = {0.34, 0.3, 0.28, 0.3};
  const double width[4] = {0.33, 0.3, 0.27, 0.25};
  for (int i = 0; i < 4; ++i) {
    RockSpec s;
    s.semi = Vec3(width[i], 0.82 * width[i], 0);
    s.center.head<2>() = Eigen::Vector2d(0.025 * ((i % 2) ? 1 : -1), 0.015 * i);
    s.exponent = 2.3;
    s.taper = 0.1;
    s.yaw = 0.5 + 0.7 * i;
    s.jitter = 0.06;
    s.seed = 502 + std::uint64_t(i);
    s.points = 48;
    s.seats.push_back(seat_on(free.back()));
    const double z = max_z(free.back());
    if (i < 3) {
      fit_between(s, z, z + thickness[i], 0.65, 0.6);
    } else {
      fit_on(s, z, thickness[i], 0.65);
    }
    free.push_back(shaped_rock(s));
  }
  model.pieces.push_back(
      {"bedrock", support_under(vertices_on(free[0], {0, 0, 0}), {0, 0, 0}, 0.1, 0.3, 0.8, 510), true});
  model.pieces.push_back({"pedestal", free[0], false});
  for (int i = 0; i < 4; ++i) model.pieces.push_back({"rock" + std::to_string(i + 1), free[i + 1], false});
  model.failure_note = "below: rocks that topple, and the pedestal if it goes, fall off the bedrock";
  model.simple_stack = true;
  return model;
}

LibraryModel three_stack_wedge() {
  LibraryModel model;
  model.name = "three_stack_wedge";
  model.description =
      "Three-rock stack, 1.3 m, on a pedestal sloping 14 degrees, its bottom rock held up on the "
      "downhill side by a small wedge (analogue of the study's three-rock stack with a wedge)";
  const double slope = std::tan(0.245);  // the pedestal top falls towards +x
  const HeightPlane pedestal_top{0, -slope, 0};
  const double crease = -0.15;                     // where the rock's base turns from slope to flat
  const double flat = pedestal_top.at(crease, 0);  // z of the flat part of the base = wedge top
  RockSpec bottom;
  bottom.semi = Vec3(0.4, 0.32, 0);
  bottom.center.head<2>() = Eigen::Vector2d(0.06, 0);
  bottom.exponent = 2.3;
  bottom.taper = 0.1;
  bottom.seed = 601;
  bottom.points = 56;
  fit_between(bottom, flat, 0.45, 0.6, 0.6);  // floor z = flat, ceiling 0.45
  bottom.floors.push_back(pedestal_top);      // uphill the base follows the slope
  const TriangleSoup b = shaped_rock(bottom);
  RockSpec wedge;
  wedge.center = Vec3(crease + 0.3, 0.0, flat - 0.06);
  wedge.semi = Vec3(0.28, 0.3, 0.14);
  wedge.exponent = 2.5;
  wedge.jitter = 0.04;
  wedge.seed = 602;
  wedge.points = 32;
  wedge.sides.push_back({-1, 0, -(crease + 0.05)});  // x >= crease + 5 cm: no knife edge
  wedge.floors.push_back(pedestal_top);
  wedge.ceilings.push_back({flat, 0, 0});
  wedge.seats.push_back({flat, face_polygon(b, flat, 1e-12), 0.02});  // under the rock's flat base
  const TriangleSoup w = shaped_rock(wedge);
  std::vector<TriangleSoup> free{b};
  const double thickness[2] = {0.4, 0.45};
  const double width[2] = {0.33, 0.27};
  for (int i = 0; i < 2; ++i) {
    RockSpec s;
    s.semi = Vec3(width[i], 0.8 * width[i], 0);
    s.center.head<2>() = Eigen::Vector2d(0.04 - 0.03 * i, 0.02);
    s.exponent = 2.2;
    s.taper = 0.15;
    s.yaw = 1.1 + 0.9 * i;
    s.seed = 603 + std::uint64_t(i);
    s.points = 48;
    s.seats.push_back(seat_on(free.back()));
    const double z = max_z(free.back());
    if (i == 0) {
      fit_between(s, z, z + thickness[i], 0.65, 0.6);
    } else {
      fit_on(s, z, thickness[i], 0.65);
    }
    free.push_back(shaped_rock(s));
  }
  std::vector<Vec3> top = vertices_on(b, pedestal_top);
  for (const auto& v : vertices_on(w, pedestal_top)) top.push_back(v);
  model.pieces.push_back({"pedestal", support_under(top, pedestal_top, kMargin, 0.35, 0.85, 610), true});
  model.pieces.push_back({"wedge", w, false});
  model.pieces.push_back({"rock1", free[0], false});
  model.pieces.push_back({"rock2", free[1], false});
  model.pieces.push_back({"rock3", free[2], false});
  model.failure_note = "below: rocks (or the wedge) that go fall off the sloping pedestal";
  return model;
}

}  // namespace

std::vector<LibraryModel> rock_library() {
  std::vector<LibraryModel> lib;
  lib.push_back(rectangular_block(0.1, "block_a01"));
  lib.push_back(rectangular_block(0.2, "block_a02"));
  lib.push_back(rectangular_block(0.3, "block_a03"));
  lib.push_back(rectangular_block(0.4, "block_a04"));
  lib.push_back(geode());
  lib.push_back(two_piece_rock());
  lib.push_back(five_stack_wall());
  lib.push_back(block_against_face());
  lib.push_back(four_stack_unstable_pedestal());
  lib.push_back(three_stack_wedge());
  lib.push_back(single_rock("single_rock_050", 0.50, 0.66, 0.03, 0.3, 901));
  lib.push_back(single_rock("single_rock_060", 0.60, 0.76, 0.03, 1.4, 902));
  lib.push_back(single_rock("single_rock_075", 0.765, 0.84, 0.03, 2.5, 903));
  lib.push_back(single_rock("single_rock_090", 0.915, 0.88, 0.03, 4.0, 904));
  return lib;
}

Scene library_scene(const LibraryModel& model, const contact::ContactLaw& law, double density) {
  Scene s;
  s.law = law;
  s.density = density;
  s.failure = model.failure;
  s.source = model.name;
  for (const auto& p : model.pieces) s.bodies.push_back(body_from_soup(p.name, p.soup, density, p.fixed));
  return s;
}

}  // namespace rigid::library
