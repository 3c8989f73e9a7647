// Damped integration (Alg. A.2) allocates nothing in a step once its working lists have grown to
// the scene: every list a step fills is kept by the stepper from step to step and written over.
// This executable replaces the global operator new with one that counts while a test asks it
// to; nothing else in it allocates during the counted steps.
#include <catch2/catch.hpp>

#include <cstddef>
#include <cstdlib>
#include <new>
#include <string>

#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/io/scene.hpp"

namespace {
bool counting = false;  // single-threaded: the steps run on the test's thread
long allocations = 0;
}  // namespace

// Every form of the global operator new and delete is replaced, in matching pairs (malloc and
// free, aligned_alloc and free), so that no library's new meets another's delete (AddressSanitizer
// checks that they match).
namespace {
void* counted(std::size_t size, std::size_t alignment = 0) {
  if (counting) ++allocations;
  if (size == 0) size = 1;
  if (alignment > alignof(std::max_align_t))
    return std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
  return std::malloc(size);
}
}  // namespace

void* operator new(std::size_t size) {
  if (void* p = counted(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  if (void* p = counted(size)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return counted(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return counted(size); }
void* operator new(std::size_t size, std::align_val_t alignment) {
  if (void* p = counted(size, static_cast<std::size_t>(alignment))) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  if (void* p = counted(size, static_cast<std::size_t>(alignment))) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

using namespace boxsim;

namespace {
/// The allocations of `counted` steps of 1/60 s of the scene after `warm` uncounted ones.
long allocationsOfSteps(const std::string& scene, DampedIntegrationParams params, int warm,
                        int counted, double mu = 0.0) {
  Scene loaded = loadScene(std::string(BOXSIM_SOURCE_DIR) + "/chapters/impulse_damped/scenes/" +
                           scene + ".json");
  for (RigidBody& body : loaded.world.bodies) body.friction = Friction{mu, mu};
  DampedIntegrationStepper stepper(params);
  for (int i = 0; i < warm; ++i) stepper.step(loaded.world, 1.0 / 60.0);
  allocations = 0;
  counting = true;
  int awake = 0;
  for (int i = 0; i < counted; ++i) {
    const StepStats stats = stepper.step(loaded.world, 1.0 / 60.0);
    awake += static_cast<int>(loaded.world.bodies.size()) - 1 - stats.sleeping;
  }
  counting = false;
  // The steps counted did work: a world all asleep would allocate nothing trivially.
  CHECK(awake > 0);
  return allocations;
}
}  // namespace

TEST_CASE("A damped step allocates nothing once its lists have grown to the scene",
          "[impulse_damped][allocation]") {
  // Each scene is counted once its contacts have formed: a body's first contacts with a new
  // neighbour grow its lists (that is the warm-up), later steps reuse them.
  DampedIntegrationParams params;
  SECTION("the die bouncing to rest") { CHECK(allocationsOfSteps("die", params, 180, 60) == 0); }
  SECTION("the clump of Fig. 6.7 settling on the ground") {
    CHECK(allocationsOfSteps("clump100_ground", params, 300, 60) == 0);
  }
  // Sleeping off: every body stays awake and every stage of the step runs for it.
  params.sleep.enabled = false;
  SECTION("the tower, awake") { CHECK(allocationsOfSteps("tower10", params, 60, 60) == 0); }
  SECTION("the clump on the ground with Coulomb friction, awake") {
    // Boxes left on an edge or a corner tumble on until about 12 s (their friction holds no
    // load beyond their support: SupportVerdict::held), and the sweep's lists grow with the
    // ground the clump covers until then.
    CHECK(allocationsOfSteps("clump100_ground", params, 720, 60, 0.5) == 0);
  }
  SECTION("a pile of 343 cubes, awake") {
    CHECK(allocationsOfSteps("pile343", params, 300, 60) == 0);
  }
  SECTION("the base-10 pyramid after the shot, awake") {
    CHECK(allocationsOfSteps("pyramid10_shot", params, 420, 60) == 0);
  }
  SECTION("a pile of 343 cubes with impact passes and damping of supported bodies only, awake") {
    // Their trajectory differs from the default's: a box meets a last new neighbour later than
    // step 300 (either option alone: 2 or 3 allocations in steps 300-360), none after step 600.
    params.impactPasses = 20;
    params.damping.supportedOnly = true;
    CHECK(allocationsOfSteps("pile343", params, 600, 60) == 0);
  }
}
