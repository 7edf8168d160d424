// Variant expansion: every [[object]] in every variant, object-major, each knowing its base
// object and variant index.
#include <gtest/gtest.h>

#include "rigid/job/variants.hpp"

namespace rigid::job {
namespace {

std::vector<io::JobFileObject> two_objects() { return {{"a", "/s/a.toml", ""}, {"b", "/s/b.toml", "/s/b_state.toml"}}; }

TEST(ExpandVariants, WithoutVariantsTheObjectsAsTheyAre) {
  const std::vector<JobObject> out = expand_variants(two_objects(), scenario::VariantSpace{});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1].name, "b");
  EXPECT_EQ(out[1].state, "/s/b_state.toml");
  EXPECT_EQ(out[1].base, -1);
  EXPECT_EQ(out[1].variant, -1);
  EXPECT_EQ(out[1].label(), "b");
}

TEST(ExpandVariants, ObjectMajor) {
  scenario::VariantSpace space;
  space.keys = {scenario::VariantKey::friction};
  for (double f : {0.4, 0.6, 0.8}) {
    scenario::VariantValue v;
    v.number = f;
    space.variants.push_back({v});
  }
  ASSERT_EQ(space.count(), 3);
  const std::vector<io::JobFileObject> in = two_objects();
  const std::vector<JobObject> out = expand_variants(in, space);
  ASSERT_EQ(out.size(), in.size() * 3);
  std::size_t i = 0;
  for (std::size_t o = 0; o < in.size(); ++o) {
    for (int v = 0; v < 3; ++v, ++i) {
      EXPECT_EQ(out[i].name, in[o].name);
      EXPECT_EQ(out[i].scene, in[o].scene);
      EXPECT_EQ(out[i].base, int(o));
      EXPECT_EQ(out[i].variant, v);
      EXPECT_EQ(out[i].variant_scene, "");  // friction is no alternative scene
      EXPECT_EQ(out[i].label(), in[o].name + " [v" + std::to_string(v) + "]");
    }
  }
}

TEST(ExpandVariants, AnAlternativeSceneIsWhatIsSimulated) {
  scenario::VariantSpace space;
  space.keys = {scenario::VariantKey::scene};
  for (const char* file : {"/s/scan1.toml", "/s/scan2.toml"}) {
    scenario::VariantValue v;
    v.text = file;
    space.variants.push_back({v});
  }
  const std::vector<JobObject> out = expand_variants({{"a", "/s/a.toml", ""}}, space);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].simulated_scene(), "/s/scan1.toml");
  EXPECT_EQ(out[1].simulated_scene(), "/s/scan2.toml");
  EXPECT_EQ(out[1].scene, "/s/a.toml");
}

}  // namespace
}  // namespace rigid::job
