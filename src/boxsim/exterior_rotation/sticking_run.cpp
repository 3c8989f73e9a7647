#include "boxsim/exterior_rotation/sticking_run.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <gsl/gsl_fit.h>

#include "boxsim/collision/broad_phase.hpp"

namespace boxsim {

double pointGap(const StickingScene& scene, int i) {
  const PointConstraint& p = scene.points[i];
  const RigidBody& a = scene.world.bodies[p.a];
  const RigidBody& b = scene.world.bodies[p.b];
  const Vec3 n = scene.world.bodies[p.normalBody].R * p.normalLocal;
  return ((b.s.x + b.R * p.rB) - (a.s.x + a.R * p.rA)).dot(n);
}

namespace {

/// The link of the top body: the last link containing it.
int topLink(const StickingScene& scene) {
  for (std::size_t k = 0; k < scene.links.size(); ++k)
    for (const int b : scene.links[k].bodies)
      if (b == scene.topBody) return static_cast<int>(k);
  throw std::invalid_argument("the top body of scene '" + scene.name + "' is in no link");
}

/// The simulated hinge of link k: the mean of the a-side material points of its hinge contact.
Vec3 simulatedHinge(const StickingScene& scene, int k) {
  Vec3 sum = Vec3::Zero();
  int count = 0;
  for (const PointConstraint& p : scene.points) {
    if (p.contact != scene.pivots[k]) continue;
    const RigidBody& a = scene.world.bodies[p.a];
    sum += a.s.x + a.R * p.rA;
    ++count;
  }
  return sum / count;
}

double totalEnergy(const World& world) { return world.kineticEnergy() + world.potentialEnergy(); }

}  // namespace

StickingRun runSticking(const StickingScene& scene, StickingMethod method, double dt, int steps,
                        const std::function<void(const World&, double)>& onStep) {
  if (steps < 1) throw std::invalid_argument("runSticking needs at least one step");
  StickingRun run{{}, scene, {}};
  StickingScene& s = run.end;
  HingeReference reference(scene);
  const int link = topLink(scene);
  const double radius0 = (scene.world.bodies[scene.topBody].s.x - simulatedHinge(scene, link)).norm();
  const double energy0 = totalEnergy(scene.world);
  const double referenceEnergy0 = reference.energy();
  const int contacts = static_cast<int>(scene.contacts.size());
  for (int step = 0; step <= steps; ++step) {
    const double t = step * dt;
    reference.advanceTo(t);
    StickingSample sample;
    sample.t = t;
    sample.penetration = deepestPenetration(s.world);
    sample.contactGap.assign(contacts, 0.0);
    std::vector<int> pointsPerContact(contacts, 0);
    sample.minGap = 0.0;
    sample.maxGap = 0.0;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const PointConstraint& p = s.points[i];
      const double gap = pointGap(s, static_cast<int>(i));
      sample.minGap = std::min(sample.minGap, gap);
      sample.maxGap = std::max(sample.maxGap, gap);
      sample.contactGap[p.contact] += gap;
      ++pointsPerContact[p.contact];
      const RigidBody& a = s.world.bodies[p.a];
      const RigidBody& b = s.world.bodies[p.b];
      sample.maxError = std::max(sample.maxError, ((b.s.x + b.R * p.rB) - (a.s.x + a.R * p.rA)).norm());
    }
    for (int c = 0; c < contacts; ++c)
      if (pointsPerContact[c] > 0) sample.contactGap[c] /= pointsPerContact[c];
    sample.top = s.world.bodies[s.topBody].s.x;
    sample.topReference = reference.centre(s.topBody);
    sample.radialError = (sample.top - simulatedHinge(s, link)).norm() - radius0;
    sample.referenceError = (sample.top - sample.topReference).norm();
    const StickingSolution f = solveStickingForces(s.world, s.points, contacts);
    for (const int pivot : s.pivots) sample.pivotLoads.push_back(contactLoad(s, f, pivot));
    sample.energyChange = totalEnergy(s.world) - energy0;
    sample.referenceEnergyChange = reference.energy() - referenceEnergy0;
    sample.referenceAngles = reference.angles();
    if (onStep) onStep(s.world, t);
    run.samples.push_back(sample);
    if (step < steps) stepSticking(s, method, dt);
  }
  StickingSummary& m = run.summary;
  m.minPivotNormal = run.samples.front().pivotLoads.front().normal;
  for (const StickingSample& x : run.samples) {
    m.maxPenetration = std::max(m.maxPenetration, x.penetration);
    m.maxError = std::max(m.maxError, x.maxError);
    m.minGap = std::min(m.minGap, x.minGap);
    m.maxGap = std::max(m.maxGap, x.maxGap);
    m.maxAbsRadialError = std::max(m.maxAbsRadialError, std::abs(x.radialError));
    m.maxReferenceError = std::max(m.maxReferenceError, x.referenceError);
    for (const ContactLoad& load : x.pivotLoads) {
      m.minPivotNormal = std::min(m.minPivotNormal, load.normal);
      m.maxRequiredMu = std::max(m.maxRequiredMu, load.requiredMu);
    }
    m.maxAbsReferenceEnergyChange = std::max(m.maxAbsReferenceEnergyChange, std::abs(x.referenceEnergyChange));
  }
  return run;
}

double convergenceOrder(const std::vector<double>& dt, const std::vector<double>& error) {
  if (dt.size() != error.size() || dt.size() < 2)
    throw std::invalid_argument("convergenceOrder: needs as many errors as steps, at least two");
  std::vector<double> x(dt.size()), y(dt.size());
  for (std::size_t i = 0; i < dt.size(); ++i) {
    if (!(dt[i] > 0.0) || !(error[i] > 0.0))
      throw std::invalid_argument("convergenceOrder: steps and errors must be positive numbers");
    x[i] = std::log(dt[i]);
    y[i] = std::log(error[i]);
  }
  double intercept = 0.0, slope = 0.0, cov00 = 0.0, cov01 = 0.0, cov11 = 0.0, sumsq = 0.0;
  gsl_fit_linear(x.data(), 1, y.data(), 1, x.size(), &intercept, &slope, &cov00, &cov01, &cov11,
                 &sumsq);
  return slope;
}

}  // namespace boxsim
