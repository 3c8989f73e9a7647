/// \file
/// One contact per touching pair, with its normal chosen by one of three models
/// (\thesis{§3.3.2} and its footnote): the separating-axis test's axis, the closest face kept
/// from the previous step (the thesis' choice), or the gradient of the box's object-space signed
/// distance (the improvement the footnote proposes, after Guendelman et al.'s signed distance).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/core/newtonian_impulse.hpp"
#include "boxsim/core/pair_table.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// A collision as COLLIDE sees it (\alg{COLLIDE L7} findContactPoint): one point and one normal
/// per pair of bodies.
struct ImpulseContact {
  int a = -1;                   ///< body index
  int b = -1;                   ///< body index, a < b
  Vec3 point = Vec3::Zero();    ///< m: the centroid of the pair's contact manifold
  Vec3 normal = Vec3::UnitY();  ///< unit, from a towards b
  double depth = 0.0;           ///< m, deepest penetration of the manifold (negative: a gap)
  /// m: the lever arm of the impulse on a, from a's centre to `point` where the contact was
  /// found (contact_gathering.hpp: at a's predicted pose, while COLLIDE sees a where it stands).
  Vec3 ra = Vec3::Zero();
  /// m: the same for b.
  Vec3 rb = Vec3::Zero();
  /// The pair's Coulomb friction (combinedFriction of the bodies'); frictionless in the
  /// thesis' scenes.
  Friction friction;
  /// With friction only: the contact patch about `point` (applyPatchFriction); empty for a
  /// frictionless contact.
  ContactPatch patch;
};

/// Signed distance of world point p from the surface of a box, m: negative inside. When
/// `gradient` is given it receives the unit outward gradient (inside: the normal of the nearest
/// face; outside: the direction from the nearest surface point).
double boxSignedDistance(const Obb& box, const Vec3& p, Vec3* gradient = nullptr);

/// Chooses contact normals and remembers, per pair, the closest face of the previous step.
class ContactNormalTracker {
 public:
  /// A tracker for the given model.
  explicit ContactNormalTracker(ContactNormalModel model = ContactNormalModel::PreviousClosestFace)
      : model_(model) {}

  /// One ImpulseContact per manifold, in the manifolds' order. Under PreviousClosestFace the
  /// normal is the current normal of the face that was closest to the pair in the previous step
  /// (when the pair touched then); the face found now is remembered for the next step. The
  /// lever arms are from the bodies' centres where they stand to the manifold's centroid.
  std::vector<ImpulseContact> contactsOf(const World& world,
                                         const std::vector<ContactManifold>& manifolds);
  /// Where one pair's faces sit in the tracker's tables in a step (contactOf), kept by the
  /// caller, one per pair: a default one, or one from an earlier step, is found afresh.
  struct FacePlaces {
    std::uint64_t step = 0;  ///< the tables' generation they were found in; 0: never
    int current = -1;        ///< the pair's place in this step's faces, -1: not remembered yet
    int previous = -1;       ///< its place in the previous step's faces, -1: none
  };
  /// The contact of one manifold, as contactsOf gives it; with `record` false the manifold's
  /// face is not remembered (see remember). `places`, when given, are the pair's own (m.a and
  /// m.b its bodies), kept by the caller: a pair asked for in every pass of a step is then
  /// looked up in the tables of faces once in the step, not in every pass; the same contact
  /// and the same face remembered.
  ImpulseContact contactOf(const World& world, const ContactManifold& m, bool record = true,
                           FacePlaces* places = nullptr);
  /// Remembers the face a touching pair's manifold was built on, for the next step
  /// (PreviousClosestFace; the other models remember nothing). Called once per pass a pair is
  /// gathered in; a pair remembered twice in a step keeps the later face. `places` as for
  /// contactOf.
  void remember(const World& world, const ContactManifold& m, FacePlaces* places = nullptr);

  /// Ends a step: the faces recorded during it become "the previous step's" faces.
  void endStep();

  /// The model in use.
  ContactNormalModel model() const { return model_; }

 private:
  /// A face of body a or b: its normal is sign · (column `axis` of that body's R).
  struct FaceRef {
    bool onB = false;
    int axis = 0;
    double sign = 1.0;
  };
  Vec3 signedDistanceNormal(const World& world, const ContactManifold& m) const;
  /// The contact of a manifold with the separating-axis normal: its point, lever arms, depth,
  /// friction and patch; the normal model's normal is set by the callers.
  static ImpulseContact baseContact(const World& world, const ContactManifold& m);
  /// The face a face manifold was built on, signed so that it points from a to b.
  static FaceRef faceOf(const World& world, const ContactManifold& m);
  /// `places` made the pair's (m.a, m.b) places in this step's tables, found afresh when they
  /// were found in another step (previous_ does not change within a step, and current_ only
  /// grows, so a place found in the step stays).
  void placesInStep(const ContactManifold& m, FacePlaces& places) const {
    if (places.step == generation_) return;
    places.step = generation_;
    places.current = -1;
    places.previous = static_cast<int>(previous_.placeOf(m.a, m.b));
  }
  /// Face f's normal where the bodies of m stand now.
  static Vec3 normalOf(const World& world, const ContactManifold& m, const FaceRef& f) {
    return f.sign * world.bodies[f.onB ? m.b : m.a].R.col(f.axis);
  }

  ContactNormalModel model_;
  /// The previous step's faces by pair (a, b).
  PairTable<FaceRef> previous_;
  /// The faces recorded in this step by pair; a pair recorded twice keeps the later face, as a
  /// map assignment would.
  PairTable<FaceRef> current_;
  /// Names the tables as they stand in this step, for FacePlaces: a new number, never 0, at
  /// construction and at every endStep (from one count shared by every tracker, so that places
  /// found with one tracker are never taken for another's).
  std::uint64_t generation_ = nextGeneration();
  static std::uint64_t nextGeneration();
};

}  // namespace boxsim
