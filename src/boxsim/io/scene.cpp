#include "boxsim/io/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <set>
#include <sstream>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/core/math.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/io/scene_json.hpp"

namespace boxsim {

namespace {

using namespace scene_json;

/// Most bodies a scene may hold: a bound on memory and on the start-overlap check, far above
/// the thesis' largest scene (1000 cubes) and the 10 000-cube clump of the benchmarks.
constexpr int kMaxBodies = 20000;

Quat readOrientation(const Node& node) {
  node.requireObject(
      "an orientation {\"axis\": [x, y, z], \"angle_deg\": a} or {\"quaternion\": [w, x, y, z]}");
  node.allowKeys({"axis", "angle_deg", "quaternion"});
  if (node.has("quaternion")) {
    if (node.has("axis") || node.has("angle_deg"))
      node.fail("give either \"quaternion\" or \"axis\" with \"angle_deg\", not both",
                "remove one of them");
    return node.at("quaternion").quaternion();
  }
  if (!node.has("axis") || !node.has("angle_deg"))
    node.fail("an axis-angle orientation needs both \"axis\" and \"angle_deg\"",
              "add the missing key");
  const Vec3 axis = node.at("axis").nonZeroVec3("the rotation axis");
  const double angle = node.at("angle_deg").number();
  return axisAngleDegrees(axis, angle);
}

/// Largest friction coefficient a scene may give: far above real materials (rubber on
/// concrete is about 1), and where μ g Δt stays a small velocity change per step.
constexpr double kMaxFriction = 10.0;

/// A "friction" value: μ (static and dynamic alike) or {"static": μs, "dynamic": μd}, each in
/// [0, 10] with μd <= μs (Coulomb: sliding friction does not exceed sticking friction).
Friction readFriction(const Node& node) {
  const auto coefficient = [](const Node& n) {
    const double mu = n.number();
    if (mu < 0.0 || mu > kMaxFriction)
      n.fail("a friction coefficient must lie in [0, " + shortestText(kMaxFriction) + "] (got " +
                 shortestText(mu) + ")",
             "use e.g. 0.5 (wood on wood) or 0 for the thesis' frictionless contact");
    return mu;
  };
  if (!node.isObject()) {
    const double mu = coefficient(node);
    return {mu, mu};
  }
  node.requireObject("a friction coefficient or {\"static\": 0.6, \"dynamic\": 0.5}");
  node.allowKeys({"static", "dynamic"});
  if (!node.has("static") || !node.has("dynamic"))
    node.fail("give both \"static\" and \"dynamic\"", "write {\"static\": 0.6, \"dynamic\": 0.5}");
  const Friction f{coefficient(node.at("static")), coefficient(node.at("dynamic"))};
  if (f.muDynamic > f.muStatic)
    node.at("dynamic").fail("the dynamic coefficient exceeds the static one",
                            "make \"dynamic\" at most \"static\"");
  return f;
}

void readBody(const Node& node, Scene& scene, std::set<std::string>& names) {
  node.requireObject("a body");
  node.allowKeys({"name", "half_extents", "mass", "position", "orientation", "velocity",
                  "angular_velocity", "immovable", "launch_time", "friction"});
  if (!node.has("half_extents")) node.fail("missing \"half_extents\"", "add \"half_extents\": [0.5, 0.5, 0.5]");
  const Vec3 halfExtents = node.at("half_extents").positiveVec3(kSizeRange);
  const bool immovable = node.has("immovable") && node.at("immovable").boolean();
  RigidBody body;
  if (immovable) {
    if (node.has("mass")) node.at("mass").fail("an immovable body has no mass", "remove \"mass\"");
    body = RigidBody::immovableBox(halfExtents);
  } else {
    if (!node.has("mass"))
      node.fail("missing \"mass\"", "add \"mass\" in kg, or \"immovable\": true");
    body = RigidBody::box(halfExtents, node.at("mass").positive(kMassRange));
  }
  body.friction = node.has("friction") ? readFriction(node.at("friction")) : scene.friction;
  if (node.has("position")) body.s.x = node.at("position").vec3(kCoordinateRange);
  if (node.has("orientation")) body.s.q = readOrientation(node.at("orientation"));
  body.updateDerived();
  if (node.has("velocity") || node.has("angular_velocity")) {
    if (immovable) node.fail("an immovable body cannot move", "remove its velocities");
    if (node.has("velocity")) body.setVelocity(node.at("velocity").vec3(kSpeedRange));
    if (node.has("angular_velocity")) body.setAngularVelocity(node.at("angular_velocity").vec3(kAngularSpeedRange));
  }
  std::string name = "body_" + std::to_string(scene.world.bodies.size());
  if (node.has("name")) name = node.at("name").name();
  if (!names.insert(name).second)
    (node.has("name") ? node.at("name") : node)
        .fail("the name \"" + name + "\" is already taken", "give each body its own \"name\"");
  if (node.has("launch_time")) {
    if (immovable) node.at("launch_time").fail("an immovable body cannot be launched", "remove \"launch_time\"");
    scene.world.addLaunched(body, name, node.at("launch_time").nonNegative("s"));
  } else {
    scene.world.add(body, name);
  }
  scene.origins.push_back(node.path());
}

/// Fails at `key` when `adding` more bodies would take the scene's `before` past kMaxBodies.
void requireRoom(const Node& node, const char* key, int before, double adding) {
  if (before + adding > kMaxBodies)
    node.at(key).fail("the scene would hold " + std::to_string(static_cast<long long>(before + adding)) +
                          " bodies, more than the limit of " + std::to_string(kMaxBodies),
                      "build fewer boxes");
}

/// A builder's "size" (m) and "mass" (kg), each left at the spec's default when absent.
template <class Spec>
void readSizeAndMass(const Node& node, Spec& spec) {
  if (node.has("size")) spec.size = node.at("size").positive(kSizeRange);
  if (node.has("mass")) spec.mass = node.at("mass").positive(kMassRange);
}

/// A stacking builder's (tower, pyramid) "origin" (m) and "gap" (m, >= 0), defaults when absent.
template <class Spec>
void readOriginAndGap(const Node& node, Spec& spec) {
  if (node.has("origin")) spec.origin = node.at("origin").vec3(kCoordinateRange);
  if (node.has("gap")) spec.gap = node.at("gap").nonNegative("m", &kCoordinateRange);
}

/// The "die" builder (scene_builders.hpp, DieSpec).
void readDie(const Node& node, World& world) {
  node.allowKeys({"type", "size", "mass", "position", "tilt_deg", "tilt_axis", "velocity", "angular_velocity", "friction"});
  DieSpec spec;
  readSizeAndMass(node, spec);
  if (node.has("position")) spec.position = node.at("position").vec3(kCoordinateRange);
  if (node.has("tilt_deg")) spec.tiltDeg = node.at("tilt_deg").number();
  if (node.has("tilt_axis")) spec.tiltAxis = node.at("tilt_axis").nonZeroVec3("the tilt axis");
  if (node.has("velocity")) spec.velocity = node.at("velocity").vec3(kSpeedRange);
  if (node.has("angular_velocity")) spec.angularVelocity = node.at("angular_velocity").vec3(kAngularSpeedRange);
  addDie(world, spec);
}

/// The "tower" builder (TowerSpec), into a world of `before` bodies.
void readTower(const Node& node, World& world, int before) {
  node.allowKeys({"type", "count", "size", "mass", "origin", "gap", "friction"});
  TowerSpec spec;
  if (node.has("count")) spec.count = node.at("count").count();
  if (node.has("count")) requireRoom(node, "count", before, spec.count);
  readSizeAndMass(node, spec);
  readOriginAndGap(node, spec);
  addTower(world, spec);
}

/// The "pyramid" builder (PyramidSpec), into a world of `before` bodies.
void readPyramid(const Node& node, World& world, int before) {
  node.allowKeys({"type", "base", "size", "mass", "origin", "gap", "friction"});
  PyramidSpec spec;
  if (node.has("base")) spec.base = node.at("base").count();
  if (node.has("base")) requireRoom(node, "base", before, 0.5 * spec.base * (spec.base + 1.0));
  readSizeAndMass(node, spec);
  readOriginAndGap(node, spec);
  addPyramid(world, spec);
}

/// The "clump" builder (ClumpSpec), into a world of `before` bodies.
void readClump(const Node& node, World& world, int before) {
  node.allowKeys({"type", "count", "size", "mass", "spacing", "center", "target", "speed", "spin", "seed", "friction"});
  ClumpSpec spec;
  if (node.has("count")) spec.count = node.at("count").count();
  if (node.has("count")) requireRoom(node, "count", before, spec.count);
  readSizeAndMass(node, spec);
  if (node.has("spacing")) spec.spacing = node.at("spacing").positive(kSizeRange);
  if (node.has("center")) spec.center = node.at("center").vec3(kCoordinateRange);
  if (node.has("target")) spec.target = node.at("target").vec3(kCoordinateRange);
  if (node.has("speed")) spec.speed = node.at("speed").bounded(kSpeedRange);
  if (node.has("spin")) spec.spin = node.at("spin").nonNegative("rad/s", &kAngularSpeedRange);
  if (node.has("seed")) spec.seed = static_cast<unsigned long>(node.at("seed").count());
  // Without a "spacing" key the default spacing can still be too small for a large "size";
  // the error then names "size", the key that is there.
  if (!(spec.spacing > spec.size))
    (node.has("spacing") ? node.at("spacing") : node.at("size"))
        .fail("the spacing (2 m unless given) must exceed the cube size so the cubes start apart",
              "make \"spacing\" larger than \"size\"");
  addClump(world, spec);
}

void readBuilder(const Node& node, Scene& scene, std::set<std::string>& names) {
  node.requireObject("a builder");
  if (!node.has("type"))
    node.fail("missing \"type\"", "add \"type\": one of die, tower, pyramid, clump");
  const std::string type = node.at("type").string();
  const int before = static_cast<int>(scene.world.bodies.size());
  if (type == "die") {
    readDie(node, scene.world);
  } else if (type == "tower") {
    readTower(node, scene.world, before);
  } else if (type == "pyramid") {
    readPyramid(node, scene.world, before);
  } else if (type == "clump") {
    readClump(node, scene.world, before);
  } else {
    node.at("type").fail("unknown builder type \"" + type + "\"",
                         "use one of die, tower, pyramid, clump");
  }
  const Friction friction = node.has("friction") ? readFriction(node.at("friction")) : scene.friction;
  for (std::size_t i = before; i < scene.world.bodies.size(); ++i) {
    scene.world.bodies[i].friction = friction;
    // Builders name their boxes by role ("tower_3"); a second builder of the same kind gets
    // the body index appended so that every name stays unique.
    std::string& name = scene.world.names[i];
    if (!names.insert(name).second) {
      name += '_';  // not "_" + ...: GCC 12 -O3 warns falsely on that (-Wstringop-overflow)
      name += std::to_string(i);
      names.insert(name);
    }
    scene.origins.push_back(node.path() + " (" + type + " box " + std::to_string(i - before) + ")");
  }
}

void checkNoOverlap(const Scene& scene) {
  // Boxes may touch at the start (a stacked tower overlaps by rounding) but not overlap by
  // more than the techniques' own intersection threshold.
  const double tolerance = kIntersectionDepthTolerance;
  // A body waiting for its launch is immovable until then, and pairs of two immovable bodies
  // are never candidates; so check a copy with every body launched, or a body waiting inside
  // the ground or a wall would first collide when its launch starts inside it.
  World w = scene.world;
  w.applyLaunches(std::numeric_limits<double>::infinity());
  for (const auto& [i, j] : candidatePairs(w)) {
    const SeparatingAxisResult sat = separatingAxisTest(Obb::of(w.bodies[i]), Obb::of(w.bodies[j]));
    if (sat.depth > tolerance) {
      std::ostringstream os;
      os << scene.source << ": " << scene.origins[i] << " and " << scene.origins[j]
         << ": the boxes \"" << w.names[i] << "\" and \"" << w.names[j] << "\" overlap by "
         << sat.depth << " m at the start. Fix: move them apart (touching is allowed)";
      throw SceneError(os.str());
    }
  }
}

/// The scene-wide keys: description, gravity (m/s^2), restitution, friction, broad phase.
void readSettings(const Node& top, Scene& scene) {
  if (top.has("description")) scene.description = top.at("description").string();
  if (top.has("gravity")) scene.world.gravity = top.at("gravity").vec3(kGravityRange);
  if (top.has("restitution")) {
    const Node e = top.at("restitution");
    scene.world.restitution = e.number();
    if (scene.world.restitution < 0.0 || scene.world.restitution > 1.0)
      e.fail("restitution must lie in [0, 1]", "use 0.9 as the thesis (§3.3.2)");
  }
  if (top.has("friction")) scene.friction = readFriction(top.at("friction"));
  if (top.has("broad_phase")) {
    const Node b = top.at("broad_phase");
    const std::string name = b.string();
    const std::string valid = broadPhaseName(BroadPhase::AllPairs) + ", " +
                              broadPhaseName(BroadPhase::SweepAndPrune);
    try {
      scene.world.broadPhase = parseBroadPhase(name);
    } catch (const std::invalid_argument&) {
      b.fail("unknown broad phase \"" + name + "\"", "use one of: " + valid);
    }
  }
}

/// The "ground" object: height (m), half size (m), half thickness (m) and friction.
void readGround(const Node& g, Scene& scene, std::set<std::string>& names) {
  g.requireObject("the ground {\"height\": 0, \"half_size\": 50, \"half_thickness\": 0.5}");
  g.allowKeys({"height", "half_size", "half_thickness", "friction"});
  const double height = g.has("height") ? g.at("height").bounded(kCoordinateRange) : 0.0;
  const double halfSize = g.has("half_size") ? g.at("half_size").positive(kSizeRange) : 50.0;
  const double halfThickness = g.has("half_thickness") ? g.at("half_thickness").positive(kSizeRange) : 0.5;
  const int ground = scene.world.addGround(height, halfSize, halfThickness);
  scene.world.bodies[ground].friction = g.has("friction") ? readFriction(g.at("friction")) : scene.friction;
  scene.origins.push_back("/ground");
  names.insert(scene.world.names[ground]);
}

/// Calls read on each element of the array top/key, if there is one (key: "bodies" or
/// "builders"); fails when it is not an array. `source` names the scene file in messages.
template <class Read>
void forEachIn(const Node& top, const Json& root, const char* key, const std::string& source,
               Read read) {
  if (!top.has(key)) return;
  const Json& array = root.at(key);
  if (!array.is_array())
    top.at(key).fail("expected an array of " + std::string(key),
                     "write \"" + std::string(key) + "\": [ {...}, ... ]");
  const std::string prefix = top.at(key).path() + "/";
  for (std::size_t i = 0; i < array.size(); ++i)
    read(Node(array[i], prefix + std::to_string(i), source));
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& source) {
  const Json root = parseJson(text, source);
  Scene scene;
  scene.source = source;
  const Node top(root, "", scene.source);
  top.requireObject("a scene");
  top.allowKeys(
      {"description", "gravity", "restitution", "friction", "broad_phase", "ground", "bodies",
       "builders"});
  readSettings(top, scene);
  std::set<std::string> names;
  if (top.has("ground")) readGround(top.at("ground"), scene, names);
  forEachIn(top, root, "bodies", scene.source, [&](const Node& body) {
    if (static_cast<int>(scene.world.bodies.size()) >= kMaxBodies)
      body.fail("more than " + std::to_string(kMaxBodies) + " bodies", "use fewer bodies");
    readBody(body, scene, names);
  });
  forEachIn(top, root, "builders", scene.source,
            [&](const Node& builder) { readBuilder(builder, scene, names); });
  if (scene.world.movableCount() == 0)
    top.fail("the scene has no movable body", "add a body to \"bodies\" or a builder to \"builders\"");
  checkNoOverlap(scene);
  return scene;
}

Scene loadScene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file. Fix: check the path");
  std::ostringstream text;
  text << in.rdbuf();
  return parseScene(text.str(), path);
}

}  // namespace boxsim
