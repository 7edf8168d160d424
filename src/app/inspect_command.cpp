// `rigid inspect`: what Rigid made of a scene's meshes (mass properties and checks).
#include <cmath>
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/scene_file.hpp"
#include "scene_input.hpp"

namespace rigid::app {
namespace {

io::Json vec_json(const Vec3& v) { return io::Json::array({v.x(), v.y(), v.z()}); }

// + 0.0 turns -0 into 0, which prints as 0
double degrees(double rad) { return rad * 180.0 / kPi + 0.0; }

// A coordinate to the tenth of a millimetre, what a scan resolves: the 1e-17 m of a centroid that
// is 0 up to rounding prints as 0.0000
double to_tenth_mm(double m) { return std::round(m * 1e4) / 1e4 + 0.0; }

// The contact law the scene runs, with that law's parameters only: rigid contact has no springs.
io::Json contact_json(const scenario::Scene& scene) {
  const auto& law = scene.law;
  io::Json j;
  j["method"] = contact::contact_method_name(law.method);
  j["friction"] = law.friction;
  if (law.method == contact::ContactMethod::rigid) {
    j["restitution"] = law.restitution;
  } else {
    j["normal_stiffness_n_m1_5"] = law.normal_stiffness;
    j["shear_stiffness_n_m"] = law.shear_stiffness;
    j["damping_s_m"] = law.damping;
  }
  return j;
}

void print_contact(const scenario::Scene& scene) {
  const auto& law = scene.law;
  if (law.method == contact::ContactMethod::rigid) {
    std::printf("contact: rigid (non-penetrating, Moreau-Jean): friction %.3g, restitution %.3g", law.friction,
                law.restitution);
  } else {
    std::printf("contact: penalty (Hertz springs): K_N %.3g N/m^1.5, K_S %.3g N/m, friction %.3g, damping %.3g s/m",
                law.normal_stiffness, law.shear_stiffness, law.friction, law.damping);
  }
  std::printf("; density %.4g kg/m^3\n", scene.density);
}

// The rocking parameters as they are printed in JSON: angles in rad, directions also in degrees.
io::Json rocking_json(const analysis::RockingParameters& r) {
  io::Json j;
  j["alpha_rad"] = r.alpha;
  j["static_toppling_g"] = analysis::static_toppling_g(r);
  j["radius_m"] = r.radius;
  j["p_rad_s"] = r.p;
  j["weakest_azimuth_deg"] = degrees(r.azimuth);
  io::Json azimuths = io::Json::array(), alphas = io::Json::array(), polygon = io::Json::array();
  for (std::size_t k = 0; k < r.alpha_by_azimuth.size(); ++k) {
    azimuths.push_back(360.0 * double(k) / double(r.alpha_by_azimuth.size()));
    alphas.push_back(r.alpha_by_azimuth[k]);
  }
  for (const auto& corner : r.support_polygon) polygon.push_back(io::Json::array({corner.x(), corner.y()}));
  j["azimuths_deg"] = azimuths;
  j["alpha_by_azimuth_rad"] = alphas;
  j["support_polygon_m"] = polygon;
  return j;
}

void print_rocking(const analysis::RockingParameters& r) {
  std::printf("rocking: alpha %.4g rad (static toppling %.4g g) towards azimuth %.1f deg, R %.4g m, p %.4g rad/s\n",
              r.alpha, analysis::static_toppling_g(r), degrees(r.azimuth), r.radius, r.p);
  std::printf("  support polygon: %zu corners; alpha by azimuth of the ground acceleration (deg: rad):",
              r.support_polygon.size());
  for (std::size_t k = 0; k < r.alpha_by_azimuth.size(); ++k) {
    std::printf("%s %.1f: %.4g", k % 4 == 0 ? "\n   " : ",", 360.0 * double(k) / double(r.alpha_by_azimuth.size()),
                r.alpha_by_azimuth[k]);
  }
  std::printf("\n");
}

void inspect(const std::string& path, bool json) {
  // loading runs every mesh check (closed, oriented, convex); a failure throws before this point
  const scenario::Scene scene = load_scene_with_warnings(path);
  const auto rocking = analysis::rocking_parameters(scene);
  for (const auto& b : scene.bodies) {
    const auto& s = b.shape;
    const Vec3 centroid = scenario::centroid_position(b);
    const bool offset = b.centre_of_mass_offset.squaredNorm() > 0;
    if (json) {
      io::Json j;
      j["block"] = b.name;
      j["fixed"] = b.fixed;
      j["vertices"] = long(s.vertices.size());
      j["faces"] = long(s.faces.size());
      j["volume_m3"] = s.volume;
      j["mass_kg"] = s.mass;
      j["centroid_m"] = vec_json(centroid);
      j["centre_of_mass_m"] = vec_json(b.position);
      j["principal_moments_kg_m2"] = vec_json(s.inertia);
      j["bounding_radius_m"] = s.bounding_radius;
      if (b.pieces.empty()) {
        j["checks"] = io::Json::array({"closed", "oriented", "convex", "finite"});
      } else {
        // a compound body: the mesh gives the mass properties, its convex pieces the contact
        double contact_volume = 0;
        long contact_vertices = 0;
        for (const auto& piece : b.pieces) {
          contact_volume += piece.volume;
          contact_vertices += long(piece.vertices.size());
        }
        j["contact_pieces"] = long(b.pieces.size());
        j["contact_volume_m3"] = contact_volume;
        j["contact_vertices"] = contact_vertices;
        j["checks"] = io::Json::array({"closed", "oriented", "manifold", "finite", "pieces convex"});
      }
      // a single free block resting on its pedestals: its rocking parameters (physics.md §2)
      if (!b.fixed && rocking) j["rocking"] = rocking_json(*rocking);
      j["contact"] = contact_json(scene);
      std::printf("%s\n", io::json_line(j).c_str());
    } else {
      std::printf("%s (%s): %zu vertices, %zu faces\n", b.name.c_str(), b.fixed ? "fixed" : "free", s.vertices.size(),
                  s.faces.size());
      std::printf("  volume %.4g m^3, mass %.4g kg\n", s.volume, s.mass);
      std::printf("  centroid (%.4f, %.4f, %.4f) m\n", to_tenth_mm(centroid.x()), to_tenth_mm(centroid.y()),
                  to_tenth_mm(centroid.z()));
      if (offset) {
        std::printf("  centre of mass (%.4f, %.4f, %.4f) m ([centre_of_mass_offset])\n", to_tenth_mm(b.position.x()),
                    to_tenth_mm(b.position.y()), to_tenth_mm(b.position.z()));
      }
      std::printf("  principal moments %.4g %.4g %.4g kg m^2\n", s.inertia.x(), s.inertia.y(), s.inertia.z());
      if (b.pieces.empty()) {
        std::printf("  checks passed: closed, consistently oriented, convex, finite\n");
      } else {
        double contact_volume = 0;
        for (const auto& piece : b.pieces) contact_volume += piece.volume;
        std::printf(
            "  compound body: contact shape of %zu convex pieces, %.4g m^3 (the mesh: %.4g m^3); the outline "
            "above is their hull\n",
            b.pieces.size(), contact_volume, s.volume);
        std::printf("  checks passed: mesh closed, consistently oriented, manifold, finite; every piece convex\n");
      }
    }
  }
  if (!json) {
    if (rocking) print_rocking(*rocking);
    print_contact(scene);
  }
}

}  // namespace

void register_inspect_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "inspect", "Check a scene's meshes and print each block's volume, mass, centroid and principal moments");
  cmd->add_option("scene", *path, "Scene: a Rigid model file or a .toml scene file")->required();
  cmd->add_flag("--json", *json,
                "One JSON object per block, one per line, at full precision; `contact`: the law the scene runs "
                "with that law's parameters");
  cmd->callback([path, json] { inspect(*path, *json); });
}

}  // namespace rigid::app
