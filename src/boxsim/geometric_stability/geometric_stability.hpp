/// \file
/// SETGEOMETRICALLYSTABLE of \alg{A.2} (\thesis{§5.4}): which bodies cannot be accelerated by
/// gravity (along −y) or by frictionless contact forces of any size, decided from the ground up.
///
/// A movable box qualifies when every one of its contact normals is along ±y and each of the
/// four corners of its bottom face rests on a body that already qualifies. In the damped
/// technique, COLLIDE (\alg{COLLIDE L11-L14}) uses the flags to zero the vertical momentum and the
/// tipping components of the angular momentum of such bodies; the analytic technique can leave
/// their stable-to-stable contacts out of its system (\thesis{§5.4}, with that chapter).
///
/// Corners of the bottom face (the face whose outward normal points down), in the plane of that
/// face; u and v are the box's other two axes, so any yaw about y is allowed:
/// \verbatim
///           v
///           ^
///     1 +---|---+ 0       corner k = o + su h_u u + sv h_v v, o the bottom-face centre:
///       |   |   |           0: (+,+)  1: (-,+)  2: (-,-)  3: (+,-)
///       |   o---|---> u   a contact point marks corner k when its xz projection lies within
///       |       |         the corner tolerance of corner k's xz projection
///     2 +-------+ 3
/// \endverbatim
#pragma once

#include <array>
#include <string>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/collision/xz_hull.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/geometric_stability/load_stability.hpp"

namespace boxsim {

/// Tolerances of the geometric-stability test. The thesis leaves the word "equivalent" of
/// \alg{SETGEOMETRICALLYSTABLE L13} and \alg{SETGEOMETRICALLYSTABLE L19} and the coincidence of
/// \alg{SETGEOMETRICALLYSTABLE L15} unquantified.
struct GeometricStabilityParams {
  /// Unitless, in [0, 1): a direction n counts as along ±y when 1 − |n·y| is at most this.
  /// It applies to contact normals and to the face normal that makes a box "level". 1e-4 is a
  /// tilt of about 0.8°; a box tilted that much lifts one edge of a 1 m face by 14 mm, far more
  /// than any contact margin, so it loses two corners anyway: the corner rule, not this
  /// tolerance, is what rejects visibly tilted boxes.
  double normalTolerance = 1e-4;
  /// Unitless, >= 0, a fraction of the smaller half extent of the bottom face: a contact point
  /// marks a corner when their xz projections are closer than this fraction times that half
  /// extent (m). 1e-3 is 0.5 mm on a unit cube: it absorbs rounding and a flush edge, and
  /// rejects a real overhang. Scaling with the box keeps the test the same at every size.
  double cornerTolerance = 1e-3;
  /// Ablation: the footnote of \thesis{§5.4} instead of the corner rule. A body then qualifies
  /// when the xz convex hull of its support points (points of its downward contacts with
  /// qualifying bodies) covers the xz projection of its bottom face, within the corner
  /// tolerance. For boxes both rules agree: the support points lie in the bottom face, and a
  /// hull of points inside a rectangle contains the rectangle only if it contains its corners.
  bool useSupportHull = false;
  /// Beyond the thesis (\thesis{§6.3.1}, Figs. 6.4 and 6.5): after §5.4's rule, also mark the
  /// boxes that hold under the loads they have (load_stability.hpp: a linear program of
  /// equilibrium over the support forces of each group of resting boxes whose loads are all
  /// known). Off: the thesis' classification alone.
  bool underLoad = false;
};

/// Which classification a technique runs (the command line's --geometric-stability).
enum class GeometricStabilityMode {
  Off,        ///< none: every body is simulated in full
  Thesis,     ///< \thesis{§5.4}'s rule (SETGEOMETRICALLYSTABLE)
  UnderLoad,  ///< §5.4's rule, then stability under load (GeometricStabilityParams::underLoad)
};

/// "off", "thesis", "under_load".
std::string geometricStabilityModeName(GeometricStabilityMode mode);
/// Parses the names of geometricStabilityModeName(); throws std::invalid_argument naming the
/// known ones on others.
GeometricStabilityMode parseGeometricStabilityMode(const std::string& name);

/// One flag per body of `world` (StabilityFlag): kGeometricallyStable (1) for a geometrically
/// stable body, kStableUnderLoad (2) for one stable under its loads (params.underLoad only),
/// kUnstable (0) otherwise.
/// \param world     bodies with up-to-date derived rotation R (columns = box axes)
/// \param contacts  every contact manifold of the world, as findContacts(world, margin) returns
///                  them with a small margin (e.g. 1e-6 m), so that exactly touching boxes have
///                  a manifold; in any order. A missing side contact can only make a body look
///                  stable that is not.
/// \param params    tolerances and the hull ablation
/// \return flags in body order: immovable bodies are always stable; a movable body is stable
///         when it is level (a face normal along −y), none of its contacts has a normal off
///         the y axis, every contact under it is with a stable body, and the four corners of
///         its bottom face coincide with points of those contacts. The result does not depend
///         on the order of bodies or contacts. With params.underLoad, addStableUnderLoad adds
///         its verdicts.
/// \throws std::invalid_argument when a manifold names a body outside the world, or a
///         tolerance is negative, not finite, or normalTolerance >= 1; std::runtime_error from
///         addStableUnderLoad (a build without GLPK).
/// \thesis{§5.4}, \alg{SETGEOMETRICALLYSTABLE L1-L20}; the deviations are in the
/// chapter page \ref chapter_geometric_stability.
std::vector<char> setGeometricallyStable(const World& world,
                                         const std::vector<ContactManifold>& contacts,
                                         const GeometricStabilityParams& params = {});

/// setGeometricallyStable with its working lists kept from call to call, for a stepper that
/// asks every step: once its lists have grown to the world's size, a call allocates nothing
/// (with params.underLoad, addStableUnderLoad still does). The same flags as the free function.
class GeometricStability {
 public:
  /// setGeometricallyStable(world, contacts, params); the flags stay valid until the next call.
  const std::vector<char>& operator()(const World& world,
                                      const std::vector<ContactManifold>& contacts,
                                      const GeometricStabilityParams& params = {});

  /// What the sweep knows of one body besides its flag.
  struct BodyMarks {
    std::array<bool, 4> corners{};  ///< bottom-face corners marked so far (L15)
    std::vector<Vec2> support;      ///< footnote rule: xz points of contacts with stable bodies
    bool ruledOut = false;          ///< some contact disqualified it for good
  };
  /// The bottom face of a box: what "the bottom plane of the box" (\thesis{§5.4}) means for a
  /// box of any orientation.
  struct BottomFace {
    bool level = false;             ///< its outward normal is along −y within normalTolerance
    std::array<Vec2, 4> corners{};  ///< xz projections, numbered as in the file's diagram
    double tolerance = 0.0;         ///< m: how near a point must be to a corner to mark it
  };
  /// One point of a manifold whose normal is along y, as A.2 sees a contact: a point with a top
  /// and a bottom body.
  struct VerticalContact {
    double height = 0.0;     ///< y of the point, m
    int bottom = -1;         ///< body index
    int top = -1;            ///< body index
    int manifold = -1;       ///< index into the contacts
    int point = -1;          ///< index into the manifold's points
    Vec2 xz = Vec2::Zero();  ///< the point projected to the xz plane, m
  };

 private:
  std::vector<char> stable_;              ///< the flags of the last call
  std::vector<BodyMarks> marks_;          ///< per body
  std::vector<BottomFace> bottom_;        ///< per body
  std::vector<VerticalContact> sorted_;   ///< L6's points, lowest first
  std::vector<Vec2> hullPoints_, hull_;   ///< the footnote rule's hull
};

}  // namespace boxsim
