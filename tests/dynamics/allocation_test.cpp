// The time step's inner loop must not allocate: a counting global operator new watches a rocking
// block, the same block as a compound of two convex pieces (the merged friction patches) and a geode
// impact after the contact buffers have grown.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "rigid/geometry/polyhedron.hpp"
#include "rigid/library/builders.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
// GCC 12 calls free() here "mismatched" once it inlines the test's std::string allocations into
// this replacement pair; both sides are malloc/free by construction
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace rigid {
namespace {

scenario::Scene rocking_block(contact::ContactMethod model, bool compound) {
  contact::ContactLaw law;
  law.method = model;
  if (!compound) return library::block_on_pedestal(0.1, 0.5, 0.5, law);
  // a 0.5 x 0.5 x 1.0 block (stockier: it rocks on its pedestal without toppling off it) as two
  // glued halves, each resting on the pedestal
  auto scene = library::block_on_pedestal(0.25, 0.5, 0.5, law);
  const Vec3 lo(-0.25, -0.25, 0), hi(0.25, 0.25, 1.0);
  geometry::MeshOptions convex;
  convex.require_convex = true;
  std::vector<geometry::ClosedMesh> pieces;
  pieces.push_back(geometry::make_closed_mesh(geometry::box_soup(lo, Vec3(0.0, hi.y(), hi.z())), convex, "half"));
  pieces.push_back(geometry::make_closed_mesh(geometry::box_soup(Vec3(0.0, lo.y(), lo.z()), hi), convex, "half"));
  auto body =
      geometry::build_compound(geometry::make_closed_mesh(geometry::box_soup(lo, hi), {}, "block"), pieces, 2600, {});
  auto& block = scene.bodies[1];
  const Vec3 lift = block.position - body.shape.translation;  // keep the builder's placement
  block.shape = std::move(body.shape);
  block.pieces = std::move(body.pieces);
  block.position = block.shape.translation + lift;
  block.orientation = block.shape.rotation;
  return scene;
}

class StepAllocation : public ::testing::TestWithParam<std::tuple<contact::ContactMethod, bool>> {};

TEST_P(StepAllocation, SteppingARockingBlockAllocatesNothing) {
  const auto scene = rocking_block(std::get<0>(GetParam()), std::get<1>(GetParam()));
  const long at_start = g_allocations.load();
  dynamics::World world(scene.bodies, scene.law, dynamics::StepSettings{});
  ASSERT_GT(g_allocations.load(), at_start) << "the allocation counter is not live";
  const double dt = world.dt();
  // warm-up: contacts form and buffers reach their size
  for (int k = 0; k < 2000; ++k) world.step(dt, Vec3::Zero(), Vec3::Zero());
  const long before = g_allocations.load();
  for (int k = 0; k < 20000; ++k) {
    const double t = k * dt;
    const Vec3 v(0.3 * std::sin(12.0 * t), 0.2 * std::cos(9.0 * t), 0.05 * std::sin(20.0 * t));
    world.step(dt, v, v);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(world.stats().contact_steps, 20000) << "the block must stay on its pedestal";
}

INSTANTIATE_TEST_SUITE_P(BothModels, StepAllocation,
                         ::testing::Combine(::testing::Values(contact::ContactMethod::penalty,
                                                              contact::ContactMethod::rigid),
                                            ::testing::Bool()),
                         [](const auto& info) {
                           return std::string(contact::contact_method_name(std::get<0>(info.param))) +
                                  (std::get<1>(info.param) ? "_compound" : "");
                         });

}  // namespace
}  // namespace rigid
