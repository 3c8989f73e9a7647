/// \file
/// The narrow phases of a step, kept: the separating-axis test of each pair of boxes
/// (separatingAxisTest, \thesis{§3.2}) remembered with the two poses it was run at, and handed
/// back instead of run again while both boxes stand exactly there.
///
/// A step of damped integration (\alg{A.2}) asks for the narrow phase of the same pair at the
/// same poses several times: FIXCONTACTCONSTRAINTS finds the contacts where the step leaves the
/// bodies (\alg{DAMPEDINTEGRATION L5}) and tests each contact again before it nudges; the next
/// step's once-per-step gathering finds them at its start, which are those very poses; a body
/// that DAMPENOBJECTS snapped (\alg{DAMPENOBJECTS L23-L28}) or that sleeps stands bitwise still
/// for many steps. The test depends on the two boxes alone (centre, axes, half extents), so a
/// kept result is the result the test would give, bit for bit: keeping changes no trajectory,
/// only the time (tested: collision_test.cpp against the test itself, determinism_test.cpp on
/// whole trajectories).
///
/// This is the first part of the persistent contacts of Bullet (btPersistentManifold) and
/// Jolt (ContactConstraintManager): those keep a pair's features while its relative pose moves
/// within a bound and so change the contacts a little; this keeps them only for the same
/// poses and changes nothing.
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/obb.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim {

/// The separating-axis tests of the pairs of one world, kept between calls and steps (the file
/// comment). Pairs are named by the body indices of their two boxes in the order the caller
/// passes them: (i, j) and (j, i) are kept apart, since the swapped test's result agrees with
/// the swapped result only up to the signs of zero components of the normal. Use:
/// axis() or collide() for every narrow phase, endStep() once per step. Results are those of
/// separatingAxisTest with default SeparatingAxisParams.
class KeptNarrowPhase {
 public:
  /// A store that keeps the tests it runs; with `keep` false it runs every test asked for and
  /// keeps none (the same results: for comparisons).
  explicit KeptNarrowPhase(bool keep = true) : keep_(keep) {}

  /// separatingAxisTest(a, b) for box a of body i and box b of body j (i != j, both >= 0):
  /// the kept result when both boxes are bitwise those of the last test of (i, j), else the
  /// test run now and kept.
  SeparatingAxisResult axis(int i, const Obb& a, int j, const Obb& b);
  /// collideBoxes(a, b, margin) with the test taken from axis(i, a, j, b); m, margin >= 0.
  /// The clip of the incident face is kept with the test (ClippedContact: it does not depend on
  /// the margin), so the pair's manifold for another margin at the same poses costs no clipping.
  /// A pair whose last test found it apart is first measured along that test's axis where it
  /// stands now (separatedBeyond): when that settles it, the manifold has no points, as the
  /// test's would, and its depth is the depth along that axis (<= -margin), not the test's;
  /// the test is not run. Fields a and b of the manifold are left at -1, as collideBoxes
  /// leaves them.
  ContactManifold collide(int i, const Obb& a, int j, const Obb& b, double margin);

  /// One narrow phase of a batch (collideAll): bodies i and j (i != j) where they stand, within
  /// `margin` (m, >= 0).
  struct Request {
    int i;          ///< body of the first box (the pair is kept in its list)
    int j;          ///< body of the second box
    double margin;  ///< m, >= 0
  };
  /// Runs item(k) once for every k in [0, count), in any order and on any threads, and returns
  /// when every call has: how a batch spreads its independent work (the techniques' threads,
  /// parallelFor). Empty: in order on the calling thread.
  using ItemLoop = std::function<void(int count, const std::function<void(int)>& item)>;
  /// The loop collideAll runs its rounds of tests through, for batches of `minRequests`
  /// requests or more; a smaller batch, and every batch without a loop (empty, the default), is
  /// answered by collide() request after request, which keeps each pair's data in the cache
  /// from its check to its answer.
  void setLoop(ItemLoop loop, std::size_t minRequests = 0) {
    loop_ = std::move(loop);
    loopMin_ = minRequests;
  }
  /// The requests of the next collideAll, emptied: fill it, then call collideAll. Kept in the
  /// store, so that a batch allocates nothing once the lists have grown to the scene.
  std::vector<Request>& newBatch() {
    batch_.clear();
    return batch_;
  }
  /// collide(r.i, box of r.i, r.j, box of r.j, r.margin) for every request r of the batch
  /// (newBatch), the boxes those of `world`'s bodies where they stand: visit(k, manifold) for
  /// each request k in order, on the calling thread. The same manifolds, and the same store and
  /// counts after it, as those calls one after another, provided no two requests name the same
  /// pair (i, j): a pair's answer depends on its own kept test alone, and the store's versions
  /// and entries are made in request order. The one-axis checks, the separating-axis tests and
  /// the clips, each pair's own, run in two rounds through the loop (setLoop); the bookkeeping
  /// runs on the calling thread. `visit` must not use the store.
  template <class Visit>
  void collideAll(const World& world, Visit&& visit) {
    if (!keep_ || !loop_ || batch_.size() < loopMin_) {
      for (std::size_t k = 0; k < batch_.size(); ++k) {
        const Request& r = batch_[k];
        visit(k, collide(r.i, Obb::of(world.bodies[static_cast<std::size_t>(r.i)]), r.j,
                         Obb::of(world.bodies[static_cast<std::size_t>(r.j)]), r.margin));
      }
      return;
    }
    runBatch(world);
    for (std::size_t k = 0; k < batch_.size(); ++k) visit(k, answer(k));
  }
  /// Ends a step: pairs not asked for in the step that ends are forgotten, so the store holds
  /// the pairs that are near now, not every pair that ever was.
  void endStep();

  /// Tests run since construction (the narrow phases this store did not spare).
  long tests() const { return tests_; }
  /// Tests handed back from the store since construction.
  long reuses() const { return reuses_; }
  /// Clips (clipContact) made since construction; the other manifolds of collide() came from a
  /// kept clip or had no points within their margin.
  long clips() const { return clips_; }
  /// Tests collide() spared by a one-axis check (separatedBeyond) since construction.
  long axisChecks() const { return axisChecks_; }

 private:
  /// What the store last saw of a body: its box, and a number that changes whenever the box
  /// does (bit for bit).
  struct Seen {
    Obb box;
    long version = 0;  ///< 0: never seen
  };
  /// A kept test of pair (i, j), in body i's list.
  struct Entry {
    int j;
    long step;      ///< one more than the step it was last asked for in
    long versionA;  ///< body i's version when it ran
    long versionB;  ///< body j's version when it ran
    SeparatingAxisResult result;
    bool clipped;   ///< its clip, at the same place in clips_'s list, is the test's
  };
  /// Body i's entry for (i, j) with boxes a and b, as a place in its list: the kept one when
  /// both boxes are bitwise those of its test (a reuse; `test` false), else one placed for a
  /// test to run now, its result still to be written (`test` true).
  int place(int i, const Obb& a, int j, const Obb& b, bool& test);
  /// Where body i's list holds pair (i, j), or -1.
  int find(int i, int j) const;
  /// place(), with the test run.
  int entry(int i, const Obb& a, int j, const Obb& b);
  /// Entry e of body i's list.
  Entry& at(int i, int e);
  /// Whether pair (i, j) was apart at its last test and still is beyond `margin` along that
  /// test's axis (separatedBeyond): then `e` is its entry and `depth` the depth along the axis.
  bool apartAlong(int i, const Obb& a, int j, const Obb& b, double margin, int& e,
                  double& depth) const;
  /// The manifold of a pair settled by apartAlong, with no points, counted as a one-axis check.
  ContactManifold apartManifold(int i, int e, double depth);
  /// Clips entry e of body i (boxes a and b) when its test is within `margin` and it is not
  /// clipped yet; whether it did.
  bool clipWithin(int i, int e, const Obb& a, const Obb& b, double margin);
  /// The manifold of entry e of body i within `margin`: from its clip (clipWithin made it), or
  /// none when its test is apart beyond the margin.
  ContactManifold manifoldOf(int i, int e, const Obb& a, const Obb& b, double margin);
  /// Body `body`'s version for `box`: the one it had if the box is bitwise the last seen, else
  /// a new one.
  long versionOf(int body, const Obb& box);
  /// Box of body i of the batch's world.
  Obb boxOf(int i) const { return Obb::of(world_->bodies[static_cast<std::size_t>(i)]); }
  /// collideAll's rounds, up to the answers: afterwards answer(k) is request k's.
  void runBatch(const World& world);
  /// Request k's manifold, once runBatch has run: to be asked once per request, in order.
  ContactManifold answer(std::size_t k);
  /// item(k) for k in [0, count) through the loop (setLoop).
  void run(std::size_t count, void (KeptNarrowPhase::*item)(std::size_t));
  /// Round one for request k: apart along its last test's axis?
  void checkAxis(std::size_t k);
  /// Round two for the w-th request of work_: its test and clip, into its entry.
  void testAndClip(std::size_t w);

  /// What collideAll knows of a request between its rounds.
  struct Pending {
    enum : char { Apart, Kept, Test } state = Test;  ///< settled by one axis, handed back, run
    bool clipped = false;  ///< its clip was made in this batch
    int entry = -1;        ///< its entry's place in body i's list (-1 in the first round: none)
    double depth = 0.0;    ///< m, Apart: the depth along the last test's axis
  };
  std::vector<Pending> pending_;  ///< collideAll's, per request (kept: no allocation per batch)
  std::vector<int> work_;         ///< collideAll's requests with a test or a clip to make
  std::vector<Request> batch_;    ///< the next collideAll's requests (newBatch)
  ItemLoop loop_;                 ///< collideAll's rounds (setLoop)
  std::size_t loopMin_ = 0;       ///< the fewest requests a batch runs through loop_ with
  const World* world_ = nullptr;  ///< the world of the batch being run
  void (KeptNarrowPhase::*item_)(std::size_t) = nullptr;  ///< the round run() runs

  /// Per body i, the tests of the pairs (i, j) kept, in the order they were first asked for.
  /// A step asks for a body's pairs together (pairs come sorted by body), so a lookup reads one
  /// short list that is already in the cache, where a table by pair would read a random slot.
  std::vector<std::vector<Entry>> kept_;
  /// Per body i, the clips of its entries, place for place (apart: a lookup reads the entries
  /// alone, and a clip is ten times an entry).
  std::vector<std::vector<ClippedContact>> clipsOf_;
  std::vector<Seen> seen_;  ///< per body
  long versions_ = 0;       ///< the last version handed out
  bool keep_;
  long step_ = 0;
  long tests_ = 0;
  long reuses_ = 0;
  long clips_ = 0;
  long axisChecks_ = 0;
};

}  // namespace boxsim
