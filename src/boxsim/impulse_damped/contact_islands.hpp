/// \file
/// Islands of the step's contact graph, for stopping the passes of \alg{A.2} island by island.
///
/// The graph's vertices are the bodies an impulse may move within the passes, its edges the
/// pairs that may touch in the step (the step's candidate pairs of ContactGathering,
/// OncePerStep). Immovable bodies, the ground say, join nothing: an impulse never moves them, so
/// nothing passes through them from one island to another. Bullet and ODE group bodies into
/// islands the same way, for their solvers and for sleeping.
///
/// Why a pass may stop for one island: a pass of RESOLVECOLLISIONS or RESOLVECONTACTS (\alg{A.2})
/// reads, for the contacts of an island, only the poses and momenta of its bodies (and of the
/// immovable ones, which do not change). When the pass leaves every momentum of the island as
/// it found it, the next pass predicts the same poses, finds the same contacts and would again
/// change nothing, so the island's later passes can be skipped with the same bits:
///
/// - RESOLVECOLLISIONS: every pass has the same restitution and gravity, so "no momentum of the
///   island changed" (IslandSettling::Unchanged) is enough.
/// - RESOLVECONTACTS: the restitution grows from pass to pass (\alg{RESOLVECONTACTS L5}), and
///   an approaching contact whose impulse rounded to no change might change something at the
///   next restitution, or wake a sleeper there. So the island must also have had no impulse
///   at all (IslandSettling::Unapproached): every contact separating or at rest, which does not
///   depend on the restitution. With the gravity trick a resting contact approaches by g Δt in
///   every pass, so a resting island never stops early; islands in flight or coming apart do.
///
/// An island that stopped is taken up again when the pairs grow during the step (an impulse sped
/// a body up past the bounds the candidates were found with) and join it to an active one:
/// before the join it could touch nothing of the other, after it it may.
///
/// A sleeping body stands in as immovable (\thesis{§4.5}), but a contact may wake it within a
/// pass (Sleeping::beforeCollide), and awake it carries impulses into every body it touches, in
/// that very pass. So its caller counts a sleeper among the bodies an impulse may move
/// (OncePerStepGathering::setSleepers): what may wake it and what it may then push are one
/// island, which settles only after a pass that changed none of it, waking included. Found in
/// Fig. 6.7's frictional clump, where a woken box pushed a column whose island had settled, and
/// the bits differed from the passes run for every island.
#pragma once

#include <cstddef>
#include <vector>

namespace boxsim {

/// Which passes of an island may be skipped after a pass (the file comment).
enum class IslandSettling {
  Never,        ///< every pass runs for every island (\alg{A.2} as written)
  Unchanged,    ///< RESOLVECOLLISIONS: after a pass that changed no momentum of the island
  Unapproached  ///< RESOLVECONTACTS: after a pass with no impulse and no change in the island
};

/// The islands of the movable bodies: a union–find over the pairs joined (path halving, union
/// by size, both deterministic), with per island whether it is settled (its remaining passes
/// of the current loop are skipped) and whether the current pass changed it.
class ContactIslands {
 public:
  /// One island per body (movable.size() of them), none settled; `movable[i]` false marks
  /// body i as one no impulse moves within the passes, which join() never joins (a sleeper,
  /// which may wake, counts as movable: the file comment).
  void reset(const std::vector<char>& movable);
  /// One island per body for n bodies, every one movable, none settled.
  void reset(std::size_t n);
  /// Joins the islands of bodies a and b (indices below the reset's size); does nothing when
  /// either is immovable. The joined island is settled only if both were.
  void join(int a, int b);
  /// Points every body straight at its island's root, so that the lookups of a pass (a few
  /// per contact) take one step until the next join.
  void flatten();
  /// Whether bodies a and b are in one island.
  bool together(int a, int b) { return root(a) == root(b); }
  /// Whether body i is movable and its island settled.
  bool settled(int i) { return movable_[static_cast<std::size_t>(i)] && settled_[root(i)]; }
  /// Marks the island of body i (if movable) as changed in the current pass.
  void markChanged(int i);
  /// Whether the island of body i is marked changed in the current pass (false if immovable).
  bool changed(int i) { return movable_[static_cast<std::size_t>(i)] && changed_[root(i)]; }
  /// Ends a pass: every active island not marked changed becomes settled; the marks clear.
  /// \return whether every island is now settled (the loop of passes can end).
  bool settleUnchanged();
  /// Every island active again (a new loop of passes begins).
  void activateAll();
  /// Bodies covered (the size of the last reset).
  std::size_t size() const { return parent_.size(); }

 private:
  /// The root of body i's island: one step after flatten(), rootFar otherwise.
  std::size_t root(int i) {
    const auto p = static_cast<std::size_t>(parent_[static_cast<std::size_t>(i)]);
    return parent_[p] == static_cast<int>(p) ? p : rootFar(p);
  }
  /// The root of the island of body k, halving the path on the way.
  std::size_t rootFar(std::size_t k);
  std::vector<int> parent_;
  std::vector<int> size_;
  std::vector<char> movable_;
  std::vector<char> settled_;  ///< per root
  std::vector<char> changed_;  ///< per root
};

}  // namespace boxsim
