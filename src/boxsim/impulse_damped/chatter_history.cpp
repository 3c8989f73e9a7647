/// \file
/// Chatter detected from history (\thesis{§6.3.1}): the envelope of a window's poses, the work
/// of gravity and the trend of the kinetic energy.
#include "boxsim/impulse_damped/chatter_history.hpp"

#include <algorithm>

namespace boxsim {

void ChatterHistory::resize(std::size_t n) { bodies_.resize(n); }

void ChatterHistory::reset(std::size_t i) {
  if (i < bodies_.size()) bodies_[i] = Body{};
}

void ChatterHistory::record(std::size_t i, const RigidBody& body, const Vec3& g, long window) {
  Body& h = bodies_[i];
  h.window.push_back(Sample{body.s.x, body.s.q, body.kineticEnergy()});
  while (static_cast<long>(h.window.size()) > window) h.window.erase(h.window.begin());
  h.chatters = static_cast<long>(h.window.size()) == window && judge(h.window, body, g);
}

bool ChatterHistory::judge(const std::vector<Sample>& window, const RigidBody& body,
                           const Vec3& g) const {
  const Sample& first = window.front();
  // (1) The envelope of the envelope filter (\thesis{§5.5}): r = envelope ℓ for the centre, r / h
  // for the orientation. The turn from the first pose, d = q₀* q, has |d.vec| = sin(θ/2) <= θ/2,
  // so comparing it with r / (2h) needs only a square root (the same bits everywhere,
  // docs/web.md) and lets through at most the turn whose half-angle sine is r / (2h).
  const double ell = body.halfExtents.minCoeff();
  const double r = envelope_ * ell, halfTurn = r / (2.0 * body.halfExtents.norm());
  for (const Sample& s : window)
    if ((s.x - first.x).norm() > r || (first.q.conjugate() * s.q).vec().norm() > halfTurn)
      return false;
  // (2) No work of gravity: the centre sank along g by no more than the slop.
  const double gNorm = g.norm();
  if (gNorm > 0.0 && g.dot(window.back().x - first.x) / gNorm > slop_ * ell) return false;
  // (3) No energy gathered: the last step's no more than the largest of the first half.
  double firstHalf = 0.0;
  for (std::size_t k = 0; k < std::max<std::size_t>(1, window.size() / 2); ++k)
    firstHalf = std::max(firstHalf, window[k].energy);
  return window.back().energy <= firstHalf;
}

}  // namespace boxsim
