#include "rigid/job/variants.hpp"

namespace rigid::job {

std::vector<JobObject> expand_variants(const std::vector<io::JobFileObject>& objects,
                                       const scenario::VariantSpace& variants) {
  std::vector<JobObject> out;
  const auto plain = [](const io::JobFileObject& o) {
    JobObject j;
    j.name = o.name;
    j.scene = o.scene;
    j.state = o.state;
    return j;
  };
  for (std::size_t o = 0; o < objects.size(); ++o) {
    if (variants.count() == 0) {
      out.push_back(plain(objects[o]));
      continue;
    }
    for (int v = 0; v < variants.count(); ++v) {
      JobObject e = plain(objects[o]);
      e.base = int(o);
      e.variant = v;
      e.variant_scene = scenario::variant_scene(variants, v);
      out.push_back(std::move(e));
    }
  }
  return out;
}

}  // namespace rigid::job
