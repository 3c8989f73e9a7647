#include "boxsim/filtering/trajectory_measures.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/filtering/box_filter.hpp"
#include "boxsim/filtering/envelope.hpp"
#include "boxsim/filtering/orientation_average.hpp"

namespace boxsim {

namespace {

void requireWindow(const Trajectory& t, FrameWindow w, std::size_t minFrames) {
  if (w.begin >= w.end || w.end > t.frames.size() || w.end - w.begin < minFrames)
    throw std::invalid_argument("frame window [" + std::to_string(w.begin) + ", " +
                                std::to_string(w.end) + ") must hold at least " +
                                std::to_string(minFrames) + " of the trajectory's " +
                                std::to_string(t.frames.size()) + " frames");
}

void requireBodies(const Trajectory& t, const std::vector<std::size_t>& bodies) {
  for (std::size_t b : bodies)
    if (b >= t.bodies.size())
      throw std::invalid_argument("body index " + std::to_string(b) + " is out of range; the trajectory has " +
                                  std::to_string(t.bodies.size()) + " bodies");
}

Obb boxOf(const Trajectory& t, std::size_t frame, std::size_t body) {
  const TrajectoryFrame& f = t.frames[frame];
  return Obb{f.x[body], f.q[body].toRotationMatrix(), t.bodies[body].halfExtents};
}

}  // namespace

FrameWindow frameWindow(const Trajectory& trajectory, double t0, double t1) {
  FrameWindow w{trajectory.frames.size(), 0};
  for (std::size_t k = 0; k < trajectory.frames.size(); ++k) {
    const double t = trajectory.frames[k].t;
    if (t >= t0 - 1e-9 && t <= t1 + 1e-9) {
      w.begin = std::min(w.begin, k);
      w.end = k + 1;
    }
  }
  if (w.begin >= w.end || w.end - w.begin < 3) {
    const std::string span =
        trajectory.frames.empty()
            ? "no frames"
            : shortestText(trajectory.frames.front().t) + " .. " + shortestText(trajectory.frames.back().t) + " s";
    throw std::invalid_argument("the interval [" + shortestText(t0) + ", " + shortestText(t1) +
                                "] s holds fewer than 3 frames of the run (" + span +
                                "); choose an interval inside the run");
  }
  return w;
}

std::vector<std::size_t> restingBodies(const Trajectory& raw, FrameWindow window,
                                       const RestingParams& params) {
  requireWindow(raw, window, 1);
  std::vector<std::size_t> resting;
  const TrajectoryFrame& first = raw.frames[window.begin];
  for (std::size_t b = 0; b < raw.bodies.size(); ++b) {
    if (raw.bodies[b].immovable) continue;
    const Envelope envelope(params.displacementFraction * raw.bodies[b].halfExtents.minCoeff(),
                           params.angle);
    bool rests = true;
    for (std::size_t k = window.begin; k < window.end && rests; ++k) {
      const TrajectoryFrame& f = raw.frames[k];
      rests = envelope.contains(first.x[b], first.q[b], f.x[b], f.q[b]);
    }
    if (rests) resting.push_back(b);
  }
  return resting;
}

std::vector<std::size_t> movableBodies(const Trajectory& trajectory) {
  std::vector<std::size_t> movable;
  for (std::size_t b = 0; b < trajectory.bodies.size(); ++b)
    if (!trajectory.bodies[b].immovable) movable.push_back(b);
  return movable;
}

MotionMeasures motionMeasures(const Trajectory& displayed, FrameWindow window,
                              const std::vector<std::size_t>& bodies, const MeasureParams& params) {
  requireWindow(displayed, window, 3);
  requireBodies(displayed, bodies);
  MotionMeasures m;
  m.bodies = bodies.size();
  if (bodies.empty()) return m;
  const std::vector<TrajectoryFrame>& f = displayed.frames;

  // Chatter: second differences over the window's inner frames.
  double sumX = 0.0, sumQ = 0.0;
  std::size_t samples = 0;
  for (std::size_t b : bodies) {
    for (std::size_t k = window.begin + 1; k + 1 < window.end; ++k) {
      sumX += (f[k + 1].x[b] - 2.0 * f[k].x[b] + f[k - 1].x[b]).squaredNorm();
      const Vec3 after = rotationVector(f[k].q[b], f[k + 1].q[b]);
      const Vec3 before = rotationVector(f[k - 1].q[b], f[k].q[b]);
      sumQ += (after - before).squaredNorm();
      ++samples;
    }
  }
  m.chatterPosition = sumX / static_cast<double>(samples);
  m.chatterAngle = sumQ / static_cast<double>(samples);

  // Squirm: path length per second of the low-passed poses.
  BoxFilterParams lowPass;
  lowPass.halfWidth = params.squirmHalfWidth;
  const Trajectory slow = boxFilter(displayed, lowPass);
  const double seconds = f[window.end - 1].t - f[window.begin].t;
  double pathX = 0.0, pathQ = 0.0, shownX = 0.0, shownQ = 0.0;
  for (std::size_t b : bodies) {
    for (std::size_t k = window.begin + 1; k < window.end; ++k) {
      pathX += (slow.frames[k].x[b] - slow.frames[k - 1].x[b]).norm();
      pathQ += rotationAngle(slow.frames[k - 1].q[b], slow.frames[k].q[b]);
      shownX += (f[k].x[b] - f[k - 1].x[b]).norm();
      shownQ += rotationAngle(f[k - 1].q[b], f[k].q[b]);
    }
  }
  const double perBodySecond = static_cast<double>(bodies.size()) * seconds;
  m.squirmPosition = pathX / perBodySecond;
  m.squirmAngle = pathQ / perBodySecond;
  m.displayedSpeedPosition = shownX / perBodySecond;
  m.displayedSpeedAngle = shownQ / perBodySecond;
  return m;
}

PopMeasure pops(const Trajectory& displayed, FrameWindow window, const std::vector<std::size_t>& bodies) {
  requireWindow(displayed, window, 2);
  requireBodies(displayed, bodies);
  PopMeasure p;
  for (std::size_t b : bodies) {
    for (std::size_t k = window.begin + 1; k < window.end; ++k) {
      const TrajectoryFrame& f0 = displayed.frames[k - 1];
      const TrajectoryFrame& f1 = displayed.frames[k];
      p.position = std::max(p.position, (f1.x[b] - f0.x[b]).norm());
      p.angle = std::max(p.angle, rotationAngle(f0.q[b], f1.q[b]));
    }
  }
  return p;
}

namespace {

/// Visits every pair (a < b, not both immovable) of `t`'s bodies in the window's frames whose
/// bounding spheres meet in frame k of `t` or of `other`, as visit(k, a, b, boxBox).
template <class Visit>
void forNearPairs(const Trajectory& t, const Trajectory& other, FrameWindow window, Visit visit) {
  const std::size_t n = t.bodies.size();
  std::vector<double> reach(n);
  for (std::size_t b = 0; b < n; ++b) reach[b] = t.bodies[b].halfExtents.norm();
  for (std::size_t k = window.begin; k < window.end; ++k) {
    const TrajectoryFrame& f = t.frames[k];
    const TrajectoryFrame& g = other.frames[k];
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = a + 1; b < n; ++b) {
        const bool immovableA = t.bodies[a].immovable;
        const bool immovableB = t.bodies[b].immovable;
        if (immovableA && immovableB) continue;
        if ((f.x[a] - f.x[b]).norm() > reach[a] + reach[b] &&
            (g.x[a] - g.x[b]).norm() > reach[a] + reach[b])
          continue;
        visit(k, a, b, !immovableA && !immovableB);
      }
    }
  }
}

double depthOf(const Trajectory& t, std::size_t k, std::size_t a, std::size_t b) {
  return std::max(0.0, separatingAxisTest(boxOf(t, k, a), boxOf(t, k, b)).depth);
}

}  // namespace

OverlapMeasure deepestOverlap(const Trajectory& trajectory, FrameWindow window) {
  requireWindow(trajectory, window, 1);
  OverlapMeasure o;
  forNearPairs(trajectory, trajectory, window, [&](std::size_t k, std::size_t a, std::size_t b, bool boxBox) {
    double& deepest = boxBox ? o.boxBox : o.boxGround;
    deepest = std::max(deepest, depthOf(trajectory, k, a, b));
  });
  return o;
}

OverlapMeasure overlapIntroduced(const Trajectory& raw, const Trajectory& displayed, FrameWindow window) {
  if (raw.frames.size() != displayed.frames.size() || raw.bodies.size() != displayed.bodies.size())
    throw std::invalid_argument("overlapIntroduced compares a filtered run with its raw run: they must "
                                "have the same frames and bodies");
  requireWindow(displayed, window, 1);
  OverlapMeasure o;
  forNearPairs(displayed, raw, window, [&](std::size_t k, std::size_t a, std::size_t b, bool boxBox) {
    double& worst = boxBox ? o.boxBox : o.boxGround;
    worst = std::max(worst, depthOf(displayed, k, a, b) - depthOf(raw, k, a, b));
  });
  return o;
}

PeakAcceleration peakAcceleration(const Trajectory& trajectory, FrameWindow window,
                                  const std::vector<std::size_t>& bodies) {
  requireWindow(trajectory, window, 3);
  requireBodies(trajectory, bodies);
  PeakAcceleration a;
  const std::vector<TrajectoryFrame>& f = trajectory.frames;
  for (std::size_t k = window.begin + 1; k + 1 < window.end; ++k) {
    const double h0 = f[k].t - f[k - 1].t;
    const double h1 = f[k + 1].t - f[k].t;
    const double h = 0.5 * (h0 + h1);
    for (std::size_t b : bodies) {
      const Vec3 v0 = (f[k].x[b] - f[k - 1].x[b]) / h0;
      const Vec3 v1 = (f[k + 1].x[b] - f[k].x[b]) / h1;
      a.linear = std::max(a.linear, (v1 - v0).norm() / h);
      const Vec3 w0 = rotationVector(f[k - 1].q[b], f[k].q[b]) / h0;
      const Vec3 w1 = rotationVector(f[k].q[b], f[k + 1].q[b]) / h1;
      a.angular = std::max(a.angular, (w1 - w0).norm() / h);
    }
  }
  return a;
}

}  // namespace boxsim
