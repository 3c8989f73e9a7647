/// \file
/// The OBB-OBB separating-axis test over 15 axes (\thesis{§3.2}; Eberly).
#pragma once

#include "boxsim/collision/contact.hpp"

namespace boxsim {

/// m: a pair intersects when its separating-axis depth exceeds this. Boxes built touching (a
/// tower) overlap by rounding, ~1e-17 m for unit boxes; 1 nm ignores that and nothing else. The
/// default of the techniques' intersection tests (TimeOfImpactParams::depthTolerance of the
/// time-of-impact search), and the measure by which scene loading rejects boxes that overlap at
/// the start.
inline constexpr double kIntersectionDepthTolerance = 1e-9;

/// Tolerances of the separating-axis test.
struct SeparatingAxisParams {
  /// Edge-edge axes whose cross product is shorter than this (unitless, the sine of the angle
  /// between the edges) are skipped: near-parallel edges give no reliable axis, and their face
  /// axes already separate such boxes.
  double parallelCutoff = 1e-6;
  /// A face axis is preferred over an edge axis unless the edge axis' depth is smaller by more
  /// than this relative amount (flush faces must produce face contacts, not edge contacts).
  double edgeBias = 0.05;
  /// Added to every |C_ij| = |a_i . b_j| used by the edge-edge axes (unitless; Eberly's
  /// robustness trick). It dominates the rounding error of C (a few ulp, ~1e-16) by four orders
  /// of magnitude, so rounding never makes an edge axis report a gap that is not there, and it
  /// makes an edge axis that coincides with a face axis (flush boxes) lose to the face axis.
  /// It inflates an edge depth by at most absCEpsilon * (sum of 4 half extents) / |a_i x b_j|.
  double absCEpsilon = 1e-12;
  /// Face axes whose depths differ by less than this fraction of the boxes' size (the sum of
  /// their largest half extents) count as tied, and the tie goes to the larger face, then to
  /// the lower box along the axis, so a box resting flush on the ground (or on an equal box)
  /// always clips against the lower face whatever rounding says. The rule looks only at
  /// geometry, never at which box is A, so it is swap-symmetric.
  double faceTieTolerance = 1e-9;
  /// Speed only, the same answer bit for bit either way (tested): edge-edge axes that provably
  /// lose to the best face are left out, most without their cross product (they are worked out
  /// from the face axes' numbers first). false evaluates every edge axis, the plain loop over
  /// the 15 axes.
  bool skipLosingEdgeAxes = true;
};

/// Tests boxes A and B for overlap on the 3 face axes of A, the 3 of B and the 9 edge-edge
/// axes, and returns the axis of least penetration (\thesis{§3.2}; D. Eberly, "Dynamic
/// Collision Detection using Oriented Bounding Boxes", its table of the 15 axes, and
/// "Intersection of Convex Objects: The Method of Separating Axes").
///
/// Overlapping boxes (every axis has depth > 0): the axis of least depth, except that a face
/// axis is kept unless an edge axis is smaller by more than params.edgeBias (relative) plus
/// the face tie width (faceTieTolerance times the boxes' size), and face axes within that
/// width of each other go to the larger face, then the lower box.
/// Separated or touching boxes: depth = -(largest gap over the tested axes) <= 0, up to that
/// same width (an edge gap must exceed the face gap by more than it; an edge gap is reported
/// whenever every face axis overlaps) and intersecting = false; the normal is that gap's axis.
/// intersecting is exactly depth > 0.
///
/// The answer is symmetric: swapping A and B gives the same depth (bit for bit), the negated
/// normal, and FaceA and FaceB (indexA and indexB) exchanged. Where the chosen face axis is
/// perpendicular to the line of centres, its sign, and the choice between equal tied faces of
/// A and B, go by the lexicographic order of the centres, so this holds there too; only two
/// concentric boxes with equal tied faces keep the kind (and may keep the normal).
/// \param a, b   the boxes; their axes must be orthonormal (within 3e-10: the edge axes left out
///               by a bound rely on it; a normalised quaternion's matrix is within ~1e-16)
/// \return depth in m, unit normal from A to B (for an edge axis, the normalised cross
///         product, so depths along every axis are in metres)
SeparatingAxisResult separatingAxisTest(const Obb& a, const Obb& b,
                                        const SeparatingAxisParams& params = {});

/// separatingAxisTest(a, b, params) for a caller that needs only the contact within `margin`
/// (m, >= 0): boxes whose best face axis (the full test's own, its ties and all) is apart by at
/// least the margin get that face's result, the edge axes not looked at: depth <= -margin,
/// intersecting false, the face's normal, kind and indices. The full test's depth is then no
/// greater (it reports that face or an edge axis apart by more), so buildContactManifold within
/// the margin gives no point for either, and separatedBeyond may measure along the face next
/// time. Every other pair gets the full test's result, bit for bit. For boxes apart the edge
/// axes (a cross product, a root and a division each; none can be left out as losing) are most
/// of the test's cost. A negative or NaN margin runs the full test.
SeparatingAxisResult separatingAxisTestWithin(const Obb& a, const Obb& b, double margin,
                                              const SeparatingAxisParams& params = {});

/// The best of the 6 face axes of boxes A and B as separatingAxisTest weighs them (least
/// depth, near ties to the larger face, then the lower box), whatever the edge axes say: its
/// depth (m; > 0 overlapping along it), unit normal from A to B, kind (FaceA or FaceB) and
/// indices; intersecting is depth > 0 along this axis alone. For a pair whose test chose an
/// edge axis, the face a small turn may bring flush (clipContact of this result gives the
/// corners that would then touch; SlowPairCache).
SeparatingAxisResult bestFaceAxis(const Obb& a, const Obb& b,
                                  const SeparatingAxisParams& params = {});

/// A one-axis shortcut of separatingAxisTest for a pair tested before (temporal coherence, as
/// in Gottschalk, Lin and Manocha's OBBTree, 1996, and most engines' cached separating axes):
/// the depth along the axis `axis` named (its kind, indexA and indexB; typically the answer
/// of the pair's last test), computed by the same expression as in the full test.
///
/// Returns true only when separatingAxisTest(a, b, params).depth <= -margin is certain, so a
/// caller that treats such a pair as "no contact within margin" gets the full test's answer
/// bit for bit. Why: the full test's depth exceeds the least depth over its axes by at most
/// the face tie width w (faceTieTolerance times the sum of the largest half extents), so a
/// depth d along one tested axis with d + 2 w <= -margin (w again covering rounding) bounds it.
/// An edge axis too close to parallel to be tested (parallelCutoff) and NaN give false; false
/// means only "run the full test".
/// \param margin  m, >= 0
/// \param depth   when given and the answer is true, receives the depth along the axis (m,
///                 <= -margin)
bool separatedBeyond(const Obb& a, const Obb& b, const SeparatingAxisResult& axis, double margin,
                     const SeparatingAxisParams& params = {}, double* depth = nullptr);

/// A lower bound (m) of separatingAxisTest(a', b', params).depth for boxes a' and b' that are a
/// and b moved apart or together by a translation of length at most t (m), their axes and
/// extents unchanged, given `result` = separatingAxisTest(a, b, params): atLeast(t); -infinity
/// when result.depth <= 0 or is not finite (no claim), or t is not >= 0. What does not depend
/// on t is worked out once, at construction: FIXCONTACTCONSTRAINTS asks after every nudge of a
/// box, to nudge it many times between two tests.
///
/// Why it holds: along each tested axis (unit, or an edge axis divided by its length) the
/// depth is a constant minus |axis . (c_b - c_a)|, so a translation changes it by at most its
/// length; which edge axes are tested depends on the axes alone. The reported depth of
/// overlapping boxes is at most the least tested depth widened by the relative edge bias and
/// the face tie width (a face is kept unless an edge beats it by both), so every tested axis
/// has depth >= depth (1 - edgeBias) - tie width, and so has every axis after the translation
/// less its length; a relative 1e-9 of the coordinates covers the rounding of either test.
class DepthAfterTranslation {
 public:
  /// The bound for boxes a and b, `result` being separatingAxisTest(a, b, params).
  DepthAfterTranslation(const Obb& a, const Obb& b, const SeparatingAxisResult& result,
                        const SeparatingAxisParams& params = {});
  /// The lower bound (m) after a translation of length at most `translation` (m).
  double atLeast(double translation) const;

 private:
  bool claim_;        ///< result.depth > 0 and finite: there is a bound to give
  double reduced_;    ///< m, result.depth (1 - edgeBias) - tie width
  double scaleBase_;  ///< m, 1 + the largest |centre coordinate| of a and of b + all half extents
};

}  // namespace boxsim
