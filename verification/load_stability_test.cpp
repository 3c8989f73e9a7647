// Verification of stability under load (load_stability.hpp, beyond the thesis: §6.3.1, Figs.
// 6.4 and 6.5): hand-derived thresholds, the rule of known loads, and a brute-force check of the
// verdicts against the accelerations of the full frictionless contact LCP on random stacks.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "boxsim/analytic_lcp/analytic_stepper.hpp"
#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"
#include "boxsim/geometric_stability/load_stability.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "seeded_random.hpp"
#include "test_worlds.hpp"

using namespace boxsim;
using boxsim::testing::groundWorld;

namespace {

constexpr double kMargin = 1e-6;  // m, as the §5.4 tests: touching boxes get a manifold
constexpr double kDt = 1.0 / 60.0;

/// The flags under load, and what the call examined.
struct Verdict {
  std::vector<char> flags;
  LoadStabilityReport report;
};

Verdict classify(const World& world, double cornerTolerance = GeometricStabilityParams{}.cornerTolerance) {
  GeometricStabilityParams params;
  params.cornerTolerance = cornerTolerance;
  const std::vector<ContactManifold> contacts = findContacts(world, kMargin);
  Verdict v{setGeometricallyStable(world, contacts, params), {}};
  v.report = addStableUnderLoad(world, contacts, params, v.flags);
  return v;
}

/// Names of the bodies with the given flag.
std::set<std::string> named(const World& world, const std::vector<char>& flags, char flag) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < flags.size(); ++i)
    if (flags[i] == flag) names.insert(world.names[i]);
  return names;
}

/// Largest linear (m/s²) or angular (rad/s²) acceleration among `bodies` under the full
/// frictionless LCP (no body left out), drift correction off.
double largestAcceleration(const World& world, const std::vector<int>& bodies) {
  AnalyticParams params;
  params.driftCorrection = false;
  const std::vector<Vec3> a = AnalyticStepper(params).contactAccelerations(world, kDt);
  double largest = 0.0;
  for (int i : bodies) largest = std::max({largest, a[2 * i].norm(), a[2 * i + 1].norm()});
  return largest;
}

World heavyBridge(double topMass, double armMass = 1.0) {
  World world = groundWorld();
  addFig6_5HeavyBridge(world, topMass, armMass);
  return world;
}

/// Fig. 6.5 with the given top, and Fig. 6.4's staircase 5 m beside it (along z).
World bridgeAndStaircase(double topMass) {
  World world = heavyBridge(topMass);
  World staircase;
  addFig6_4Staircase(staircase);
  for (std::size_t k = 0; k < staircase.bodies.size(); ++k) {
    RigidBody b = staircase.bodies[k];
    b.s.x.z() += 5.0;
    b.updateDerived();
    world.add(b, staircase.names[k]);
  }
  return world;
}

/// A unit cube of 1 kg turned 20° about z with its lowest edge on the plane y = planeY, its
/// centre over (x, z) = (0, z): resting on an edge, it topples.
RigidBody tiltedCube(double planeY, double z) {
  RigidBody tilted = RigidBody::box(Vec3::Constant(0.5), 1.0);
  const double angle = 20.0 * kPi / 180.0;
  tilted.s.q = Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
  tilted.s.x = Vec3(0.0, planeY + 0.5 * (std::cos(angle) + std::sin(angle)), z);
  tilted.updateDerived();
  return tilted;
}

}  // namespace

TEST_CASE("Fig. 6.4: a staircase of overhanging blocks is stable as one heavier object",
          "[geometric_stability][under_load]") {
  World world = groundWorld();
  addFig6_4Staircase(world);
  const Verdict v = classify(world);
  // §5.4's rule: only the bottom block (each upper one overhangs its support).
  CHECK(named(world, v.flags, kGeometricallyStable) == std::set<std::string>{"ground", "block0"});
  // Under load: the three upper blocks, one component, one program of 3 × 3 equations.
  CHECK(named(world, v.flags, kStableUnderLoad) ==
        std::set<std::string>{"block1", "block2", "block3"});
  CHECK(v.report.components == 1);
  CHECK(v.report.largestRows == 9);
  // The top two taken together have their centre at x = (0.45 + x3) / 2 over block1's support
  // [−0.05, 0.65]: past it for x3 > 0.85, and then no block of the component holds.
  World broken = groundWorld();
  addFig6_4Staircase(broken, 0.9);
  const Verdict b = classify(broken);
  CHECK(named(broken, b.flags, kStableUnderLoad).empty());
  CHECK(b.report.components == 1);
  CHECK(b.report.stableComponents == 0);
  // Brute force: the full LCP holds the first staircase and not the second.
  CHECK(largestAcceleration(world, {2, 3, 4}) < 1e-4);
  CHECK(largestAcceleration(broken, {2, 3, 4}) > 0.1);
}

TEST_CASE("Fig. 6.5: the heavy top holds its two tipping supports, above twice an arm's mass",
          "[geometric_stability][under_load]") {
  // Hand-derived (addFig6_5HeavyBridge): about an arm's pedestal edge, its own weight turns it
  // outward with arm mass × 0.5 m, the top's half weight inward with topMass/2 × 0.5 m at most:
  // stable for topMass >= 2 armMass, up to the margin of 0.5 mm.
  for (const double armMass : {1.0, 2.5}) {
    INFO("arm mass " << armMass << " kg");
    const std::set<std::string> held{"arm_left", "arm_right", "top"};
    const World heavy = heavyBridge(2.0 * armMass * 1.02, armMass);
    const World light = heavyBridge(2.0 * armMass * 0.98, armMass);
    CHECK(named(heavy, classify(heavy).flags, kStableUnderLoad) == held);
    CHECK(named(light, classify(light).flags, kStableUnderLoad).empty());
    // §5.4's rule marks the pedestals only: each arm overhangs.
    CHECK(named(heavy, classify(heavy).flags, kGeometricallyStable) ==
          std::set<std::string>{"ground", "pedestal_left", "pedestal_right"});
    // Brute force: the full LCP holds the heavy one; in the light one the arms tip.
    CHECK(largestAcceleration(heavy, {3, 4, 5}) < 1e-4);
    CHECK(largestAcceleration(light, {3, 4, 5}) > 0.01);
  }
  // Without one pedestal its arm has nothing under it: nothing holds.
  World oneSided = heavyBridge(10.0);
  oneSided.bodies.erase(oneSided.bodies.begin() + 1);
  oneSided.names.erase(oneSided.names.begin() + 1);
  CHECK(named(oneSided, classify(oneSided).flags, kStableUnderLoad).empty());
}

TEST_CASE("Only boxes whose loads are all known are judged under load",
          "[geometric_stability][under_load]") {
  World world = heavyBridge(4.0);
  REQUIRE(classify(world).report.bodiesAdded == 3);
  SECTION("a cube tilted onto the top brings an unknown load: none is judged") {
    world.add(tiltedCube(2.5, 0.0), "tilted");
    const Verdict v = classify(world);
    CHECK(named(world, v.flags, kStableUnderLoad).empty());
    CHECK(v.report.components == 0);
  }
  SECTION("a cube touching an arm from the side rules the arm, and so its component, out") {
    addBox(world, "side", Vec3::Constant(0.25), Vec3(3.25, 1.25, 0.0));
    CHECK(named(world, classify(world).flags, kStableUnderLoad).empty());
  }
  SECTION("a level cube resting on the top joins the component, and its weight helps") {
    addBox(world, "load", Vec3::Constant(0.5), Vec3(0.0, 3.0, 0.0));
    const Verdict v = classify(world);
    CHECK(named(world, v.flags, kStableUnderLoad) ==
          std::set<std::string>{"arm_left", "arm_right", "top", "load"});
    CHECK(v.report.largestRows == 12);
  }
  SECTION("a cube falling above, not touching, changes nothing") {
    addBox(world, "falling", Vec3::Constant(0.5), Vec3(0.0, 4.0, 0.0));
    CHECK(classify(world).report.bodiesAdded == 3);
  }
}

TEST_CASE("Stability under load agrees with the full LCP on random stacks",
          "[geometric_stability][under_load][brute_force]") {
  // Random staircases (2 to 5 cubes of 0.3-3 kg on a base cube, each shifted up to 0.85 m in x
  // and z from the one under it) and random Fig. 6.5 bridges (top 0.2-6 kg, arms 0.5-2 kg). A
  // verdict is checked against the accelerations of the full frictionless LCP, the brute-force
  // answer: a stable component has none (the LCP's ε is 1e-5), an unstable one has some body
  // accelerating. Cases within the margin (the verdict changes with it) are left out.
  testing::SeededRandom random(20261123);
  int stable = 0, unstable = 0, marginal = 0;
  for (int trial = 0; trial < 300; ++trial) {
    World world = groundWorld();
    std::vector<int> chain;
    if (trial % 3 == 2) {
      addFig6_5HeavyBridge(world, random.uniform(0.2, 6.0), random.uniform(0.5, 2.0));
      chain = {3, 4, 5};
    } else {
      addBox(world, "base", Vec3::Constant(0.5), Vec3(0.0, 0.5, 0.0));
      Vec3 at(0.0, 0.5, 0.0);
      const int count = random.integer(2, 5);
      for (int k = 0; k < count; ++k) {
        at += Vec3(random.uniform(-0.85, 0.85), 1.0, random.uniform(-0.85, 0.85));
        RigidBody cube = RigidBody::box(Vec3::Constant(0.5), random.uniform(0.3, 3.0));
        cube.s.x = at;
        cube.updateDerived();
        chain.push_back(world.add(cube, "cube" + std::to_string(k)));
      }
    }
    const Verdict v = classify(world);
    const Verdict exact = classify(world, 0.0);
    // The whole chain is one component with every load known, or some cube is stable by §5.4
    // (a cube wholly on the one below) and splits it; then the verdicts are per component.
    bool anyStable = false, allStable = true;
    for (int i : chain) {
      anyStable = anyStable || v.flags[i] != kUnstable;
      allStable = allStable && v.flags[i] != kUnstable;
    }
    if (v.flags != exact.flags) {
      ++marginal;
      continue;
    }
    const double a = largestAcceleration(world, chain);
    INFO("trial " << trial << ": largest acceleration " << a << ", stable " << allStable);
    if (allStable) {
      ++stable;
      CHECK(a < 1e-4);
    } else {
      ++unstable;
      CHECK(a > 1e-4);
    }
    // Whatever the split, a body marked stable is held by the full LCP.
    if (anyStable && !allStable) {
      std::vector<int> held;
      for (int i : chain)
        if (v.flags[i] != kUnstable) held.push_back(i);
      CHECK(largestAcceleration(world, held) < 1e-4);
    }
  }
  INFO(stable << " stable, " << unstable << " unstable, " << marginal << " within the margin");
  // Both verdicts are exercised, and few cases fall within the 0.5 mm margin.
  CHECK(stable >= 30);
  CHECK(unstable >= 30);
  CHECK(marginal <= 3);
}

TEST_CASE("The analytic method with stability under load accelerates every body as the full LCP",
          "[geometric_stability][under_load][analytic]") {
  // Fig. 6.5 held by its heavy top, Fig. 6.4's staircase beside it, and a cube tilted 20° onto
  // an edge on the ground beside them, toppling (a non-zero acceleration).
  World world = bridgeAndStaircase(4.0);
  world.add(tiltedCube(0.0, -5.0), "tilted");

  AnalyticParams full;
  full.driftCorrection = false;
  AnalyticParams thesis = full, underLoad = full;
  thesis.useGeometricStability = underLoad.useGeometricStability = true;
  underLoad.geometricStability.underLoad = true;
  const AnalyticStepper fullStepper(full), thesisStepper(thesis), loadStepper(underLoad);
  const std::vector<Vec3> a = fullStepper.contactAccelerations(world, kDt);
  const std::vector<Vec3> b = loadStepper.contactAccelerations(world, kDt);
  thesisStepper.contactAccelerations(world, kDt);
  INFO("LCP size: full " << fullStepper.lastLcpSize() << ", thesis " << thesisStepper.lastLcpSize()
                         << ", under load " << loadStepper.lastLcpSize());
  // Every held box leaves the system: only the tilted cube's contact with the ground stays.
  CHECK(loadStepper.lastLcpSize() < thesisStepper.lastLcpSize());
  CHECK(loadStepper.lastLcpSize() <= 4);
  double differs = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    differs = std::max(differs, (a[i] - b[i]).norm());
    largest = std::max(largest, a[i].norm());
  }
  INFO("largest acceleration " << largest << ", largest difference " << differs);
  CHECK(largest > 1.0);    // the tilted cube topples: not a comparison of zeros
  CHECK(differs < 1e-4);   // ε = 1e-5 on either side, and rounding
}

TEST_CASE("Simulated, the heavy bridge stands and the light one falls",
          "[geometric_stability][under_load][analytic]") {
  // The physics the verdicts predict, run for 1 s by the analytic method with nothing left out.
  const auto largestDisplacement = [](double topMass) {
    World world = heavyBridge(topMass);
    const World start = world;
    AnalyticStepper stepper;
    for (int k = 0; k < 60; ++k) stepper.step(world, kDt);
    double largest = 0.0;
    for (std::size_t i = 0; i < world.bodies.size(); ++i)
      largest = std::max(largest, (world.bodies[i].s.x - start.bodies[i].s.x).norm());
    return largest;
  };
  CHECK(largestDisplacement(4.0) < 1e-3);   // m: held
  CHECK(largestDisplacement(1.0) > 0.05);   // m: the arms tip and the top drops
}

TEST_CASE("Stability under load does not depend on the order of bodies or contacts",
          "[geometric_stability][under_load]") {
  const World world = bridgeAndStaircase(3.0);
  const std::vector<char> flags = classify(world).flags;
  std::vector<int> order(world.bodies.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  testing::SeededRandom(7).shuffle(order);
  World shuffled;
  for (int j : order) shuffled.add(world.bodies[j], world.names[j]);
  std::vector<ContactManifold> contacts = findContacts(shuffled, kMargin);
  std::reverse(contacts.begin(), contacts.end());
  GeometricStabilityParams params;
  params.underLoad = true;
  const std::vector<char> shuffledFlags = setGeometricallyStable(shuffled, contacts, params);
  for (std::size_t j = 0; j < order.size(); ++j)
    CHECK(shuffledFlags[j] == flags[order[j]]);
  CHECK(std::count(flags.begin(), flags.end(), kStableUnderLoad) == 6);
}

TEST_CASE("The mode names of --geometric-stability read back, and others are refused",
          "[geometric_stability][under_load][cli]") {
  for (const GeometricStabilityMode mode : {GeometricStabilityMode::Off, GeometricStabilityMode::Thesis,
                                            GeometricStabilityMode::UnderLoad})
    CHECK(parseGeometricStabilityMode(geometricStabilityModeName(mode)) == mode);
  CHECK_THROWS_WITH(parseGeometricStabilityMode("load"), Catch::Contains("under_load"));
  std::vector<char> tooFew(1, 0);
  CHECK_THROWS_AS(addStableUnderLoad(heavyBridge(3.0), {}, {}, tooFew), std::invalid_argument);
}
