/// \file
/// The slow-pair prediction of the once-per-step gathering (once_per_step_gathering.hpp): one
/// narrow phase per step at the current poses for the pairs of slow bodies (and of bodies
/// moving together), and in every pass the depth of each cached point at the predicted poses
/// by a Taylor expansion in the displacement:
///
///     depth' = depth + n · (d_a(p) - d_b(p)),
///     d(p) = Δt (v' + ω × r) + ½ Δt² ω × (ω × r),   r = p - x.
///
/// DEVIATION(RESOLVECOLLISIONS L2-L3, RESOLVECONTACTS L2-L3): these bodies are not moved
/// to their predicted poses; what differs is stated in once_per_step_gathering.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/collision/kept_narrow_phase.hpp"
#include "boxsim/collision/obb.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/step_bodies.hpp"

namespace boxsim {

/// What a pass reads of a cached pair before its points, kept apart from them (most pairs of a
/// pile stop here): its bodies and how near its points can come.
struct PairReach {
  int a;                 ///< body index, a < b
  int b;                 ///< body index
  int count;             ///< its points
  double deepest = 0.0;  ///< m, the largest depth of its points
  double leverA = 0.0;   ///< m, the largest |r_a| of its points
  double leverB = 0.0;   ///< m, the largest |r_b| of its points
};

/// The cached pairs of a step in increasing (a, b) order and their predicted contacts.
class SlowPairCache {
 public:
  /// `pairReach`: ImpulseParams::pairReach, whether pairs with a fast body that move together
  /// are cached too; `edgeCorners`: ImpulseParams::edgeCorners, whether an edge-edge pair keeps
  /// the corners of its best face beside its point (Alternate).
  explicit SlowPairCache(bool pairReach = true, bool edgeCorners = false)
      : pairReach_(pairReach), edgeCorners_(edgeCorners) {}

  /// Forgets every cached pair.
  void clear();
  /// Whether bodies i < j of `world` may be cached: both slow, or moving together
  /// (StepBodies::movingTogether, with pairReach on), and their bounds, each movable body's
  /// widened by `slowWidening` times its smallest half extent (more than a slow body can move in
  /// a pass), within `margin` (m). If so, `pairMargin` gets the margin of their narrow phase at
  /// the current poses, m: `margin` plus both widenings (add takes it).
  bool wanted(const World& world, const StepBodies& bodies, int i, int j, double margin,
              double slowWidening, double& pairMargin) const;
  /// Caches bodies i < j that wanted() accepted, given `m`, their narrow phase where they stand
  /// within `pairMargin` (m): if it finds them closer than that margin (a pair with a fast body
  /// needs manifold points besides), keeps the normal model's contact now and the manifold's
  /// points. Returns the pair's index in the cache, or -1 when it is not cached. Pairs must
  /// come in increasing (i, j) order.
  int add(const World& world, const StepBodies& bodies, int i, int j, double pairMargin,
          const ContactManifold& m, ContactNormalTracker& normals);

  /// The cached pairs' bodies and reach, in cache order.
  const std::vector<PairReach>& reaches() const { return reaches_; }
  /// Whether cached pair `reach` is predicted from the cache in this pass rather than gathered
  /// as written although it has a fast body: it has points, pairReach is on and its two bodies
  /// move together (StepBodies::movingTogether).
  bool predictedTogether(const StepBodies& bodies, const PairReach& reach) const {
    return reach.count > 0 && pairReach_ && bodies.movingTogether(reach.a, reach.b);
  }
  /// Cached pair k's contact in this pass, from its predicted points (an edge-edge pair's, or
  /// its corners', Alternate) or, with none to predict from, from the narrow phase where its
  /// slow bodies stand (the same in every pass of the step); false when none is within
  /// `margin` (m). With a predicted anchor (StepBodies::anchored) `world` is the bodies at
  /// their anchors (the cache's poses). Remembers its face in the normal model once while the
  /// pair stays slow. A narrow phase runs through `kept`.
  bool passContact(const World& world, const StepBodies& bodies, std::size_t k, double dt,
                   double margin,
                   ContactNormalTracker& normals, KeptNarrowPhase& kept, ImpulseContact& contact);
  /// Cached pair k is gathered as written in this pass (one of its bodies turned fast): what
  /// it remembered of its face comes after anything remembered before.
  void forgetFace(std::size_t k) {
    predicted_[k].remembered = false;
    if (predicted_[k].alternate >= 0)
      alternates_[static_cast<std::size_t>(predicted_[k].alternate)].predicted.remembered = false;
  }

 private:
  /// One manifold point as a pass reads it: its predicted depth is its depth plus a linear
  /// function of r_a, the same for every point of the pair (predictedContact).
  struct CachedPoint {
    Vec3 position;     ///< m, world, at the current pose
    double depth;      ///< m, along the manifold normal at the current pose
    Vec3 ra;           ///< p - x_a, m
  };
  /// What every pass reads of a cached pair to predict its contact besides its PairReach (its
  /// bodies and point count), kept apart from the rest (CachedPair) and its points kept one
  /// after another in points_: a pass walks the pairs in order and reads only these, a few
  /// cache lines a pair.
  struct PredictedPair {
    Vec3 normal;          ///< the manifold's normal, a to b (the direction depths are measured in)
    Vec3 contactNormal;   ///< the normal model's normal for the contact
    Friction friction;    ///< the contact's
    double patchRadius;   ///< m, the found contact's patch radius
    int first;            ///< its first point in points_
    bool remembered = false;  ///< its face was handed to the normal model since it last was fast
    /// With friction: how many of its points the found contact's patch holds (0 to 4) and which
    /// (their indices among the pair's points), in the order around the patch; kept here rather
    /// than with the patch itself, which no pass reads, so that predicting a frictional contact
    /// reads no more cache lines than a frictionless one.
    std::int8_t patchCount = 0;
    std::array<std::int8_t, 4> patchOrder{};  ///< see patchCount
    /// An edge-edge pair's corners of its best face (Alternate), or -1: none.
    int alternate = -1;
  };
  /// With ImpulseParams::edgeCorners, the corners of an edge-edge pair's best face, a second
  /// set of points with a normal of its own. An edge-edge manifold has one point, a material
  /// point of each edge, and says nothing of the corners a small relative turn brings down:
  /// the face axis (bestFaceAxis) clipped within the pair's margin gives the incident face's
  /// corners. Each pass takes one of the two contacts, the first of them that has a point
  /// within the margin: the edge point first, as the narrow phase chose it, unless the pair is
  /// nearly flush (its edge axis within about 8° of the face's normal, kFlushCosine), where the
  /// narrow phase's choice of edge or face rests on a few per cent of depth (its edge bias) and
  /// the corners are what the boxes rest on. Measured on the settling pile against the narrow
  /// phase at every pass' poses (contact_gathering_test): corners kept only for pairs not
  /// nearly flush miss nearly as many contacts as none at all, for the misses are nearly flush
  /// pairs; the edge point first for those too kept the shot frictional pyramid of 10 from
  /// sleeping, a resting pair switching between the two contacts from pass to pass.
  /// The face's clip is made when a pass first asks for the corners (most edge-edge pairs of a
  /// heap stay apart, or keep their edge point, and never do).
  struct Alternate {
    SeparatingAxisResult face;  ///< the best face axis at the cache's poses
    double clipMargin = 0.0;    ///< m, the pair's margin (SlowPairCache::add)
    bool first = false;         ///< tried before the edge point (nearly flush)
    bool built = false;         ///< the fields below are made
    PredictedPair predicted;    ///< its normal, contact normal, friction, points (alternate -1)
    PairReach reach;            ///< its bodies, points, deepest and levers
    ContactManifold manifold;   ///< the face clip (its face is what the normal model remembers)
  };
  /// |n_edge · n_face| above which an edge-edge pair counts as nearly flush (cos 8.1°).
  static constexpr double kFlushCosine = 0.99;
  /// One cached pair: what only the normal model and the narrow phase of a pair with no points
  /// read of it.
  struct CachedPair {
    /// The manifold at the current pose (its kind and normal name the face the normal model
    /// remembers).
    ContactManifold manifold;
    /// A pair with no point to predict from (count 0) gets the narrow phase where its slow
    /// bodies stand, the same in every pass of the step: its manifold, found in the first pass
    /// that needs it (index into exactManifolds_), or kExactUnknown.
    int exact = kExactUnknown;
  };
  static constexpr int kExactUnknown = -1;

  /// Whether a point of the cached pair `reach` may come within `margin` (m) in this pass:
  /// false only when predictedContact would find none.
  static bool mayTouch(const StepBodies& bodies, const PairReach& reach, double margin);
  /// The Taylor-predicted contact of the points of `pair` (`reach` its bodies and reach);
  /// false when no point is within `margin` (m).
  bool predictedContact(const World& world, const StepBodies& bodies, const PredictedPair& pair,
                        const PairReach& reach, double dt, double margin,
                        ImpulseContact& contact) const;
  /// Cached pair k's contact from its alternate corners (Alternate), asked before its edge point
  /// when nearly flush, else after the edge point found none: as passContact, remembering the
  /// face of the corners' clip; false when no corner comes within `margin` (m).
  bool alternateContact(const World& world, const StepBodies& bodies, std::size_t k, double dt,
                        double margin, ContactNormalTracker& normals, ImpulseContact& contact);
  /// Gives cached pair `pair` (bodies i, j) the corners of its best face within `pairMargin`
  /// (m) beside its edge-edge manifold (Alternate), to be clipped when first asked for.
  void addAlternate(const World& world, PredictedPair& pair, int i, int j, double pairMargin);
  /// Makes alternate `alternate` of cached pair k: its face's clip, its points and the normal
  /// model's contact, where the cache's bodies stand (`world`).
  void buildAlternate(const World& world, std::size_t k, Alternate& alternate,
                      ContactNormalTracker& normals);
  /// Writes the predicted pair and reach of manifold `m` (bodies i, j) with the normal model's
  /// contact `found`, its points appended to points_.
  void keepPoints(const World& world, const ContactManifold& m, int i, int j,
                  const ImpulseContact& found, PredictedPair& predicted, PairReach& reach);

  bool pairReach_;
  bool edgeCorners_;
  std::vector<CachedPair> pairs_;
  std::vector<PairReach> reaches_;  ///< per entry of pairs_, in its order
  std::vector<PredictedPair> predicted_;  ///< per entry of pairs_, in its order
  std::vector<CachedPoint> points_;  ///< the pairs' points, pair after pair (PredictedPair::first)
  std::vector<ContactManifold> exactManifolds_;  ///< the pairs' narrow phases (CachedPair::exact)
  std::vector<Alternate> alternates_;  ///< the edge-edge pairs' face corners (Alternate)
};

// Defined here, inlined into the merge of every pass (mergeSlowPairs), which asks it for each
// cached pair: for a pair found apart at once (mayTouch) the call cost more than the answer.
[[gnu::always_inline]] inline
bool SlowPairCache::passContact(const World& world, const StepBodies& bodies, std::size_t k,
                                double dt, double margin,
                                ContactNormalTracker& normals, KeptNarrowPhase& kept,
                                ImpulseContact& contact) {
  const PairReach& reach = reaches_[k];
  bool& remembered = predicted_[k].remembered;
  if (reach.count > 0) {
    // Too far apart for any point to come within the margin: no contact, as predictedContact
    // would find, without reading the points.
    const int alt = predicted_[k].alternate;
    if (alt >= 0 && alternates_[static_cast<std::size_t>(alt)].first &&
        alternateContact(world, bodies, k, dt, margin, normals, contact))
      return true;
    if (!mayTouch(bodies, reach, margin) ||
        !predictedContact(world, bodies, predicted_[k], reach, dt, margin, contact))
      return alt >= 0 && !alternates_[static_cast<std::size_t>(alt)].first &&
             alternateContact(world, bodies, k, dt, margin, normals, contact);
    // The bodies have not moved since the cache was built: its manifold names the face, the
    // same in every pass, so remembering it once is remembering it every pass.
    if (!remembered) normals.remember(world, pairs_[k].manifold);
    remembered = true;
    return true;
  }
  CachedPair& pair = pairs_[k];
  // No point to predict from: the narrow phase where the two slow bodies stand. Neither body
  // moved since the first pass that looked: the narrow phase answers as then.
  if (pair.exact == kExactUnknown) {
    pair.exact = static_cast<int>(exactManifolds_.size());
    exactManifolds_.push_back(kept.collide(reach.a, Obb::of(world.bodies[reach.a]), reach.b,
                                           Obb::of(world.bodies[reach.b]), margin));
    exactManifolds_.back().a = reach.a;
    exactManifolds_.back().b = reach.b;
  }
  const ContactManifold& m = exactManifolds_[static_cast<std::size_t>(pair.exact)];
  if (m.count == 0) return false;
  // Its face is remembered once while it stays slow, as the predicted pairs'.
  contact = normals.contactOf(world, m, !remembered);
  remembered = true;
  return true;
}

}  // namespace boxsim
