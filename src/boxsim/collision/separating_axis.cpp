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
///
/// Cost. Most pairs a step tests are boxes resting face on face, so the work is arranged for
/// them: a normal (three divisions for an edge axis) and the tie-break data (face area,
/// height) are formed only for the few axes that can still win, an edge axis whose depth
/// provably cannot win is not divided out at all, and most such axes are not even formed: a
/// lower bound of their overlap from the face axes' numbers rules them out before their cross
/// product (edgeOverlapAtLeast). None of this changes a result bit: every value that reaches
/// the result, or a comparison that picks it, is computed by the same expression as in the
/// plain loop over all 15 axes (separatingAxisTest with SeparatingAxisParams::
/// skipLosingEdgeAxes off, against which it is tested).
#include "boxsim/collision/separating_axis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

namespace boxsim {
namespace {

/// A face axis in the running for the least depth, with everything its tie-break looks at.
struct AxisCandidate {
  double depth = 0.0;       ///< m, rA + rB - |L . D| with L a unit vector
  Vec3 normal = Vec3::Zero();  ///< unit, from A to B
  AxisKind kind = AxisKind::FaceA;
  int indexA = 0;
  int indexB = 0;
  double faceArea = 0.0;    ///< m^2, area of the face whose normal this is
  double height = 0.0;      ///< m, the face's box centre along the unsigned axis
  /// 0 when the face's box comes first in the order of centreOrder, 1 when second: the last
  /// label-free word between two tied faces.
  int owner = 0;
};

/// An edge-edge axis L = a_i x b_j (not normalised) with its depth. The unit normal costs
/// three divisions and is needed only to break an exact tie of depths or for the answer, so
/// it is formed on demand, from the same L, |L| and sign as the depth.
struct EdgeAxis {
  double depth = 0.0;    ///< m, ((rA + rB) - |L . D|) / |L|
  Vec3 L = Vec3::Zero();  ///< a_i x b_j in world space
  double length = 0.0;   ///< |L|, >= parallelCutoff
  double dist = 0.0;     ///< L . D, its sign orients the normal from A to B
  int indexA = 0;
  int indexB = 0;

  /// Unit normal from A to B.
  Vec3 normal() const { return dist >= 0.0 ? Vec3(L / length) : Vec3(-L / length); }
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

/// -1 when a's centre comes before b's in lexicographic order (x, then y, then z), 1 when
/// after, 0 when they are the same point. Swapping the boxes negates it.
int centreOrder(const Obb& a, const Obb& b) {
  for (int k = 0; k < 3; ++k)
    if (a.center[k] != b.center[k]) return a.center[k] < b.center[k] ? -1 : 1;
  return 0;
}

/// The face tie-break among faces already within the tie tolerance of the least depth:
/// the larger face; then the box lower along the unsigned axis, so of two equal boxes stacked
/// flush the lower one gives the reference face whatever the rounding; then the smaller depth;
/// then the unsigned axis; then the box whose centre comes first (centreOrder). Only for
/// concentric boxes with equal faces does the label decide.
bool betterFace(const AxisCandidate& p, const AxisCandidate& q) {
  if (p.faceArea != q.faceArea) return p.faceArea > q.faceArea;
  if (p.height != q.height) return p.height < q.height;
  if (p.depth != q.depth) return p.depth < q.depth;
  if (axisBefore(p.normal, q.normal) || axisBefore(q.normal, p.normal))
    return axisBefore(p.normal, q.normal);
  if (p.owner != q.owner) return p.owner < q.owner;
  return p.indexA + p.indexB < q.indexA + q.indexB;
}

/// Least depth first, then the unsigned axis, then the edge indices. The normals are formed
/// only on an exact tie of depths.
bool betterEdge(const EdgeAxis& p, const EdgeAxis& q) {
  if (p.depth != q.depth) return p.depth < q.depth;
  const Vec3 np = p.normal();
  const Vec3 nq = q.normal();
  if (axisBefore(np, nq) || axisBefore(nq, np)) return axisBefore(np, nq);
  if (p.indexA != q.indexA) return p.indexA < q.indexA;
  return p.indexB < q.indexB;
}

/// Face axis k of the test (0..2: face axis k of A, 3..5: face axis k-3 of B) with its
/// tie-break data, given its depth, dist = axis . D and order = centreOrder(a, b).
AxisCandidate faceCandidate(const Obb& a, const Obb& b, int k, double depth, double dist,
                            int order) {
  AxisCandidate f;
  f.depth = depth;
  if (k < 3) {
    const int i1 = (k + 1) % 3, i2 = (k + 2) % 3;
    // dist == 0 (concentric boxes): A's axis as is, B's axis negated, so a swap still negates.
    f.normal = dist >= 0.0 ? Vec3(a.axes.col(k)) : Vec3(-a.axes.col(k));
    f.kind = AxisKind::FaceA;
    f.indexA = k;
    f.faceArea = 4.0 * a.halfExtents[i1] * a.halfExtents[i2];
  } else {
    const int j = k - 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
    f.normal = dist > 0.0 ? Vec3(b.axes.col(j)) : Vec3(-b.axes.col(j));
    f.kind = AxisKind::FaceB;
    f.indexB = j;
    f.faceArea = 4.0 * b.halfExtents[j1] * b.halfExtents[j2];
  }
  const Vec3 axis = unsignedAxis(f.normal);
  f.height = axis.dot(k < 3 ? a.center : b.center);
  // With D perpendicular to the axis (dist == 0) the normal's sign and which of two equal
  // faces wins have no geometric answer along it; the centres' order gives one that a swap
  // negates. Only concentric boxes (order 0) fall back to the labels above.
  f.owner = (order == 0 ? k < 3 : (k < 3) == (order < 0)) ? 0 : 1;
  if (dist == 0.0 && order != 0) f.normal = order < 0 ? axis : Vec3(-axis);
  return f;
}

/// The face tie width, m: faceTieTolerance times the boxes' size (the sum of their largest half
/// extents). Face depths closer than this count as tied (SeparatingAxisParams).
double faceTieWidth(const Obb& a, const Obb& b, const SeparatingAxisParams& params) {
  return params.faceTieTolerance * (a.halfExtents.maxCoeff() + b.halfExtents.maxCoeff());
}

/// Depth (m) along face axis i of A, Eberly's row L = A_i: rA + rB - |L . D| with rA = e^A_i
/// and rB = sum_j e^B_j |C_ij|, where absC(i, j) = |a_i . b_j| and dist = a_i . D (m). The
/// full test and its one-axis shortcut (separatedBeyond) both use it, so they agree bit for bit.
template <class AbsC>
double faceDepthA(const Obb& a, const Obb& b, const AbsC& absC, int i, double dist) {
  const Vec3& ea = a.halfExtents;
  const Vec3& eb = b.halfExtents;
  const double rA = ea[i];
  const double rB = eb[0] * absC(i, 0) + eb[1] * absC(i, 1) + eb[2] * absC(i, 2);
  return (rA + rB) - std::abs(dist);
}

/// Depth (m) along face axis j of B, Eberly's row L = B_j: rA = sum_i e^A_i |C_ij|, rB = e^B_j,
/// dist = b_j . D (m). As faceDepthA.
template <class AbsC>
double faceDepthB(const Obb& a, const Obb& b, const AbsC& absC, int j, double dist) {
  const Vec3& ea = a.halfExtents;
  const Vec3& eb = b.halfExtents;
  const double rA = ea[0] * absC(0, j) + ea[1] * absC(1, j) + ea[2] * absC(2, j);
  const double rB = eb[j];
  return (rA + rB) - std::abs(dist);
}

/// An edge-edge axis L = a_i x b_j before it is divided by |L| (Eberly's rows L = A_i x B_j).
struct EdgeOverlap {
  Vec3 L;          ///< a_i x b_j in world space; |L| is the sine of the angle between the edges
  double dist;     ///< L . D, m
  double overlap;  ///< (rA + rB) - |L . D|, m times |L|: Eberly's unnormalised separation
};

/// Calls f(I, J) with I, J std::integral_constant<int, i> and <int, j> for edge indices known
/// only at run time (0..2 each), so that the axis functions below see their indices as constants:
/// the index arithmetic costs more than an axis' own.
template <class F>
decltype(auto) withEdgeIndices(int i, int j, F&& f) {
  using std::integral_constant;
  switch (3 * i + j) {
    case 0: return f(integral_constant<int, 0>{}, integral_constant<int, 0>{});
    case 1: return f(integral_constant<int, 0>{}, integral_constant<int, 1>{});
    case 2: return f(integral_constant<int, 0>{}, integral_constant<int, 2>{});
    case 3: return f(integral_constant<int, 1>{}, integral_constant<int, 0>{});
    case 4: return f(integral_constant<int, 1>{}, integral_constant<int, 1>{});
    case 5: return f(integral_constant<int, 1>{}, integral_constant<int, 2>{});
    case 6: return f(integral_constant<int, 2>{}, integral_constant<int, 0>{});
    case 7: return f(integral_constant<int, 2>{}, integral_constant<int, 1>{});
    default: return f(integral_constant<int, 2>{}, integral_constant<int, 2>{});
  }
}

/// The projected radii rA + rB of edge-edge axis L = a_i x b_j (m times |L|), absCEdge(r, c)
/// being |C_rc| + absCEpsilon: Eberly's rows L = A_i x B_j. One expression for edgeOverlap and
/// edgeOverlapAtLeast, so that the two agree bit for bit.
template <int i, int j, class AbsCEdge>
double edgeRadii(const Obb& a, const Obb& b, const AbsCEdge& absCEdge) {
  const Vec3& ea = a.halfExtents;
  const Vec3& eb = b.halfExtents;
  constexpr int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
  constexpr int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  const double rA = ea[i1] * absCEdge(i2, j) + ea[i2] * absCEdge(i1, j);
  const double rB = eb[j1] * absCEdge(i, j2) + eb[j2] * absCEdge(i, j1);
  return rA + rB;
}

/// Edge-edge axis L = a_i x b_j with its overlap, absCEdge as for edgeRadii and D = centre of B
/// - centre of A (m). Shared by the full test and separatedBeyond.
template <int i, int j, class AbsCEdge>
EdgeOverlap edgeOverlap(const Obb& a, const Obb& b, const Vec3& D, const AbsCEdge& absCEdge) {
  EdgeOverlap e;
  // The cross product in world space: the swapped call computes b_j x a_i, the exact
  // negation, so |L| and |L . D| agree bit for bit.
  e.L = a.axes.col(i).cross(b.axes.col(j));
  e.dist = e.L.dot(D);
  // Eberly's unnormalised separation; dividing by |L| turns it into metres.
  e.overlap = edgeRadii<i, j>(a, b, absCEdge) - std::abs(e.dist);
  return e;
}

/// A lower bound (m times |L|) of edgeOverlap<i, j>'s overlap from what the face axes already
/// hold, without the cross product: in A's frame L = a_i x b_j is C(i1, j) a_i2 - C(i2, j) a_i1,
/// so L . D = C(i1, j) (a_i2 . D) - C(i2, j) (a_i1 . D), with C_ij = a_i . b_j and dist the face
/// axes' a_k . D (FaceDepths::dist, A's first). The radii are edgeOverlap's own (edgeRadii);
/// only |L . D| is formed another way, and `slack` (m) covers how far the two forms can differ:
/// their rounding (about 20 ulp of |D|) and the axes' departure from orthonormal (3 δ |D| for
/// columns orthonormal within δ).
template <int i, int j, class AbsCEdge>
double edgeOverlapAtLeast(const Obb& a, const Obb& b, const Mat3& C,
                          const std::array<double, 6>& dist, const AbsCEdge& absCEdge,
                          double slack) {
  constexpr int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
  const double distL = C(i1, j) * dist[i2] - C(i2, j) * dist[i1];
  return (edgeRadii<i, j>(a, b, absCEdge) - std::abs(distL)) - slack;
}

/// The depths of the six face axes (Eberly's table of the 15 tests, rows L = A_i, L = B_j).
struct FaceDepths {
  std::array<double, 6> depth;  ///< m; 0..2 face axes of A, 3..5 face axes of B
  std::array<double, 6> dist;   ///< m, axis . D, whose sign orients the face normal
  double least;                 ///< m, the least of the six depths
};

/// The six face depths, absC being |C| and D = centre of B - centre of A (m). Depths only: the
/// normal and the tie-break data are formed by bestFace for the tied faces alone.
FaceDepths faceDepths(const Obb& a, const Obb& b, const Vec3& D, const Mat3& absC) {
  FaceDepths f;
  for (int i = 0; i < 3; ++i) {
    f.dist[i] = a.axes.col(i).dot(D);
    f.depth[i] = faceDepthA(a, b, absC, i, f.dist[i]);
  }
  for (int j = 0; j < 3; ++j) {
    f.dist[3 + j] = b.axes.col(j).dot(D);
    f.depth[3 + j] = faceDepthB(a, b, absC, j, f.dist[3 + j]);
  }
  f.least = f.depth[0];
  for (const double depth : f.depth) f.least = std::min(f.least, depth);
  return f;
}

/// The best face: least depth, near ties (within tieWidth, m) to the larger face (betterFace).
/// Only the tied faces get a candidate (normal, area, height), compared in index order.
/// (No face is tied only if the depths are NaN; the default candidate returned is then
/// meaningless, as is the answer anyway.)
AxisCandidate bestFace(const Obb& a, const Obb& b, const FaceDepths& faces, double tieWidth) {
  AxisCandidate face;
  bool haveFace = false;
  const int order = centreOrder(a, b);
  for (int k = 0; k < 6; ++k) {
    // A tie never crosses depth 0, so "intersecting" and "depth > 0" keep meaning the same.
    const bool tied = faces.depth[k] <= faces.least + tieWidth &&
                      (faces.depth[k] > 0.0) == (faces.least > 0.0);
    if (!tied) continue;
    const AxisCandidate f = faceCandidate(a, b, k, faces.depth[k], faces.dist[k], order);
    if (!haveFace || betterFace(f, face)) face = f;
    haveFace = true;
  }
  return face;
}

/// The best edge-edge axis (Eberly's rows L = A_i x B_j): least depth, then the unsigned axis,
/// then the edge indices (betterEdge). absCEdge is |C| + absCEpsilon, D = centre of B - centre
/// of A (m). Axes shorter than parallelCutoff are left out, and so are axes that provably lose
/// to the best face, of depth faceDepth (m), under the bar edgeBar (m; see "Face or edge" in
/// separatingAxisTest); NaN for both leaves none out (no comparison with NaN holds). Empty when
/// no axis is left.
std::optional<EdgeAxis> bestEdge(const Obb& a, const Obb& b, const Vec3& D, const Mat3& C,
                                 const Mat3& absCEdge, const FaceDepths& faces, double faceDepth,
                                 double edgeBar, double parallelCutoff) {
  std::optional<EdgeAxis> edge;
  // The room edgeOverlapAtLeast needs: 1e-9 |D|_1 covers its rounding (~1e-15 |D|) and axes
  // orthonormal within 3e-10, far looser than a normalised quaternion's matrix (~1e-16).
  const double slack = 1e-9 * D.cwiseAbs().sum();
  // Unrolled, so every index below is a constant: the loop bookkeeping and the "% 3" cost
  // more than the arithmetic of an axis that is not divided out.
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
#pragma GCC unroll 3
    for (int j = 0; j < 3; ++j) {
      // First from the face axes' own numbers, without the axis' cross product: an overlap that
      // is certainly at least both bars and positive is one the test below leaves out, or
      // (|L|^2 rounded just above 1) one whose depth, over both bars, could not change the
      // answer either (see below). Only axes after the first one evaluated, as below.
      if (edge) {
        const double atLeast = withEdgeIndices(i, j, [&](auto I, auto J) {
          return edgeOverlapAtLeast<I, J>(a, b, C, faces.dist, absCEdge, slack);
        });
        if (atLeast > 0.0 && atLeast >= edgeBar && atLeast >= faceDepth) continue;
      }
      const EdgeOverlap o = withEdgeIndices(
          i, j, [&](auto I, auto J) { return edgeOverlap<I, J>(a, b, D, absCEdge); });
      const double lengthSquared = o.L.squaredNorm();  // |L| = sqrt of this, as L.norm() does

      // An axis that provably loses to the face is not divided out (no root, no division).
      // lengthSquared <= 1 makes |L| <= 1, and then, overlap being a positive double and
      // rounding monotone, the rounded depth overlap / |L| is >= overlap. So overlap > 0 and
      // overlap at least both bars mean a positive depth, which cannot make "intersecting"
      // false, and one that neither comparison under "Face or edge" prefers to the face.
      // Leaving the axis out changes nothing: had it been the best edge, the best of the rest
      // is no better and loses too. (Axes below parallelCutoff are left out anyway.) The first
      // axis to pass the cutoff is always evaluated, so the running best starts from the same
      // axis as in the plain loop, which keeps the answer the same even for NaN depths, which
      // win no comparison.
      if (edge && lengthSquared <= 1.0 && o.overlap > 0.0 && o.overlap >= edgeBar &&
          o.overlap >= faceDepth)
        continue;
      const double length = std::sqrt(lengthSquared);
      // Near-parallel edges: L is mostly rounding error and the face axes already decide.
      if (length < parallelCutoff) continue;
      EdgeAxis e;
      e.depth = o.overlap / length;
      e.L = o.L;
      e.length = length;
      e.dist = o.dist;
      e.indexA = i;
      e.indexB = j;
      if (!edge || betterEdge(e, *edge)) edge = e;
    }
  }
  return edge;
}

/// C_ij = a_i . b_j, the cosines between the boxes' axes. Written as dot products so that the
/// swapped call, which computes b_j . a_i, gets the same bits (products commute; the sum runs
/// in the same order).
[[gnu::always_inline]] inline Mat3 axisCosines(const Obb& a, const Obb& b) {
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) C(i, j) = a.axes.col(i).dot(b.axes.col(j));
  return C;
}

/// The test's result from its best face (AxisCandidate), marked not intersecting.
SeparatingAxisResult faceResult(const AxisCandidate& face) {
  return {false, face.depth, face.normal, face.kind, face.indexA, face.indexB};
}

/// separatingAxisTest, and separatingAxisTestWithin when kWithin (margin in m, >= 0; unread
/// otherwise).
template <bool kWithin>
[[gnu::always_inline]] inline
SeparatingAxisResult testAxes(const Obb& a, const Obb& b, const SeparatingAxisParams& params,
                              [[maybe_unused]] double margin) {
  const Vec3 D = b.center - a.center;

  const Mat3 C = axisCosines(a, b);
  const Mat3 absC = C.cwiseAbs();
  // Eberly's robustness trick, for the edge axes only: the face depths stay exact, so exactly
  // touching faces report depth 0, not -1e-12.
  const Mat3 absCEdge = absC.array() + params.absCEpsilon;

  // --- Face axes of A and of B: the best face, least depth, near ties to the larger face ---
  const FaceDepths faces = faceDepths(a, b, D, absC);
  const double tieWidth = faceTieWidth(a, b, params);
  const AxisCandidate face = bestFace(a, b, faces, tieWidth);
  // The two bars an edge axis must get under to be chosen instead of the face (see "Face or
  // edge" below): edgeBar when the boxes overlap, face.depth when they do not.
  const double edgeBar = face.depth * (1.0 - params.edgeBias);
  // Within a margin: the best face apart by at least the margin settles it (see
  // separatingAxisTestWithin; with the face at depth <= 0, "Face or edge" below reports it or an
  // edge axis deeper apart still).
  if constexpr (kWithin)
    if (face.depth <= -margin) return faceResult(face);

  // --- Edge-edge axes L = a_i x b_j ---
  // SeparatingAxisParams::skipLosingEdgeAxes off: bars no overlap reaches, every axis in.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::optional<EdgeAxis> edge =
      bestEdge(a, b, D, C, absCEdge, faces, params.skipLosingEdgeAxes ? face.depth : nan,
               params.skipLosingEdgeAxes ? edgeBar : nan, params.parallelCutoff);

  // --- Face or edge ---
  const double leastDepth = edge ? std::min(faces.least, edge->depth) : faces.least;
  const bool intersecting = leastDepth > 0.0;
  // Overlapping: an edge axis must beat the face by the relative bias, so flush faces, whose
  // edge axes coincide with the face normal, give face contacts. Separated: the largest gap
  // wins. Either way it must also win by more than the face tie width: flush faces whose
  // depth is rounding (±1e-11 m in a resting stack) would otherwise give an edge axis that
  // rounding favours, and a one-point edge contact where a face rests on a face. Separated
  // boxes whose every face axis overlaps (a box beside the edge of a wide ground, apart along
  // an edge axis by less than the tie width) report that edge axis: the face's depth > 0 would
  // contradict intersecting = false.
  const bool useEdge = edge && (intersecting ? edge->depth < edgeBar - tieWidth
                                             : edge->depth < face.depth - tieWidth ||
                                                   face.depth > 0.0);

  SeparatingAxisResult result = faceResult(face);
  result.intersecting = intersecting;
  if (useEdge) {
    result.depth = edge->depth;
    result.normal = edge->normal();
    result.kind = AxisKind::EdgeEdge;
    result.indexA = edge->indexA;
    result.indexB = edge->indexB;
  }
  return result;
}

}  // namespace

SeparatingAxisResult separatingAxisTest(const Obb& a, const Obb& b,
                                        const SeparatingAxisParams& params) {
  return testAxes<false>(a, b, params, 0.0);
}

SeparatingAxisResult bestFaceAxis(const Obb& a, const Obb& b, const SeparatingAxisParams& params) {
  // The face part of testAxes, by the same expressions, so the face is the one it weighs.
  const Vec3 D = b.center - a.center;
  const AxisCandidate face = bestFace(a, b, faceDepths(a, b, D, axisCosines(a, b).cwiseAbs()),
                                      faceTieWidth(a, b, params));
  SeparatingAxisResult result = faceResult(face);
  result.intersecting = face.depth > 0.0;
  return result;
}

SeparatingAxisResult separatingAxisTestWithin(const Obb& a, const Obb& b, double margin,
                                              const SeparatingAxisParams& params) {
  // NaN or a negative margin: no shortcut, the full test.
  if (!(margin >= 0.0)) return separatingAxisTest(a, b, params);
  return testAxes<true>(a, b, params, margin);
}

bool separatedBeyond(const Obb& a, const Obb& b, const SeparatingAxisResult& axis, double margin,
                     const SeparatingAxisParams& params, double* depthOut) {
  const Vec3 D = b.center - a.center;
  // C and its rows as separatingAxisTest forms them, entry for entry.
  const auto absC = [&](int i, int j) { return std::abs(a.axes.col(i).dot(b.axes.col(j))); };
  double depth = 0.0;
  if (axis.kind == AxisKind::FaceA) {
    const int i = axis.indexA;
    depth = faceDepthA(a, b, absC, i, a.axes.col(i).dot(D));
  } else if (axis.kind == AxisKind::FaceB) {
    const int j = axis.indexB;
    depth = faceDepthB(a, b, absC, j, b.axes.col(j).dot(D));
  } else {
    const auto absCEdge = [&](int r, int c) { return absC(r, c) + params.absCEpsilon; };
    const EdgeOverlap o = withEdgeIndices(axis.indexA, axis.indexB, [&](auto I, auto J) {
      return edgeOverlap<I, J>(a, b, D, absCEdge);
    });
    const double length = std::sqrt(o.L.squaredNorm());
    // The full test skips such an axis, so it says nothing about the full test's answer.
    if (!(length >= params.parallelCutoff)) return false;
    depth = o.overlap / length;
  }
  const double tieWidth = faceTieWidth(a, b, params);
  // Twice the tie width: once for the full test's preference of a tied face or a face over an
  // edge, once (with the relative term) for the rounding of these few operations.
  const bool apart = depth + 2.0 * tieWidth + 1e-15 * std::abs(depth) <= -margin;
  if (apart && depthOut) *depthOut = depth;
  return apart;
}

DepthAfterTranslation::DepthAfterTranslation(const Obb& a, const Obb& b,
                                             const SeparatingAxisResult& result,
                                             const SeparatingAxisParams& params)
    : claim_(result.depth > 0.0 && std::isfinite(result.depth)),
      reduced_(result.depth * (1.0 - params.edgeBias) - faceTieWidth(a, b, params)),
      scaleBase_(1.0 + a.center.cwiseAbs().maxCoeff() + b.center.cwiseAbs().maxCoeff() +
                 a.halfExtents.sum() + b.halfExtents.sum()) {}

double DepthAfterTranslation::atLeast(double translation) const {
  if (!claim_ || !(translation >= 0.0)) return -std::numeric_limits<double>::infinity();
  // The coordinates' rounding, relative 1e-9 of their scale, the translation's included.
  return reduced_ - translation - 1e-9 * (scaleBase_ + translation);
}

}  // namespace boxsim
