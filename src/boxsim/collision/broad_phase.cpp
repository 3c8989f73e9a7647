/// \file
/// The broad phase: which pairs of bodies the narrow phase looks at (\thesis{§4.1}: the
/// thesis' scenes were small enough to need no spatial subdivision). The all-pairs test runs
/// two nested loops; sweep and prune (sweep_and_prune.cpp) finds the same pairs by sorting.
/// Either way pairs come out in increasing (i, j) order: no hashing, no pointer order, so the
/// narrow phase, and everything after it, sees the same pairs in the same order on every run
/// and with either broad phase. Which one runs is the world's choice (World::broadPhase).
#include "boxsim/collision/broad_phase.hpp"

#include <algorithm>
#include <stdexcept>

#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/collision/sweep_and_prune.hpp"

namespace boxsim {

std::string broadPhaseName(BroadPhase kind) { return enumName(kBroadPhaseNames, kind); }

BroadPhase parseBroadPhase(const std::string& name) {
  return parseEnum(kBroadPhaseNames, name, "broad phase");
}

void obbBounds(const Obb& box, double margin, Vec3& lo, Vec3& hi) {
  boundsAbout(box.center, obbReach(box), margin, lo, hi);
}

namespace {

/// The all-pairs broad phase on given bounds: every pair tested, in increasing (i, j) order.
std::vector<std::pair<int, int>> allPairs(const World& world, const std::vector<Vec3>& lo,
                                          const std::vector<Vec3>& hi, double margin) {
  const int n = static_cast<int>(world.bodies.size());
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      // Two immovable bodies (ground and wall) never need a contact between them.
      if (world.bodies[i].immovable && world.bodies[j].immovable) continue;
      if (boundsWithin(lo[i], hi[i], lo[j], hi[j], margin)) pairs.emplace_back(i, j);
    }
  }
  return pairs;
}

}  // namespace

std::vector<std::pair<int, int>> candidatePairs(const World& world, double margin) {
  const int n = static_cast<int>(world.bodies.size());
  std::vector<Vec3> lo(n), hi(n);
  for (int i = 0; i < n; ++i) obbBounds(Obb::of(world.bodies[i]), 0.0, lo[i], hi[i]);
  return candidatePairs(world, lo, hi, margin);
}

std::vector<std::pair<int, int>> candidatePairs(const World& world, const std::vector<Vec3>& lo,
                                                const std::vector<Vec3>& hi, double margin) {
  if (world.broadPhase == BroadPhase::SweepAndPrune)
    return sweepAndPrunePairs(world, lo, hi, margin);
  if (lo.size() != world.bodies.size() || hi.size() != world.bodies.size())
    throw std::invalid_argument("candidatePairs: give one pair of bounds per body");
  return allPairs(world, lo, hi, margin);
}

void candidatePairs(const World& world, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                    double margin, SweepAndPrune& sweep, std::vector<std::pair<int, int>>& pairs) {
  if (world.broadPhase == BroadPhase::SweepAndPrune) return sweep.pairs(world, lo, hi, margin, pairs);
  pairs = candidatePairs(world, lo, hi, margin);
}

namespace {
/// visit(i, j, manifold) for each pair (i, j) of `pairs` (with moved[i] or moved[j] when
/// `moved` is given, else every pair) in order: collideBoxes of bodies i and j where they stand
/// within `margin`, through the store's batch when there is one (KeptNarrowPhase::collideAll,
/// whose tests may run on several threads).
template <class Visit>
void narrowPhases(const World& world, double margin, const std::vector<std::pair<int, int>>& pairs,
                  const std::vector<char>* moved, KeptNarrowPhase* kept, Visit&& visit) {
  const auto wanted = [moved](int i, int j) { return !moved || (*moved)[i] || (*moved)[j]; };
  if (kept) {
    std::vector<KeptNarrowPhase::Request>& batch = kept->newBatch();
    for (const auto& [i, j] : pairs)
      if (wanted(i, j)) batch.push_back({i, j, margin});
    kept->collideAll(world, [&](std::size_t k, const ContactManifold& found) {
      visit(batch[k].i, batch[k].j, found);
    });
    return;
  }
  for (const auto& [i, j] : pairs)
    if (wanted(i, j))
      visit(i, j, collideBoxes(Obb::of(world.bodies[i]), Obb::of(world.bodies[j]), margin));
}

/// Appends the manifold `found` of pair (i, j) to `contacts` when it has points.
void addContact(int i, int j, const ContactManifold& found, std::vector<ContactManifold>& contacts) {
  if (found.count == 0) return;
  ContactManifold& m = contacts.emplace_back(found);
  m.a = i;
  m.b = j;
}
}  // namespace

namespace {
/// Room for at least `count` manifolds in `contacts`, grown at least twofold when it must grow:
/// a list refilled every step for a heap that keeps gathering pairs would otherwise move to a
/// new block (fresh pages from the system) at nearly every step.
void reserveAtLeast(std::vector<ContactManifold>& contacts, std::size_t count) {
  if (contacts.capacity() < count) contacts.reserve(std::max(count, 2 * contacts.capacity()));
}
}  // namespace

std::vector<ContactManifold> findContacts(const World& world, double margin) {
  return findContacts(world, margin, candidatePairs(world, margin));
}

std::vector<ContactManifold> findContacts(const World& world, double margin,
                                          const std::vector<std::pair<int, int>>& pairs,
                                          KeptNarrowPhase* kept) {
  std::vector<ContactManifold> contacts;
  findContacts(world, margin, pairs, kept, contacts);
  return contacts;
}

void findContacts(const World& world, double margin, const std::vector<std::pair<int, int>>& pairs,
                  KeptNarrowPhase* kept, std::vector<ContactManifold>& contacts) {
  // Room for every candidate at once: in the scenes that make this costly, stacks at rest,
  // nearly every candidate touches, and growing the vector step by step would copy each
  // manifold several times.
  contacts.clear();
  reserveAtLeast(contacts, pairs.size());
  narrowPhases(world, margin, pairs, nullptr, kept,
               [&contacts](int i, int j, const ContactManifold& found) {
                 addContact(i, j, found, contacts);
               });
}

bool pairIntersects(const World& world, int i, int j, double tolerance) {
  return separatingAxisTest(Obb::of(world.bodies[i]), Obb::of(world.bodies[j])).depth > tolerance;
}

std::pair<int, int> firstIntersectingPair(const World& world, double tolerance,
                                          const PairFilter& skip) {
  // A negative tolerance asks about boxes closer than -tolerance, so widen the reject to match.
  for (const std::pair<int, int>& p : candidatePairs(world, std::max(0.0, -tolerance)))
    if (pairIntersects(world, p.first, p.second, tolerance) &&
        !(skip && skip(world, p.first, p.second)))
      return p;
  return {-1, -1};
}

namespace {
/// Up to this many moved bodies, refindContacts tests each against every body (O(n) apiece)
/// instead of running the whole broad phase (a sweep costs about as much as this many).
constexpr std::size_t kMaxDirectlyRefound = 64;

/// The pairs of candidatePairs(world, margin) with a moved body, in the same order, into
/// lists.pairs: each moved body tested against every other by the broad phases' own test on the
/// bounds in lists.lo and lists.hi.
void movedPairs(const World& world, double margin, const std::vector<char>& moved,
                BroadPhaseLists& lists) {
  const int n = static_cast<int>(world.bodies.size());
  const std::vector<Vec3>& lo = lists.lo;
  const std::vector<Vec3>& hi = lists.hi;
  std::vector<std::pair<int, int>>& pairs = lists.pairs;
  pairs.clear();
  for (int i : lists.movedBodies)
    for (int j = 0; j < n; ++j) {
      // A pair of two moved bodies once, from its lower index.
      if (j == i || (moved[j] && j < i)) continue;
      if (world.bodies[i].immovable && world.bodies[j].immovable) continue;
      if (boundsWithin(lo[i], hi[i], lo[j], hi[j], margin))
        pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
  std::sort(pairs.begin(), pairs.end());
}
}  // namespace

std::vector<ContactManifold> refindContacts(const World& world, double margin,
                                            const std::vector<ContactManifold>& before,
                                            const std::vector<char>& moved,
                                            KeptNarrowPhase* kept) {
  BroadPhaseLists lists;
  std::vector<ContactManifold> contacts;
  refindContacts(world, margin, before, moved, kept, lists, contacts);
  return contacts;
}

void refindContacts(const World& world, double margin, const std::vector<ContactManifold>& before,
                    const std::vector<char>& moved, KeptNarrowPhase* kept, BroadPhaseLists& lists,
                    std::vector<ContactManifold>& contacts,
                    const std::vector<std::pair<int, int>>* pairs) {
  if (moved.size() != world.bodies.size())
    throw std::invalid_argument("refindContacts: give one moved flag per body");
  contacts.clear();
  reserveAtLeast(contacts, before.size());
  std::size_t k = 0;
  // Both lists in increasing (a, b) order: merge the kept manifolds with the new ones.
  const auto keepBefore = [&](const std::pair<int, int>& until) {
    for (; k < before.size() && std::make_pair(before[k].a, before[k].b) < until; ++k)
      if (!moved[before[k].a] && !moved[before[k].b]) contacts.push_back(before[k]);
  };
  lists.movedBodies.clear();
  for (std::size_t i = 0; i < moved.size(); ++i)
    if (moved[i]) lists.movedBodies.push_back(static_cast<int>(i));
  // Only the pairs with a moved body are looked at: with few moved bodies, finding just those
  // is cheaper than the whole broad phase, and gives the same pairs in the same order. With the
  // broad phase's answer given, they are picked from it.
  if (!pairs) {
    const std::size_t n = world.bodies.size();
    lists.lo.resize(n);
    lists.hi.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      obbBounds(Obb::of(world.bodies[i]), 0.0, lists.lo[i], lists.hi[i]);
    if (lists.movedBodies.size() <= kMaxDirectlyRefound)
      movedPairs(world, margin, moved, lists);
    else
      candidatePairs(world, lists.lo, lists.hi, margin, lists.sweep, lists.pairs);
  }
  narrowPhases(world, margin, pairs ? *pairs : lists.pairs, &moved, kept,
               [&](int i, int j, const ContactManifold& found) {
                 keepBefore({i, j});
                 addContact(i, j, found, contacts);
               });
  keepBefore({static_cast<int>(world.bodies.size()), 0});
}

double deepestPenetration(const World& world) {
  double deepest = 0.0;
  for (const std::pair<int, int>& p : candidatePairs(world))
    deepest = std::max(deepest, separatingAxisTest(Obb::of(world.bodies[p.first]),
                                                   Obb::of(world.bodies[p.second])).depth);
  return deepest;
}

}  // namespace boxsim
