/// \file
/// Contact manifolds of two boxes: face contacts by clipping the incident face against the
/// reference face (the oriented-rectangle intersection of \thesis{§3.2}), edge-edge contacts
/// by the closest points of the two edges.
#pragma once

#include <array>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/collision/separating_axis.hpp"

namespace boxsim {

/// Builds the contact manifold of boxes A and B from their separating-axis result.
/// \param a, b     the boxes
/// \param sat      separatingAxisTest(a, b)
/// \param margin   m, >= 0: points whose depth is greater than -margin are kept, so touching
///                 and nearly touching boxes also get a manifold
/// \return the manifold with normal from A to B and at most 4 points (a face clip makes up to
///         8, reduced to 4 keeping the deepest and the largest area); count == 0 when
///         sat.depth <= -margin. depth is the deepest point's depth, or sat.depth when there
///         is no point. Face contacts place each point midway between the reference face and
///         the incident face; an edge-edge contact has one point, midway between the closest
///         points of the two edges, with depth sat.depth. Feature ids encode the reference
///         and incident faces and the two clip lines through the point (face contact) or the
///         two edges (edge-edge); contact_manifold.cpp draws the numbering. The fields a and
///         b are left at -1 for the caller to fill.
/// \thesis{§3.2}; the clipping follows the reference/incident-face scheme of box2d-lite and
/// ODE's dBoxBox, written anew.
ContactManifold buildContactManifold(const Obb& a, const Obb& b, const SeparatingAxisResult& sat,
                                     double margin = 0.0);

/// Every point of the contact area of boxes A and B for the axis `sat` (\thesis{§3.2}): for a
/// face contact, each vertex of the incident face clipped to the reference face that lies
/// within `margin` (up to 8; buildContactManifold keeps 4 of them), with the same positions,
/// depths and feature ids; for an edge–edge contact, its one point; none when the boxes are
/// `margin` or more apart.
std::vector<ContactPoint> contactArea(const Obb& a, const Obb& b, const SeparatingAxisResult& sat,
                                      double margin = 0.0);

/// What a manifold is made of before the margin picks its points: the separating axis and,
/// for a face contact, every vertex of the incident face clipped to the reference face (up to
/// 8, in the clip polygon's order) with its depth, its position midway between the surfaces
/// and its feature id; for an edge-edge contact its one point. The clipping does not depend on
/// the margin, so one clip serves every margin a step asks for (KeptNarrowPhase: the resting
/// margin of FIXCONTACTCONSTRAINTS, the widened one of the once-per-step gathering).
struct ClippedContact {
  SeparatingAxisResult sat;             ///< the test the clip was made for
  int count = 0;                        ///< points; 0 to 8
  std::array<ContactPoint, 8> points{};  ///< the first `count`
  Vec3 referenceNormal = Vec3::Zero();  ///< unit, the reference face's outward normal (face)
  double tie = 0.0;                     ///< m, depths this close count as equal (reduction)
};

/// The clip of boxes A and B for `sat` = separatingAxisTest(a, b) (ClippedContact).
ClippedContact clipContact(const Obb& a, const Obb& b, const SeparatingAxisResult& sat);

/// The manifold of a clip for `margin` (m, >= 0): buildContactManifold(a, b, clip.sat, margin)
/// of the boxes the clip was made of, bit for bit (tested: collision_test.cpp, "[clip]").
ContactManifold manifoldWithin(const ClippedContact& clip, double margin);

/// separatingAxisTest followed by buildContactManifold: the narrow phase for one pair.
ContactManifold collideBoxes(const Obb& a, const Obb& b, double margin = 0.0,
                             const SeparatingAxisParams& params = {});

/// A manifold's points seen along its normal: 2D coordinates about a centre along the tangents
/// t1 = n.unitOrthogonal(), t2 = n × t1 (m), and the order of the points around the patch.
struct PatchOutline {
  std::array<Eigen::Vector2d, 4> points{};  ///< the first `count`, in the manifold's order
  std::array<int, 4> order{};               ///< indices of `points` in order around the patch
  int count = 0;                            ///< the manifold's point count, 0 to 4
};

/// The outline of m's points about `centre` (a point inside the patch: its centroid).
PatchOutline patchOutline(const ContactManifold& m, const Vec3& centre);

/// The mean distance from the centroid of a contact patch of uniform pressure, m: the radius
/// ρ at which a pressed patch resists spin about its normal (Coulomb torque up to μ N ρ). The
/// patch is the convex polygon of the manifold's points seen along its normal (3 or 4 points:
/// the mean of |r| over its area, exactly, from a fan of triangles about the centroid, each
/// integrated in closed form); 2 points are a line of contact (a quarter of its length); 0 or
/// 1 point, or an edge–edge manifold, give 0. A square of side s gives
/// s (√2 + ln(1 + √2)) / 6 ≈ 0.3826 s.
double contactPatchRadius(const ContactManifold& m);
/// contactPatchRadius(m) from m's outline about its centroid (`outline` =
/// patchOutline(m, m.centroid())), for a caller that has the outline already: the same
/// operations, so the same bits.
double contactPatchRadius(const ContactManifold& m, const PatchOutline& outline);

}  // namespace boxsim
