// The JSON writers of io (io/json.hpp, on nlohmann-json): checked by parsing what they write,
// never by comparing text.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rigid/contact/contact.hpp"
#include "rigid/core/types.hpp"
#include "rigid/dynamics/world.hpp"
#include "rigid/io/json.hpp"
#include "rigid/library/builders.hpp"
#include "rigid/motion/ground_motion.hpp"
#include "rigid/motion/measures.hpp"

namespace rigid::io {
namespace {

std::vector<double> cosine(double amplitude, double phase, std::size_t n, double dt) {
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = amplitude * std::cos(2 * kPi * double(i) * dt + phase);
  return a;
}

TEST(JsonLine, OneCompactLineWithNullForNonFiniteNumbers) {
  Json j;
  j["a"] = 0.1;
  j["nan"] = std::nan("");
  j["inf"] = HUGE_VAL;
  j["none"] = json_or_null(std::nullopt);
  j["some"] = json_or_null(2.5);
  j["bad_utf8"] = std::string("x\xff");
  const std::string s = json_line(j);
  EXPECT_EQ(s.find('\n'), std::string::npos);
  const Json back = Json::parse(s);
  EXPECT_EQ(back["a"].get<double>(), 0.1);  // shortest form that reads back exactly
  EXPECT_TRUE(back["nan"].is_null());
  EXPECT_TRUE(back["inf"].is_null());
  EXPECT_TRUE(back["none"].is_null());
  EXPECT_EQ(back["some"].get<double>(), 2.5);
  EXPECT_EQ(back["bad_utf8"].get<std::string>(), "x\xef\xbf\xbd");  // U+FFFD
  std::vector<std::string> keys;
  for (const auto& [k, v] : back.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"a", "nan", "inf", "none", "some", "bad_utf8"}));
}

TEST(MotionInfoJson, HasTheIssueKeys) {
  const double dt = 5e-4;
  const std::size_t n = 20001;
  const auto m =
      motion::make_ground_motion("p", {{cosine(1.0, 0.0, n, dt), dt, "1"}, {cosine(0.5, 0.3, n, dt), dt, "2"}});
  const std::string line = motion_info_json(motion::motion_info(m, {}, {1.0}));
  EXPECT_EQ(line.find('\n'), std::string::npos);
  const Json j = Json::parse(line);
  for (const char* key : {"npts", "dt_s", "duration_s", "gmrotd50_pga_g", "gmrotd50_pgv_cm_s", "gmroti50_pga_g",
                          "gmroti50_pgv_cm_s", "rotd50_pga_g", "pgv_pga_s", "sa"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["npts"].get<std::size_t>(), n);
  ASSERT_EQ(j["components"].size(), 2u);
  EXPECT_EQ(j["components"][0]["axis"], "x");
  EXPECT_NEAR(j["components"][0]["pga_g"].get<double>(), 1.0 / kGravity, 1e-12);
  for (const char* key : {"pgv_cm_s", "pgd_cm", "label"}) EXPECT_TRUE(j["components"][1].contains(key)) << key;
  ASSERT_EQ(j["sa"].size(), 1u);
  for (const char* key : {"period_s", "x_g", "y_g", "gmrotd50_g", "rotd50_g"})
    EXPECT_TRUE(j["sa"][0].contains(key)) << key;
  // one horizontal: no orientation-independent keys
  const auto one = motion::make_ground_motion("o", {{cosine(1.0, 0.0, n, dt), dt, "1"}});
  const Json j1 = Json::parse(motion_info_json(motion::motion_info(one)));
  EXPECT_FALSE(j1.contains("gmroti50_pga_g"));
  EXPECT_TRUE(j1.contains("pgv_pga_s"));
  EXPECT_FALSE(j1.contains("sa"));
}

TEST(PhysicsJson, KeysInOrderAndValuesReadBackExactly) {
  contact::ContactLaw law;
  law.friction = 0.7;
  scenario::Scene scene = library::block_on_pedestal(0.1, 0.5, 0.3, law);
  scenario::RunSettings run;
  run.step.dt = 1.0 / 3.0 * 1e-4;
  const int stop_after = 7;
  const std::string accuracy = "fast";
  const Json j = Json::parse(physics_json(scene, run, accuracy, stop_after));
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"contact",
                                            "restitution",
                                            "normal_stiffness",
                                            "shear_stiffness",
                                            "friction",
                                            "damping",
                                            "density",
                                            "failure_rule",
                                            "failure_tilt_deg",
                                            "step_s",
                                            "dt_s",
                                            "safety",
                                            "integrator",
                                            "duration_s",
                                            "free_time_s",
                                            "stop_after",
                                            "accuracy",
                                            "rest_speed_m_s",
                                            "rest_angular_speed_rad_s",
                                            "rest_time_s",
                                            "effects",
                                            "solver_tolerance",
                                            "solver_max_sweeps"}));
  EXPECT_EQ(j["friction"].get<double>(), 0.7);
  EXPECT_EQ(j["dt_s"].get<double>(), run.step.dt);
  EXPECT_EQ(j["step_s"].get<double>(), dynamics::time_step(scene.bodies, scene.law, run.step));
  EXPECT_EQ(j["density"].get<double>(), scene.density);
  EXPECT_EQ(j["failure_rule"], "below");
  EXPECT_EQ(j["failure_tilt_deg"].get<double>(), 0.0);
  EXPECT_EQ(j["stop_after"].get<int>(), stop_after);
  EXPECT_EQ(j["accuracy"], accuracy);
  EXPECT_EQ(j["effects"], "auto");
  EXPECT_EQ(j["solver_tolerance"].get<double>(), run.step.solver_tolerance);
  EXPECT_EQ(j["solver_max_sweeps"].get<int>(), run.step.solver_max_sweeps);
  EXPECT_EQ(j["contact"], contact::contact_method_name(law.method));
}

}  // namespace
}  // namespace rigid::io
