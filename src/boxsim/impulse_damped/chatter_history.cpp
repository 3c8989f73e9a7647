/// \file
/// Chatter detected from history (\thesis{§6.3.1}): the envelope of a window's poses, the work
/// of gravity and the trend of the kinetic energy.
#include "boxsim/impulse_damped/chatter_history.hpp"

#include <algorithm>

#include "boxsim/filtering/envelope.hpp"

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
  // (1) The envelope of the envelope filter (\thesis{§5.5}) around the window's first pose.
  const Envelope envelope = Envelope::of(body.halfExtents, envelope_);
  for (const Sample& s : window)
    if (!envelope.contains(first.x, first.q, s.x, s.q)) return false;
  // (2) No work of gravity: the centre sank along g by no more than the slop.
  const double gNorm = g.norm();
  const double ell = body.halfExtents.minCoeff();
  if (gNorm > 0.0 && g.dot(window.back().x - first.x) / gNorm > slop_ * ell) return false;
  // (3) No energy gathered: the last step's no more than the largest of the first half.
  double firstHalf = 0.0;
  for (std::size_t k = 0; k < std::max<std::size_t>(1, window.size() / 2); ++k)
    firstHalf = std::max(firstHalf, window[k].energy);
  return window.back().energy <= firstHalf;
}

}  // namespace boxsim
