/// \file
/// Eberly's 15-axis separating-axis test for two oriented boxes (\thesis{§3.2}).
///
/// Two convex bodies are disjoint exactly when some axis separates their projections. For two
/// boxes 15 axes suffice: the 3 face normals of A, the 3 of B, and the 9 cross products of an
/// edge direction of A with one of B. Along an axis L the projected half widths are rA and rB
/// and the centres are |L . D| apart (D = centre of B - centre of A); the overlap, or depth, is
/// rA + rB - |L . D|. Eberly writes every rA, rB through C = A^T B (C_ij = a_i . b_j), so the
/// test needs no corner of either box.
///
/// Symmetry is designed in, not hoped for. Every depth is written so that the swapped call
/// (B, A) evaluates the same floating-point sums with the operands commuted, which IEEE
/// arithmetic rounds identically; ties are broken by geometry (face area, the unsigned axis),
/// never by which box came first. Hence the same depth bit for bit and the exact negated normal.
#include "boxsim/collision/separating_axis.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace boxsim {
namespace {

/// One tested axis.
struct AxisCandidate {
  double depth = 0.0;       ///< m, rA + rB - |L . D| with L a unit vector
  Vec3 normal = Vec3::Zero();  ///< unit, from A to B
  AxisKind kind = AxisKind::FaceA;
  int indexA = 0;
  int indexB = 0;
  double faceArea = 0.0;    ///< m^2, area of the face whose normal this is (face axes only)
  double height = 0.0;      ///< m, the face's box centre along the unsigned axis (face axes only)
};

/// The axis direction with its sign removed: the first nonzero component is made positive.
/// L and -L, which is what A and B see after a swap, map to the same vector bit for bit.
Vec3 unsignedAxis(const Vec3& v) {
  const bool flip = v.x() < 0.0 || (v.x() == 0.0 && (v.y() < 0.0 || (v.y() == 0.0 && v.z() < 0.0)));
  return flip ? Vec3(-v) : v;
}

/// Lexicographic order of the unsigned axes: a label-free last word between exact ties.
bool axisBefore(const Vec3& p, const Vec3& q) {
  const Vec3 u = unsignedAxis(p);
  const Vec3 w = unsignedAxis(q);
  if (u.x() != w.x()) return u.x() < w.x();
  if (u.y() != w.y()) return u.y() < w.y();
  return u.z() < w.z();
}

/// The face tie-break among faces already within the tie tolerance of the least depth:
/// the larger face; then the box lower along the unsigned axis, so of two equal boxes stacked
/// flush the lower one gives the reference face whatever the rounding; then the smaller depth;
/// then the unsigned axis. Only for concentric boxes with equal faces does the label decide.
bool betterFace(const AxisCandidate& p, const AxisCandidate& q) {
  if (p.faceArea != q.faceArea) return p.faceArea > q.faceArea;
  if (p.height != q.height) return p.height < q.height;
  if (p.depth != q.depth) return p.depth < q.depth;
  if (axisBefore(p.normal, q.normal) || axisBefore(q.normal, p.normal))
    return axisBefore(p.normal, q.normal);
  if (p.kind != q.kind) return p.kind == AxisKind::FaceA;
  return p.indexA + p.indexB < q.indexA + q.indexB;
}

/// Least depth first, then the unsigned axis, then the edge indices.
bool betterEdge(const AxisCandidate& p, const AxisCandidate& q) {
  if (p.depth != q.depth) return p.depth < q.depth;
  if (axisBefore(p.normal, q.normal) || axisBefore(q.normal, p.normal))
    return axisBefore(p.normal, q.normal);
  if (p.indexA != q.indexA) return p.indexA < q.indexA;
  return p.indexB < q.indexB;
}

}  // namespace

SeparatingAxisResult separatingAxisTest(const Obb& a, const Obb& b,
                                        const SeparatingAxisParams& params) {
  const Vec3& ea = a.halfExtents;
  const Vec3& eb = b.halfExtents;
  const Vec3 D = b.center - a.center;

  // C_ij = a_i . b_j. Written as dot products so that the swapped call, which computes
  // b_j . a_i, gets the same bits (products commute; the sum runs in the same order).
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) C(i, j) = a.axes.col(i).dot(b.axes.col(j));
  const Mat3 absC = C.cwiseAbs();
  // Eberly's robustness trick, for the edge axes only: the face depths stay exact, so exactly
  // touching faces report depth 0, not -1e-12.
  const Mat3 absCEdge = absC.array() + params.absCEpsilon;

  // --- Face axes of A and of B (Eberly's table of the 15 tests, rows L = A_i, L = B_j) ---
  std::array<AxisCandidate, 6> faces;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    const double rA = ea[i];
    const double rB = eb[0] * absC(i, 0) + eb[1] * absC(i, 1) + eb[2] * absC(i, 2);
    const double dist = a.axes.col(i).dot(D);
    AxisCandidate& f = faces[i];
    f.depth = (rA + rB) - std::abs(dist);
    // dist == 0 (concentric boxes): A's axis as is, B's axis negated, so a swap still negates.
    f.normal = dist >= 0.0 ? Vec3(a.axes.col(i)) : Vec3(-a.axes.col(i));
    f.kind = AxisKind::FaceA;
    f.indexA = i;
    f.faceArea = 4.0 * ea[i1] * ea[i2];
    f.height = unsignedAxis(f.normal).dot(a.center);
  }
  for (int j = 0; j < 3; ++j) {
    const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
    const double rA = ea[0] * absC(0, j) + ea[1] * absC(1, j) + ea[2] * absC(2, j);
    const double rB = eb[j];
    const double dist = b.axes.col(j).dot(D);
    AxisCandidate& f = faces[3 + j];
    f.depth = (rA + rB) - std::abs(dist);
    f.normal = dist > 0.0 ? Vec3(b.axes.col(j)) : Vec3(-b.axes.col(j));
    f.kind = AxisKind::FaceB;
    f.indexB = j;
    f.faceArea = 4.0 * eb[j1] * eb[j2];
    f.height = unsignedAxis(f.normal).dot(b.center);
  }

  // --- Edge-edge axes L = a_i x b_j (the same table, rows L = A_i x B_j) ---
  bool haveEdge = false;
  AxisCandidate edge;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      // The cross product in world space: the swapped call computes b_j x a_i, the exact
      // negation, so |L| and |L . D| agree bit for bit.
      const Vec3 L = a.axes.col(i).cross(b.axes.col(j));
      const double length = L.norm();
      // Near-parallel edges: L is mostly rounding error and the face axes already decide.
      if (length < params.parallelCutoff) continue;
      const double rA = ea[i1] * absCEdge(i2, j) + ea[i2] * absCEdge(i1, j);
      const double rB = eb[j1] * absCEdge(i, j2) + eb[j2] * absCEdge(i, j1);
      const double dist = L.dot(D);
      AxisCandidate e;
      // Dividing by |L| turns Eberly's unnormalised separation into metres.
      e.depth = ((rA + rB) - std::abs(dist)) / length;
      e.normal = dist >= 0.0 ? Vec3(L / length) : Vec3(-L / length);
      e.kind = AxisKind::EdgeEdge;
      e.indexA = i;
      e.indexB = j;
      if (!haveEdge || betterEdge(e, edge)) edge = e;
      haveEdge = true;
    }
  }

  // --- The best face: least depth, near ties to the larger face ---
  double faceMin = faces[0].depth;
  for (const AxisCandidate& f : faces) faceMin = std::min(faceMin, f.depth);
  const double tieWidth = params.faceTieTolerance * (ea.maxCoeff() + eb.maxCoeff());
  int best = -1;
  for (int k = 0; k < 6; ++k) {
    const AxisCandidate& f = faces[k];
    // A tie never crosses depth 0, so "intersecting" and "depth > 0" keep meaning the same.
    const bool tied = f.depth <= faceMin + tieWidth && (f.depth > 0.0) == (faceMin > 0.0);
    if (tied && (best < 0 || betterFace(f, faces[best]))) best = k;
  }
  const AxisCandidate& face = faces[best];

  // --- Face or edge ---
  const double leastDepth = haveEdge ? std::min(faceMin, edge.depth) : faceMin;
  const bool intersecting = leastDepth > 0.0;
  bool useEdge = false;
  if (haveEdge) {
    // Overlapping: an edge axis must beat the face by the relative bias, so flush faces,
    // whose edge axes coincide with the face normal, give face contacts. Separated: the
    // largest gap wins outright, because -depth must be the largest gap.
    useEdge = intersecting ? edge.depth < face.depth * (1.0 - params.edgeBias)
                           : edge.depth < face.depth;
  }
  const AxisCandidate& chosen = useEdge ? edge : face;

  SeparatingAxisResult result;
  result.intersecting = intersecting;
  result.depth = chosen.depth;
  result.normal = chosen.normal;
  result.kind = chosen.kind;
  result.indexA = chosen.indexA;
  result.indexB = chosen.indexB;
  return result;
}

}  // namespace boxsim
