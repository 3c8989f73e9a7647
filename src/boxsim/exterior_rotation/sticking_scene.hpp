/// \file
/// The scenes of the exterior rotation problem (\thesis{§6.2}, Figs. 6.1–6.3): boxes that stick
/// to each other and to a fixed table with infinite static friction, so that a group pivots as
/// one body about the table's edge, or (Fig. 6.3) a second body pivots about an edge of the
/// first. Every contact point is a bilateral point constraint between two material points.
///
/// All three scenes move in the x–y plane. The table (0.5 × 0.4 × 0.5 m, immovable, on a ground
/// at y = −0.4) has its top face at y = 0 and its right edge, the pivot, on the line x = y = 0
/// along z. Every box is symmetric about z = 0, so each edge contact acts as a hinge about a
/// line parallel to z. Tipping to the right is a clockwise turn, a negative angle about +z.
/// Before the initial tilt (o: a hinge line, seen end on):
///
/// ```
///   Fig. 6.2           Fig. 6.1              Fig. 6.3
///                      +----+----+
///                      | TL | TR |                  +--------+
///    +-------+         +----+----+            +-----+---o----+  B
///    |  box  |         | BL | BR |            |  A      |
/// ---+---o---+      ---+-o--+----+         ---+----o----+
///  table  pivot     table pivot            table   pivot;  o on A's top: the hinge
/// ```
#pragma once

#include <string>
#include <vector>

#include "boxsim/core/world.hpp"

namespace boxsim {

/// One sticking contact point: material point rA of body a coincides with material point rB of
/// body b (\thesis{§6.2}: infinite static friction). A bilateral constraint of three rows.
struct PointConstraint {
  int a = -1;  ///< body index (may be immovable, e.g. the table)
  int b = -1;  ///< body index, movable
  Vec3 rA = Vec3::Zero();  ///< the material point in a's body frame, m (from a's centre)
  Vec3 rB = Vec3::Zero();  ///< the material point in b's body frame, m (from b's centre)
  /// The body whose frame `normalLocal` is given in: the body whose face carries the contact
  /// (b for an edge of a on a face of b, a for face-on-face).
  int normalBody = -1;
  Vec3 normalLocal = Vec3::UnitY();  ///< unit contact normal from a into b, in normalBody's frame
  int contact = -1;  ///< index into StickingScene::contacts of the contact this point belongs to
};

/// A contact between two bodies: its points (four corners of a face, or the two end points of
/// an edge) share it, and its total force is what a contact model would see.
struct StickingContact {
  std::string name;  ///< e.g. "pivot", "BL-TL"
  int a = -1;        ///< the body pushing
  int b = -1;        ///< the body pushed (the force reported is the one on b)
};

/// One link of the reduced (hinge-angle) model of a scene: bodies that move as one rigid body
/// about a hinge parallel to z. The hinge of link 0 is fixed; the hinge of link k > 0 is a
/// material point of link k − 1. Every scene starts at rest.
struct HingeLink {
  std::vector<int> bodies;           ///< the bodies of the link (indices into the world)
  Vec3 hinge = Vec3::Zero();         ///< the hinge point at t = 0 (world, z = 0), m
};

/// A scene of \thesis{§6.2}: the world (table, ground and the sticking boxes), its contact
/// points, and its exact motion as a chain of hinged links (the reference).
struct StickingScene {
  std::string name;                       ///< "pivoting_box", "pivoting_group" or "two_frames"
  std::string figure;                     ///< the thesis figure: "6.1", "6.2" or "6.3"
  World world;                            ///< bodies and gravity; the table and ground immovable
  std::vector<PointConstraint> points;    ///< every sticking contact point
  std::vector<StickingContact> contacts;  ///< the contacts the points belong to
  std::vector<HingeLink> links;           ///< the reference chain, link 0 on the table's edge
  /// For each link, the index into `contacts` of the contact its hinge is (contacts[pivots[0]]
  /// is the table's edge); the normal force of each must stay compressive.
  std::vector<int> pivots;
  int topBody = -1;  ///< the body furthest from the pivot, whose path Fig. 6.1 follows
  /// The simulated window, s: a substantial rotation (30–60°) over which every pivot stays
  /// compressive, so the sticking assumption is physical (checked by the tests).
  double window = 0.0;
};

/// The box of \thesis{Fig. 6.2} and how it starts.
struct PivotingBoxSpec {
  Vec3 halfExtents = Vec3(0.1, 0.05, 0.1);  ///< m; the box has 1 kg
  double overhang = 0.01;  ///< x of the box's centre beyond the table's edge before the tilt, m
  double tiltDegrees = 3.0;  ///< initial clockwise turn about the edge, degrees
  /// StickingScene::window, s: 39° of rotation; the pivot's normal force falls to 42% of its
  /// initial value and sticking needs μ = 1.0 at the end.
  double window = 7.0 / 30.0;
};

/// \thesis{Fig. 6.2}: a box ("box", 1 kg) on the table's edge with its centre beyond it,
/// turned clockwise about the edge and at rest, so it tips over the edge about its bottom
/// face's contact line, not about its own centre. One link.
StickingScene pivotingBox(const PivotingBoxSpec& spec = {});

/// \thesis{Fig. 6.1}: four cubes of 0.2 m and 1 kg stuck in a 2 × 2 block ("BL", "BR", "TL",
/// "TR", bottom/top, left/right), the block's centre 0.05 m beyond the table's edge, only BL
/// resting on the table; turned 3° clockwise about the edge, at rest. The block pivots as one
/// body; "TR" is the top box. One link; window 1/3 s (35°; the pivot's normal force falls to
/// 28% of its initial value and sticking needs μ = 0.90 at the end).
StickingScene pivotingGroup();

/// The two boxes of \thesis{Fig. 6.3} and how they start.
struct TwoFramesSpec {
  double overhangA = 0.0;  ///< x of cube A's centre beyond the table's edge before the tilt, m
  Vec3 halfExtentsB = Vec3(0.1, 0.02, 0.1);  ///< m: a plank 0.2 × 0.04 × 0.2 m
  double massB = 0.5;                        ///< kg
  double overhangB = 0.02;  ///< B's centre beyond A's top right edge (along A's top), m
  double tiltDegreesA = 3.0;   ///< A's (and with it B's) clockwise turn about the table's edge
  double tiltDegreesB = 10.0;  ///< B's further clockwise turn about A's top right edge
  /// StickingScene::window, s: A turns 16° and B 46°; the hinge's normal force falls to 29% of
  /// its initial value and sticking needs μ = 0.91 there at the end.
  double window = 0.2;
};

/// \thesis{Fig. 6.3}: two rotating frames in one group. A cube "A" of 0.2 m and 1 kg pivots on
/// the table's edge, and a box "B" lying on A's top, beyond A's top right edge and turned
/// further about it, pivots about that edge: a planar double hinge. Two links.
StickingScene twoFrames(const TwoFramesSpec& spec = {});

/// The three scenes in the order of the thesis' figures: 6.1, 6.2, 6.3.
std::vector<StickingScene> allStickingScenes();

}  // namespace boxsim
