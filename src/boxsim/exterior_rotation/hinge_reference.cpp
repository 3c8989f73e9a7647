#include "boxsim/exterior_rotation/hinge_reference.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <Eigen/Cholesky>
#include <stdexcept>
#include <string>

namespace boxsim {

namespace {
double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& w) { return u.x() * w.y() - u.y() * w.x(); }
Eigen::Vector2d turned(double phi, const Eigen::Vector2d& u) {
  return Eigen::Vector2d(std::cos(phi) * u.x() - std::sin(phi) * u.y(),
                         std::sin(phi) * u.x() + std::cos(phi) * u.y());
}
Eigen::Vector2d planar(const Vec3& p) { return Eigen::Vector2d(p.x(), p.y()); }
Quat aboutZRadians(double phi) { return Quat(Eigen::AngleAxisd(phi, Vec3::UnitZ())); }
}  // namespace

struct HingeReference::Driver {
  gsl_odeiv2_system system{};
  gsl_odeiv2_driver* driver = nullptr;
  ~Driver() {
    if (driver) gsl_odeiv2_driver_free(driver);
  }
};

int HingeReference::rate(double, const double* y, double* dydt, void* self) {
  const HingeReference& ref = *static_cast<const HingeReference*>(self);
  const int n = static_cast<int>(ref.links_.size());
  const Eigen::VectorXd phiDDot = ref.acceleration(y);
  for (int i = 0; i < n; ++i) {
    dydt[i] = y[n + i];
    dydt[n + i] = phiDDot[i];
  }
  return GSL_SUCCESS;
}

HingeReference::HingeReference(const StickingScene& scene, const HingeReferenceParams& params)
    : gravity_(scene.world.gravity), driver_(std::make_unique<Driver>()) {
  if (scene.links.empty())
    throw std::invalid_argument("scene '" + scene.name + "' has no hinge links for a reference");
  const World& world = scene.world;
  for (const RigidBody& body : world.bodies) {
    x0_.push_back(body.s.x);
    q0_.push_back(body.s.q);
    mass_.push_back(0.0);
  }
  for (std::size_t k = 0; k < scene.links.size(); ++k) {
    const HingeLink& spec = scene.links[k];
    if (spec.bodies.empty())
      throw std::invalid_argument("link " + std::to_string(k) + " of scene '" + scene.name +
                                  "' has no bodies");
    Link link;
    link.bodies = spec.bodies;
    Vec3 centre = Vec3::Zero();
    for (const int b : spec.bodies) {
      if (world.bodies[b].s.P != Vec3::Zero() || world.bodies[b].s.L != Vec3::Zero())
        throw std::invalid_argument("body '" + world.names[b] + "' of scene '" + scene.name +
                                    "' is moving; the hinge reference starts at rest");
      link.mass += world.bodies[b].mass;
      centre += world.bodies[b].mass * world.bodies[b].s.x;
      mass_[b] = world.bodies[b].mass;
    }
    centre /= link.mass;
    // Parallel axes: each body's I_zz (world) plus m d² about the link's centre.
    for (const int b : spec.bodies) {
      const RigidBody& body = world.bodies[b];
      const Mat3 I = body.R * body.IbodyInvDiag.cwiseInverse().asDiagonal() * body.R.transpose();
      link.inertia += I(2, 2) + body.mass * planar(body.s.x - centre).squaredNorm();
    }
    link.c = planar(centre - spec.hinge);
    link.h = k + 1 < scene.links.size() ? planar(scene.links[k + 1].hinge - spec.hinge)
                                        : Eigen::Vector2d::Zero();
    links_.push_back(link);
    hinge0_.push_back(spec.hinge);
  }
  y_.assign(2 * links_.size(), 0.0);
  driver_->system = gsl_odeiv2_system{&HingeReference::rate, nullptr, y_.size(), this};
  driver_->driver = gsl_odeiv2_driver_alloc_y_new(&driver_->system, gsl_odeiv2_step_rk8pd, 1e-4,
                                                  params.absoluteTolerance, params.relativeTolerance);
  if (!driver_->driver) throw std::runtime_error("GSL could not allocate the reference driver");
}

HingeReference::~HingeReference() = default;

Eigen::VectorXd HingeReference::acceleration(const double* y) const {
  const int n = static_cast<int>(links_.size());
  const Eigen::Vector2d g = planar(gravity_);
  // u[k][j] as in the class comment.
  std::vector<std::vector<Eigen::Vector2d>> u(n, std::vector<Eigen::Vector2d>(n, Eigen::Vector2d::Zero()));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j <= k; ++j) u[k][j] = turned(y[j], j < k ? links_[j].h : links_[k].c);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    M(i, i) += links_[i].inertia;
    for (int k = i; k < n; ++k) {
      const double m = links_[k].mass;
      for (int j = 0; j <= k; ++j) {
        M(i, j) += m * u[k][i].dot(u[k][j]);
        f[i] += m * y[n + j] * y[n + j] * cross2(u[k][i], u[k][j]);
      }
      f[i] += m * cross2(u[k][i], g);
    }
  }
  return M.ldlt().solve(f);
}

void HingeReference::advanceTo(double t) {
  if (t < t_)
    throw std::invalid_argument("the hinge reference runs forward only: asked for t = " +
                                std::to_string(t) + " s after " + std::to_string(t_) + " s");
  if (t == t_) return;
  const int status = gsl_odeiv2_driver_apply(driver_->driver, &t_, t, y_.data());
  if (status != GSL_SUCCESS)
    throw std::runtime_error(std::string("GSL rk8pd failed in the hinge reference: ") +
                             gsl_strerror(status));
}

Eigen::VectorXd HingeReference::angles() const {
  const int n = static_cast<int>(links_.size());
  return Eigen::Map<const Eigen::VectorXd>(y_.data(), n);
}

Eigen::VectorXd HingeReference::angularVelocities() const {
  const int n = static_cast<int>(links_.size());
  return Eigen::Map<const Eigen::VectorXd>(y_.data() + n, n);
}

Eigen::VectorXd HingeReference::angularAccelerations() const { return acceleration(y_.data()); }

Vec3 HingeReference::hinge(int k) const {
  Vec3 h = hinge0_[0];
  for (int j = 0; j < k; ++j) h += aboutZRadians(y_[j]) * (hinge0_[j + 1] - hinge0_[j]);
  return h;
}

int HingeReference::linkOf(int body) const {
  for (std::size_t k = 0; k < links_.size(); ++k)
    for (const int b : links_[k].bodies)
      if (b == body) return static_cast<int>(k);
  return -1;
}

Vec3 HingeReference::centre(int body) const {
  const int k = linkOf(body);
  if (k < 0)
    throw std::invalid_argument("body " + std::to_string(body) + " is in no link of the reference");
  return hinge(k) + aboutZRadians(y_[k]) * (x0_[body] - hinge0_[k]);
}

void HingeReference::applyTo(World& world) const {
  const int n = static_cast<int>(links_.size());
  // The velocity of each hinge: the sum of φ̇_j ẑ × (turned h_j) over the links before it.
  Vec3 hingeVelocity = Vec3::Zero();
  for (int k = 0; k < n; ++k) {
    const Vec3 H = hinge(k);
    const Vec3 omega = y_[n + k] * Vec3::UnitZ();
    for (const int b : links_[k].bodies) {
      RigidBody& body = world.bodies[b];
      body.s.x = centre(b);
      body.s.q = (aboutZRadians(y_[k]) * q0_[b]).normalized();
      body.updateDerived();
      body.setVelocity(hingeVelocity + omega.cross(body.s.x - H));
      body.setAngularVelocity(omega);
    }
    if (k + 1 < n) hingeVelocity += omega.cross(hinge(k + 1) - H);
  }
}

double HingeReference::energy() const {
  const int n = static_cast<int>(links_.size());
  double kinetic = 0.0;
  double potential = 0.0;
  Eigen::Vector2d hingeVelocity = Eigen::Vector2d::Zero();
  Eigen::Vector2d H = planar(hinge0_[0]);
  for (int k = 0; k < n; ++k) {
    const double phiDot = y_[n + k];
    const Eigen::Vector2d c = turned(y_[k], links_[k].c);
    const Eigen::Vector2d v = hingeVelocity + phiDot * Eigen::Vector2d(-c.y(), c.x());
    kinetic += 0.5 * links_[k].mass * v.squaredNorm() + 0.5 * links_[k].inertia * phiDot * phiDot;
    potential -= links_[k].mass * planar(gravity_).dot(H + c);
    const Eigen::Vector2d h = turned(y_[k], links_[k].h);
    hingeVelocity += phiDot * Eigen::Vector2d(-h.y(), h.x());
    H += h;
  }
  return kinetic + potential;
}

}  // namespace boxsim
