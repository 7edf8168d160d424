#include "rigid/library/builders.hpp"

#include <array>
#include <cmath>
#include <map>

namespace rigid::library {

// scenes, drives and the run are scenario's; this module builds on them
using namespace scenario;

dynamics::BodyDef body_from_soup(const std::string& name, const geometry::TriangleSoup& soup, double density,
                                 bool fixed) {
  dynamics::BodyDef body;
  body.name = name;
  body.shape = geometry::build_block(soup, density, geometry::MeshOptions{}, name);
  body.fixed = fixed;
  body.position = body.shape.translation;
  body.orientation = body.shape.rotation;
  return body;
}

dynamics::BodyDef box_body(const std::string& name, const Vec3& lo, const Vec3& hi, double density, bool fixed) {
  return body_from_soup(name, geometry::box_soup(lo, hi), density, fixed);
}

Scene block_on_pedestal(double b, double h, double depth, const contact::ContactLaw& law, double density,
                        double pedestal_margin, double pedestal_height) {
  Scene s;
  s.law = law;
  s.density = density;
  s.source = "block_on_pedestal";
  const double m = pedestal_margin;
  s.bodies.push_back(box_body("pedestal", Vec3(-b - m, -0.5 * depth - m, -pedestal_height),
                              Vec3(b + m, 0.5 * depth + m, 0), density, true));
  s.bodies.push_back(box_body("block", Vec3(-b, -0.5 * depth, 0), Vec3(b, 0.5 * depth, 2 * h), density, false));
  return s;
}

GroundDrive one_sine_drive(double amplitude, double period, double dt) {
  GroundDrive drive;
  drive.dt = dt;
  const long n = std::lround(period / dt);
  for (long i = 0; i <= n; ++i) {
    const double t = double(i) * dt;
    drive.velocity.emplace_back(amplitude * period / (2 * kPi) * (1 - std::cos(2 * kPi * t / period)), 0, 0);
  }
  return drive;
}

geometry::TriangleSoup subdivided_box_soup(const Vec3& lo, const Vec3& hi, int n) {
  geometry::TriangleSoup soup;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      auto corner = [&](int i, int j) {
        Vec3 p;
        p[axis] = side ? hi[axis] : lo[axis];
        p[u] = lo[u] + (hi[u] - lo[u]) * i / n;
        p[v] = lo[v] + (hi[v] - lo[v]) * j / n;
        return p;
      };
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const Vec3 a = corner(i, j), b = corner(i + 1, j), c = corner(i + 1, j + 1), d = corner(i, j + 1);
          // u x v = +axis: counter-clockwise in (u, v) faces outward on the high side
          if (side) {
            soup.push_back({a, b, c});
            soup.push_back({a, c, d});
          } else {
            soup.push_back({a, c, b});
            soup.push_back({a, d, c});
          }
        }
      }
    }
  }
  return soup;
}

geometry::TriangleSoup geodesic_sphere(double radius, int frequency) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int level = 0; level < frequency; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      midpoint[key] = static_cast<int>(v.size()) - 1;
      return static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& tri : f) {
      const int ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  geometry::TriangleSoup soup;
  for (const auto& tri : f) soup.push_back({radius * v[tri[0]], radius * v[tri[1]], radius * v[tri[2]]});
  return soup;
}

}  // namespace rigid::library
