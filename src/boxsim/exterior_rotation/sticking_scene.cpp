#include "boxsim/exterior_rotation/sticking_scene.hpp"

#include <cmath>

#include "boxsim/core/world.hpp"

namespace boxsim {

namespace {

/// The initial tilt of every hinge, degrees clockwise: enough for the group to leave its
/// unstable balance at once, small enough that the motion starts near the flat configuration.
constexpr double kTiltDegrees = 3.0;

/// The table: an immovable box 0.5 × 0.4 × 0.5 m whose top face is y = 0 and whose right edge is
/// the line x = y = 0, standing on a ground at y = −0.4.
World tableWorld() {
  World world;
  world.addGround(-0.4, 5.0);
  RigidBody table = RigidBody::immovableBox(Vec3(0.25, 0.2, 0.25));
  table.s.x = Vec3(-0.25, -0.2, 0.0);
  table.updateDerived();
  world.add(table, "table");
  return world;
}

/// Body index of the table in tableWorld() (the ground is body 0).
constexpr int kTable = 1;

/// A scene on tableWorld() named `name`, drawing the thesis' figure `figure`; the rest is empty.
StickingScene tableScene(const char* name, const char* figure) {
  StickingScene scene;
  scene.name = name;
  scene.figure = figure;
  scene.world = tableWorld();
  return scene;
}

/// The rotation by `degrees` about +z.
Quat aboutZ(double degrees) { return axisAngleDegrees(Vec3::UnitZ(), degrees); }

/// Turns body k rigidly by `degrees` about the z-parallel line through `pivot`.
void turnAbout(World& world, int k, const Vec3& pivot, double degrees) {
  RigidBody& body = world.bodies[k];
  const Quat turn = aboutZ(degrees);
  body.s.x = pivot + turn * (body.s.x - pivot);
  body.s.q = (turn * body.s.q).normalized();
  body.updateDerived();
}

/// The point p (world, m) in body k's frame.
Vec3 toBody(const World& world, int k, const Vec3& p) {
  const RigidBody& body = world.bodies[k];
  return body.R.transpose() * (p - body.s.x);
}

/// Adds one contact of bodies a and b whose points are the world points `corners` (m) of the
/// current configuration; the normal is the unit axis `normalLocal` of body normalBody.
void addContact(StickingScene& scene, const std::string& name, int a, int b,
                const std::vector<Vec3>& corners, int normalBody, const Vec3& normalLocal) {
  const int contact = static_cast<int>(scene.contacts.size());
  scene.contacts.push_back({name, a, b});
  for (const Vec3& p : corners)
    scene.points.push_back({a, b, toBody(scene.world, a, p), toBody(scene.world, b, p), normalBody,
                            normalLocal, contact});
}

/// The four corners (world) of body k's face on the side `sign` (±1) of its axis `axis`.
std::vector<Vec3> faceCorners(const World& world, int k, int axis, double sign) {
  const RigidBody& body = world.bodies[k];
  const int u = (axis + 1) % 3;
  const int w = (axis + 2) % 3;
  std::vector<Vec3> corners;
  for (const double su : {-1.0, 1.0}) {
    for (const double sw : {-1.0, 1.0}) {
      Vec3 local = Vec3::Zero();
      local[axis] = sign * body.halfExtents[axis];
      local[u] = su * body.halfExtents[u];
      local[w] = sw * body.halfExtents[w];
      corners.push_back(body.s.x + body.R * local);
    }
  }
  return corners;
}

/// The two end points (world) of the z-parallel line through `p` across body k's depth.
std::vector<Vec3> edgeEnds(const World& world, int k, const Vec3& p) {
  const double hz = world.bodies[k].halfExtents.z();
  return {Vec3(p.x(), p.y(), -hz), Vec3(p.x(), p.y(), hz)};
}

constexpr double kCubeHalf = 0.1;  // m: the small cubes are 0.2 m on a side

}  // namespace

StickingScene pivotingBox(const PivotingBoxSpec& spec) {
  StickingScene scene = tableScene("pivoting_box", "6.2");
  const int box = addBox(scene.world, "box", spec.halfExtents, Vec3(spec.overhang, spec.halfExtents.y(), 0.0));
  const Vec3 pivot = Vec3::Zero();
  turnAbout(scene.world, box, pivot, -spec.tiltDegrees);
  // The table's edge lies across the box's bottom face: the face carries the normal.
  addContact(scene, "pivot", kTable, box, edgeEnds(scene.world, box, pivot), box, Vec3::UnitY());
  scene.links = {HingeLink{{box}, pivot}};
  scene.pivots = {0};
  scene.topBody = box;
  scene.window = spec.window;
  return scene;
}

StickingScene pivotingGroup() {
  StickingScene scene = tableScene("pivoting_group", "6.1");
  const Vec3 half = Vec3::Constant(kCubeHalf);
  const double left = 0.05 - kCubeHalf;   // x of the left column's centres
  const double right = 0.05 + kCubeHalf;  // x of the right column's centres
  const int bl = addBox(scene.world, "BL", half, Vec3(left, kCubeHalf, 0.0));
  const int br = addBox(scene.world, "BR", half, Vec3(right, kCubeHalf, 0.0));
  const int tl = addBox(scene.world, "TL", half, Vec3(left, 3.0 * kCubeHalf, 0.0));
  const int tr = addBox(scene.world, "TR", half, Vec3(right, 3.0 * kCubeHalf, 0.0));
  const Vec3 pivot = Vec3::Zero();
  for (const int k : {bl, br, tl, tr}) turnAbout(scene.world, k, pivot, -kTiltDegrees);
  const World& w = scene.world;
  addContact(scene, "pivot", kTable, bl, edgeEnds(w, bl, pivot), bl, Vec3::UnitY());
  // Face contacts: the four corners of the pushed box's touching face, normal of the pusher.
  addContact(scene, "BL-BR", bl, br, faceCorners(w, br, 0, -1.0), bl, Vec3::UnitX());
  addContact(scene, "BL-TL", bl, tl, faceCorners(w, tl, 1, -1.0), bl, Vec3::UnitY());
  addContact(scene, "BR-TR", br, tr, faceCorners(w, tr, 1, -1.0), br, Vec3::UnitY());
  addContact(scene, "TL-TR", tl, tr, faceCorners(w, tr, 0, -1.0), tl, Vec3::UnitX());
  scene.links = {HingeLink{{bl, br, tl, tr}, pivot}};
  scene.pivots = {0};
  scene.topBody = tr;
  scene.window = 1.0 / 3.0;
  return scene;
}

StickingScene twoFrames(const TwoFramesSpec& spec) {
  StickingScene scene = tableScene("two_frames", "6.3");
  const Vec3 halfA = Vec3::Constant(kCubeHalf);
  const int a = addBox(scene.world, "A", halfA, Vec3(spec.overhangA, halfA.y(), 0.0));
  RigidBody bodyB = RigidBody::box(spec.halfExtentsB, spec.massB);
  Vec3 hinge2(spec.overhangA + halfA.x(), 2.0 * halfA.y(), 0.0);  // A's top right edge, untilted
  bodyB.s.x = hinge2 + Vec3(spec.overhangB, spec.halfExtentsB.y(), 0.0);
  bodyB.updateDerived();
  const int b = scene.world.add(bodyB, "B");
  const Vec3 pivot = Vec3::Zero();
  turnAbout(scene.world, b, hinge2, -spec.tiltDegreesB);
  for (const int k : {a, b}) turnAbout(scene.world, k, pivot, -spec.tiltDegreesA);
  hinge2 = aboutZ(-spec.tiltDegreesA) * hinge2;
  addContact(scene, "pivot", kTable, a, edgeEnds(scene.world, a, pivot), a, Vec3::UnitY());
  addContact(scene, "hinge", a, b, edgeEnds(scene.world, b, hinge2), b, Vec3::UnitY());
  scene.links = {HingeLink{{a}, pivot}, HingeLink{{b}, hinge2}};
  scene.pivots = {0, 1};
  scene.topBody = b;
  scene.window = spec.window;
  return scene;
}

std::vector<StickingScene> allStickingScenes() { return {pivotingGroup(), pivotingBox(), twoFrames()}; }

}  // namespace boxsim
