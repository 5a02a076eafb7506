// No allocation in the step after the first: this test program counts every call of the
// global operator new (replaced below, for this program only) while scenes step on. The
// first step may allocate (buffers sized on first use); after it, only a probe's time series
// may grow, by the amortised doubling of its vector, and such growth is subtracted. The
// scenes re-sort their particles every few steps, so the sort's buffers are covered too.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <new>

#include "test_support.hpp"

namespace {
std::atomic<long> g_allocations{0};

void* counted_allocation(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}

void* counted_aligned_allocation(std::size_t n, std::align_val_t a) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t align = static_cast<std::size_t>(a);
  if (void* p = std::aligned_alloc(align, (n + align - 1) / align * align)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return counted_allocation(n); }
void* operator new[](std::size_t n) { return counted_allocation(n); }
void* operator new(std::size_t n, std::align_val_t a) { return counted_aligned_allocation(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return counted_aligned_allocation(n, a); }
// The nothrow forms too (Catch2 registers its tests with them): every form must come from
// the same malloc, or AddressSanitizer reports a new/free mismatch (scripts/test --sanitize).
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t& tag) noexcept { return operator new(n, tag); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

using namespace bsmpm;

namespace {

struct Count {
  long steps = 0, allocations = 0, probe_growths = 0;
};

// Allocations in `steps` steps after the first, less the growth of probe series.
Count allocations_after_first_step(const std::string& scene_name, const std::vector<std::string>& overrides,
                                   long steps) {
  const SceneDescription scene = load_scene(test::scene_path(scene_name), overrides);
  auto sim = build_simulation(scene);
  const GridInfo g = sim->grid_info();
  const double h_min = std::min(g.cell_size.x(), g.cell_size.y());
  auto dt = [&] { return time_step(scene.time, sim->max_signal_speed(), h_min); };
  sim->advance(dt());
  Count c;
  std::vector<std::size_t> capacity(sim->probes().size());
  for (long k = 0; k < steps; ++k) {
    for (std::size_t i = 0; i < capacity.size(); ++i) capacity[i] = sim->probes()[i]->data().capacity();
    const double step_dt = dt();
    const long before = g_allocations.load();
    sim->advance(step_dt);
    const long made = g_allocations.load() - before;
    long grown = 0;
    for (std::size_t i = 0; i < capacity.size(); ++i) grown += sim->probes()[i]->data().capacity() != capacity[i];
    c.allocations += made - grown;
    c.probe_growths += grown;
    ++c.steps;
  }
  return c;
}

}  // namespace

TEST_CASE("A fluid scene allocates nothing in its steps after the first", "[allocation]") {
  // Volume smoothing, viscosity, wall pressure probes; a sort every 7 steps.
  const Count c = allocations_after_first_step("lobovsky_h300.toml", {"grid.cell_size=0.02", "solver.sort_interval=7"}, 40);
  INFO("probe growths " << c.probe_growths);
  CHECK(c.allocations == 0);
}

TEST_CASE("A contact scene allocates nothing in its steps after the first", "[allocation]") {
  // Contact between water and an elastic gate, clamped control points, four probes.
  const Count c = allocations_after_first_step("elastic_gate.toml", {"grid.cell_size=0.004", "solver.sort_interval=7"}, 40);
  INFO("probe growths " << c.probe_growths);
  CHECK(c.allocations == 0);
}
