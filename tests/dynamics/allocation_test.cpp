// The time step's inner loop must not allocate: a counting global operator new watches a rocking
// block and a geode impact after the contact buffers have grown.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "rigid/scenario/builders.hpp"

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

class StepAllocation : public ::testing::TestWithParam<contact::ContactModel> {};

TEST_P(StepAllocation, SteppingARockingBlockAllocatesNothing) {
  contact::ContactLaw law;
  law.model = GetParam();
  const auto scene = scenario::block_on_pedestal(0.1, 0.5, 0.5, law);
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
}

INSTANTIATE_TEST_SUITE_P(BothModels, StepAllocation,
                         ::testing::Values(contact::ContactModel::penalty, contact::ContactModel::rigid),
                         [](const auto& info) { return std::string(contact::contact_model_name(info.param)); });

}  // namespace
}  // namespace rigid
