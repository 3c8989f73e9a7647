/// \file
/// Whether a body's centre of mass lies over what supports it: the statics test that
/// DAMPENOBJECTS' rest-bringing steps are gated by (DampingParams::supportTest), the one-body
/// form of geometric stability's support hull (\thesis{§5.4}).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/collision/xz_hull.hpp"
#include "boxsim/core/pair_table.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim {

/// What counts as a body's support, and when a box lies face down on a face.
struct SupportTestParams {
  /// Unitless, in [0, 1): a contact supports the body it touches from below when its normal,
  /// pointing from the other body to this one, has a y component above this
  /// (SleepParams::supportNormalY, 0.1: side contacts do not support).
  double supportNormalY = 0.1;
  /// Degrees: a box lies on a face, and a body offers a face up, when one of its axes lies within
  /// this angle of y (DampingParams::alignedAngleDeg, the checkYAxisAlignment of
  /// \alg{DAMPENOBJECTS L3}).
  double alignedAngleDeg = 3.0;
  /// m, >= 0: a box's face touches another's where the gap between them lies within ± this (the
  /// margin the contacts were found with: the stepper passes the resting-contact margin,
  /// restingContactMargin, 3.2 mm for unit cubes at 60 Hz).
  double contactBand = 3.2e-3;
  /// m, >= 0: the top faces a box lies on are level when, over the patches it touches them on,
  /// their heights lie within this of each other: one horizontal plane (the contact margin,
  /// 1e-3 of a unit cube's half side, is what the stepper passes).
  double levelTolerance = 5e-4;
};

/// How one body stands on what supports it (centreOverSupport).
struct SupportVerdict {
  /// The xz projection of the centre of mass lies over the convex hull (in x, z) of the support
  /// region, within 1e-9 m.
  bool over = false;
  /// The body lies face down on top faces only, and they are level (over the patches it
  /// touches them on, within SupportTestParams::levelTolerance of one horizontal plane):
  /// turning it flat about its centre (\alg{DAMPENOBJECTS L10}) keeps it on every one of them.
  /// False with no support.
  bool level = false;
  /// Coulomb friction cannot hold the body where it lies (markFrictionSlides): DAMPENOBJECTS'
  /// rests (L6-L21) and its snap (L23-L28) leave it alone. Never set in a frictionless world.
  bool slides = false;
  /// Coulomb friction holds the body with the load on it where it lies, and supports that hold
  /// it bear at least half its weight (markFrictionSlides): only then do DAMPENOBJECTS' rests
  /// (L6-L21) and snap (L23-L28) act on a frictional body, and then whether or not it is `over`
  /// its support (held reads the centre of its whole load, `over` its own), and its vertical
  /// rest (L7-L9) as on a box lying flat. Never set in a frictionless world.
  bool held = false;
  /// A movable body it rests on slips under it (markFrictionSlides' dragSpeed): its friction
  /// drags it along, so DAMPENOBJECTS' rests leave its horizontal velocity alone (L11-L15 for x
  /// and z) and its snap (L23-L28) leaves its pose. Never set in a frictionless world.
  bool dragged = false;
  /// The body is held (above) and its supports reach an immovable body through held bodies: it
  /// rests on the ground, or on a held stack that does (markFrictionSlides), so it cannot move
  /// down, and DAMPENOBJECTS takes any downward velocity from it (L7-L9). Never set in a
  /// frictionless world.
  bool grounded = false;
};

/// For each body of `world` (one verdict per body, in body order), whether its centre of mass
/// lies over its support region, made from the manifolds of `contacts` (world indices, normals
/// from a to b, as findContacts returns them with a margin of about params.contactBand):
///  - a box lying face down (an axis within params.alignedAngleDeg of y) on a body that offers a
///    face up in the same sense contributes the patch where the two faces touch: their overlap
///    seen from above, where the gap between their planes lies within ±params.contactBand,
///    whatever the manifold holds. The narrow phase may give such a pair a single point (a
///    separating axis across two nearly parallel edges, an edge-edge contact), four of the
///    patch's up to eight corners, or a side face's axis (a corner near the rim of a face), and
///    none of these need hold the centre of a box resting on the patch;
///  - any other contact whose normal, pointing from the other body to this one, has y above
///    params.supportNormalY contributes its manifold's points (an edge or a corner on which the
///    box leans or balances); side contacts contribute nothing.
/// A region of one point or a segment (a box balanced on an edge line) holds only a centre on it.
/// A body with no support, and an immovable body, gets {false, false}.
/// Deterministic: a function of the bodies' poses and of the set of manifolds.
/// \thesis{§5.3} (the marks of a resting box), \thesis{§5.4} (its footnote's support hull);
/// DampingParams::supportTest says why DAMPENOBJECTS needs it.
std::vector<SupportVerdict> centreOverSupport(const World& world,
                                              const std::vector<ContactManifold>& contacts,
                                              const SupportTestParams& params = {});

/// centreOverSupport with its working memory kept from call to call, so that a stepper that
/// asks every step allocates nothing once the buffers have grown to the scene (a step of a
/// 343-box heap otherwise made some 11 000 small allocations here), and incremental: a body's
/// verdict is a function of its pose, its manifolds and the poses of the bodies they touch, so
/// it is worked out again only when one of those differs bitwise from the last call's (a body
/// the damping holds still, and its supports, keep theirs: \alg{DAMPENOBJECTS L23-L28}). The
/// same verdicts, bit for bit, as the function (tested against it, whatever was asked before).
class SupportTest {
 public:
  /// centreOverSupport(world, contacts, params); the reference stays valid until the next call.
  const std::vector<SupportVerdict>& operator()(const World& world,
                                                const std::vector<ContactManifold>& contacts,
                                                const SupportTestParams& params = {});
  /// Bodies whose verdict the last call worked out anew; the others kept the call before's.
  std::size_t reworked() const {
    return static_cast<std::size_t>(std::count(changed_.begin(), changed_.end(), 1));
  }

  /// A convex polygon of the xz plane with room for what clipping a box's face makes: a face's
  /// 4 corners, and one more for each of the 6 half planes it may be cut by.
  struct Polygon {
    std::array<Vec2, 12> points{};  ///< m, the first `count`, counter-clockwise
    std::size_t count = 0;          ///< vertices; 0 to 12
  };
  /// A face of a box whose outward normal lies within the aligned angle of +y or −y.
  struct LevelFace {
    Polygon outline;  ///< xz projection, counter-clockwise; empty: no such face
    Vec3 centre = Vec3::Zero();   ///< m
    Vec3 normal = Vec3::UnitY();  ///< outward, unit
    /// Height of the face's plane above the xz point p, m.
    double heightAt(const Vec2& p) const {
      return centre.y() -
             (normal.x() * (p.x() - centre.x()) + normal.z() * (p.y() - centre.z())) / normal.y();
    }
  };

 private:
  /// What a body's verdict reads of the body itself.
  struct Pose {
    Vec3 x = Vec3::Zero();
    Mat3 R = Mat3::Identity();
    Vec3 halfExtents = Vec3::Zero();
    bool immovable = false;
  };
  /// Sets changed_: the bodies whose verdict must be worked out again in this call.
  void markChanged(const World& world, const std::vector<ContactManifold>& contacts,
                   const SupportTestParams& params);

  bool asked_ = false;             ///< a call was made (the fields below hold it)
  SupportTestParams params_;       ///< the last call's
  std::vector<Pose> poses_;        ///< per body, at the last call
  std::vector<ContactManifold> last_;  ///< the last call's manifolds with points
  PairTable<int> lastOfPair_;      ///< (a, b) -> index into last_
  std::vector<int> touching_, lastTouching_;  ///< per body: manifolds with points, now and last
  std::vector<char> moved_;        ///< per body: its pose differs from the last call's
  std::vector<char> changed_;      ///< per body: its verdict is worked out in this call
  std::vector<LevelFace> faces_;  ///< per body, 2 i + up: its level faces, when found_
  std::vector<char> found_;
  std::vector<std::pair<int, Vec2>> points_;  ///< support points, tagged with their body
  std::vector<std::size_t> start_;            ///< per body, where its points begin in grouped_
  std::vector<Vec2> grouped_;                 ///< the support points, body by body
  std::vector<Vec2> hull_;                    ///< room for one body's hull
  std::vector<double> lowest_, highest_;      ///< per body, m
  std::vector<char> facesOnly_;               ///< per body
  std::vector<SupportVerdict> verdicts_;
};

/// Where box `upper` lies face down on box `lower`'s face up, seen from above (x and z, m,
/// counter-clockwise): the overlap of the two faces where the gap between their planes lies
/// within ± params.contactBand, when both boxes have an axis within params.alignedAngleDeg of y;
/// empty otherwise. The support region SupportTest takes for such a pair, whatever points the
/// narrow phase gave it.
SupportTest::Polygon levelContactPatch(const RigidBody& upper, const RigidBody& lower,
                                       const SupportTestParams& params);

}  // namespace boxsim
