/// \file
/// The shot pyramids' impact under every engine (peer_impact.hpp).
#include "peer_impact.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace boxsim::peers {

namespace {
/// kg m/s: Σ m v of the target's boxes (every movable box but the projectile).
Vec3 targetMomentum(const PeerScene& scene, const std::vector<PeerPose>& poses, int projectile) {
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = 0; i < poses.size(); ++i)
    if (static_cast<int>(i) != projectile && !scene.boxes[i].immovable)
      sum += scene.boxes[i].mass * poses[i].v;
  return sum;
}
}  // namespace

ImpactMeasures measureImpact(const SceneSpec& spec, PeerEngine& engine, double dt) {
  const PeerScene scene = peerSceneOf(spec);
  int projectile = -1;
  for (std::size_t i = 0; i < scene.boxes.size(); ++i) {
    if (scene.boxes[i].launchTime < 0.0) continue;
    if (projectile >= 0)
      throw std::invalid_argument(spec.label() + ": more than one launched box; the impact page "
                                  "needs one projectile");
    projectile = static_cast<int>(i);
  }
  if (projectile < 0)
    throw std::invalid_argument(spec.label() +
                                ": no launched box; the impact page needs a shot scene");
  const double launch = scene.boxes[static_cast<std::size_t>(projectile)].launchTime;
  engine.load(scene);
  ImpactMeasures m;
  std::vector<PeerPose> poses, previous, start;
  const std::size_t shot = static_cast<std::size_t>(projectile);
  long impactStep = -1;
  const long steps = std::lround(spec.duration / dt);
  for (long k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k - 1) * dt;
    // The target as it stands when the projectile leaves.
    if (start.empty() && t + 1e-9 * dt >= launch) engine.read(start);
    engine.step(dt, t);
    previous.swap(poses);
    engine.read(poses);
    if (start.empty() || previous.empty()) continue;
    if (impactStep >= 0) {
      if (k == impactStep + 3)
        m.struckSpeedLater = poses[static_cast<std::size_t>(m.struckBody)].v.norm();
      continue;
    }
    // In flight the projectile's velocity changes by g Δt a step; the impact changes it by more.
    const Vec3 flight = previous[shot].v + dt * scene.gravity;
    if (!(previous[shot].v.norm() > 0.0) || (poses[shot].v - flight).norm() <= kImpactSpeed)
      continue;
    impactStep = k;
    m.found = true;
    m.time = static_cast<double>(k) * dt;
    double largest = 0.0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (i == shot || scene.boxes[i].immovable) continue;
      // Set moving by the impact: its velocity changed by more than kImpactSpeed in the step (a
      // target that was not at rest, the plain impulse step's chattering pyramid, counts so too).
      const double change = (poses[i].v - previous[i].v).norm();
      if (change > kImpactSpeed) ++m.moving;
      if (change > largest) largest = change, m.struckBody = static_cast<int>(i);
    }
    if (m.struckBody >= 0) m.struckSpeed = poses[static_cast<std::size_t>(m.struckBody)].v.norm();
    m.projectileBefore = previous[shot].v.norm();
    m.projectileAfter = poses[shot].v.norm();
    m.delivered = (targetMomentum(scene, poses, projectile) -
                   targetMomentum(scene, previous, projectile)).norm();
  }
  if (!start.empty())
    for (std::size_t i = 0; i < poses.size(); ++i)
      if (static_cast<int>(i) != projectile && !scene.boxes[i].immovable &&
          (poses[i].x - start[i].x).norm() > kMovedDistance)
        ++m.movedAtEnd;
  return m;
}

std::string impactPage(const std::vector<ImpactRow>& rows, double friction,
                       const std::string& stampText, const std::string& command) {
  std::ostringstream out;
  char mu[32];
  std::snprintf(mu, sizeof mu, "%g", friction);
  out << "# The shot's impact with friction, boxsim beside Bullet and ODE\n\n"
      << "Written by `boxsim_peers --impact` (bench/peers); do not edit by hand. Regenerate with\n"
      << "`cmake --build build --target bench_impact`.\n\n"
      << stampText << "- command: `" << command << "`\n\n"
      << "The pyramids of Fig. 6.6 (base 10) and of base 20 shot as the comparison shoots them "
         "(docs/benchmarks.md), with each engine's own sleeping and with none, every engine with "
         "Coulomb friction μ = "
      << mu
      << " at every contact, one thread, Δt = 1/60 s. The impact's step is the first step after "
         "the launch that changes the projectile's velocity by more than "
      << kImpactSpeed
      << " m/s beyond gravity's g Δt. In it: the struck box is the pyramid's box whose velocity "
         "changed most (its speed after the step, and 3 steps later); *moving* counts the "
         "pyramid's boxes whose velocity changed by more than "
      << kImpactSpeed
      << " m/s; *delivered* is the change of the pyramid's momentum |Σ m v|. *Moved* counts the "
         "boxes farther than "
      << kMovedDistance
      << " m from where they stood at the launch when the scene ends. The engines treat "
         "restitution differently in an impact of many contacts (boxsim: the thesis' collision "
         "passes; Bullet: a restitution term in its sequential-impulse solve; ODE: its bounce "
         "parameter in the LCP); at e = 0 they solve the same problem.\n\n"
      << "| scene | engine | impact (s) | struck box: speed (m/s), 3 steps later | moving | "
         "projectile before → after (m/s) | delivered (N s) | moved at the end |\n"
      << "|---|---|---|---|---|---|---|---|\n";
  for (const ImpactRow& row : rows) {
    const ImpactMeasures& m = row.measures;
    char line[512];
    if (!m.found)
      std::snprintf(line, sizeof line, "| %s | %s | none | – | – | – | – | %d |\n",
                    row.scene.c_str(), row.engine.c_str(), m.movedAtEnd);
    else
      std::snprintf(line, sizeof line,
                    "| %s | %s | %.3f | %.2f, %.2f | %d | %.2f → %.2f | %.2f | %d |\n",
                    row.scene.c_str(), row.engine.c_str(), m.time, m.struckSpeed,
                    m.struckSpeedLater, m.moving, m.projectileBefore, m.projectileAfter,
                    m.delivered, m.movedAtEnd);
    out << line;
  }
  return out.str();
}

}  // namespace boxsim::peers
