/// \file
/// Stability under load (load_stability.hpp): the components whose loads are all known, and one
/// linear program of equilibrium for each.
///
/// The program of a component, for its boxes i (mass m_i, centre c_i) and the points p of its
/// vertical contacts (position x_p, top box t_p, bottom box b_p):
/// \verbatim
///   find λ_p >= 0 (N) such that for every box i of the component
///     Σ_p s_ip λ_p                       = m_i g             (vertical force)
///     Σ_p s_ip (−(x_p − c_i)·z) λ_p      = −d_z m_i g        (moment about x)
///     Σ_p s_ip ((x_p − c_i)·x) λ_p       =  d_x m_i g        (moment about z)
///   s_ip = +1 when i = t_p (the point pushes i up), −1 when i = b_p, 0 otherwise
/// \endverbatim
/// where d is the horizontal shift of the weights the margin asks for. The horizontal forces and
/// the moment about y vanish by themselves: every force is vertical. The program is scaled so that
/// its numbers are near 1: forces in units of the component's weight, each box's moments divided
/// by its largest half extent.
#include "boxsim/geometric_stability/load_stability.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "boxsim/collision/xz_hull.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"

#ifdef BOXSIM_HAVE_GLPK
#include <glpk.h>
#endif

namespace boxsim {
namespace {

/// A point of a manifold whose normal is along ±y: what it pushes up and what it pushes down.
struct VerticalPoint {
  Vec3 x = Vec3::Zero();  ///< world, m
  int top = -1;           ///< body pushed up
  int bottom = -1;        ///< body pushed down
};

bool alongY(const Vec3& n, double tolerance) { return 1.0 - std::abs(n.y()) <= tolerance; }

/// A box with a face whose outward normal is along −y (the same "level" as §5.4's rule).
bool isLevel(const RigidBody& body, double tolerance) {
  return 1.0 - horizontalFace(body, /*up=*/false).verticality <= tolerance;
}

/// Union-find root with path halving; the smaller index becomes the root, so components are
/// named by their first body whatever the order of the unions.
int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

/// One component's program, solved for each shift of the weights. True when all are feasible.
bool componentHolds(const World& world, const std::vector<int>& bodies,
                    const std::vector<VerticalPoint>& points, double cornerTolerance,
                    LoadStabilityReport& report) {
  const int rows = 3 * static_cast<int>(bodies.size());
  const int columns = static_cast<int>(points.size());
  report.largestRows = std::max(report.largestRows, rows);
  report.largestColumns = std::max(report.largestColumns, columns);
  if (columns == 0) return false;  // nothing holds the boxes up
  const double g = -world.gravity.y();
  double weight = 0.0;
  for (int i : bodies) weight += world.bodies[i].mass * g;
  const auto localIndex = [&bodies](int body) {
    const auto it = std::lower_bound(bodies.begin(), bodies.end(), body);
    return it != bodies.end() && *it == body ? static_cast<int>(it - bodies.begin()) : -1;
  };
#ifdef BOXSIM_HAVE_GLPK
  // GLPK's arrays are 1-based: element 0 is unused.
  std::vector<int> ia(1, 0), ja(1, 0);
  std::vector<double> ar(1, 0.0);
  for (int p = 0; p < columns; ++p) {
    for (const auto& [body, sign] : {std::pair(points[p].top, 1.0), {points[p].bottom, -1.0}}) {
      const int local = localIndex(body);
      if (local < 0) continue;  // a support: stable by §5.4, or immovable
      const RigidBody& b = world.bodies[body];
      const double length = b.halfExtents.maxCoeff();
      const Vec3 r = points[p].x - b.s.x;
      const double coefficients[3] = {sign, -sign * r.z() / length, sign * r.x() / length};
      for (int k = 0; k < 3; ++k) {
        ia.push_back(3 * local + k + 1);
        ja.push_back(p + 1);
        ar.push_back(coefficients[k]);
      }
    }
  }
  glp_prob* lp = glp_create_prob();
  glp_set_obj_dir(lp, GLP_MIN);  // the objective is 0: any feasible point will do
  glp_add_rows(lp, rows);
  glp_add_cols(lp, columns);
  for (int p = 1; p <= columns; ++p) glp_set_col_bnds(lp, p, GLP_LO, 0.0, 0.0);
  glp_load_matrix(lp, static_cast<int>(ar.size()) - 1, ia.data(), ja.data(), ar.data());
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  // The four shifts of the margin (or none without one); the unshifted equilibrium is their
  // average, so it is feasible when they are.
  const std::vector<Vec3> shifts =
      cornerTolerance > 0.0 ? std::vector<Vec3>{Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitZ(),
                                                -Vec3::UnitZ()}
                            : std::vector<Vec3>{Vec3::Zero()};
  bool holds = true;
  for (const Vec3& direction : shifts) {
    for (std::size_t local = 0; local < bodies.size(); ++local) {
      const RigidBody& b = world.bodies[bodies[local]];
      const double share = b.mass * g / weight;
      const Vec3 d = cornerTolerance * horizontalFace(b, /*up=*/false).smallerHalfExtent * direction;
      const double length = b.halfExtents.maxCoeff();
      const double rhs[3] = {share, -d.z() / length * share, d.x() / length * share};
      for (int k = 0; k < 3; ++k)
        glp_set_row_bnds(lp, 3 * static_cast<int>(local) + k + 1, GLP_FX, rhs[k], rhs[k]);
    }
    if (glp_simplex(lp, &parm) != 0 || glp_get_status(lp) != GLP_OPT) {
      holds = false;
      break;
    }
  }
  glp_delete_prob(lp);
  return holds;
#else
  (void)world;
  (void)cornerTolerance;
  (void)localIndex;
  (void)weight;
  throw std::runtime_error(
      "stability under load: this build has no GLPK (libglpk-dev), so it cannot solve the "
      "equilibrium programs; use the geometric stability of §5.4 alone");
#endif
}

}  // namespace

LoadStabilityReport addStableUnderLoad(const World& world,
                                       const std::vector<ContactManifold>& contacts,
                                       const GeometricStabilityParams& params,
                                       std::vector<char>& stable) {
  const int n = static_cast<int>(world.bodies.size());
  if (static_cast<int>(stable.size()) != n)
    throw std::invalid_argument("stability under load: " + std::to_string(stable.size()) +
                                " flags for a world of " + std::to_string(n) + " bodies");
  LoadStabilityReport report;
  const double g = world.gravity.norm();
  if (!(g > 0.0) || !alongY(world.gravity / g, params.normalTolerance) || world.gravity.y() > 0.0)
    return report;

  // Candidates: movable, level, not stable by §5.4, no contact normal off the y axis.
  std::vector<char> candidate(n, 0);
  for (int i = 0; i < n; ++i)
    candidate[i] = !world.bodies[i].immovable && stable[i] == kUnstable &&
                   isLevel(world.bodies[i], params.normalTolerance);
  std::vector<VerticalPoint> points;
  for (const ContactManifold& m : contacts) {
    if (m.count == 0) continue;
    if (!alongY(m.normal, params.normalTolerance)) {
      candidate[m.a] = candidate[m.b] = 0;
      continue;
    }
    const bool bOnTop = m.normal.y() > 0.0;  // the normal runs from a to b
    for (int k = 0; k < m.count; ++k)
      points.push_back({m.points[k].position, bOnTop ? m.b : m.a, bOnTop ? m.a : m.b});
  }

  // Known loads: what is under a candidate is a candidate or stable under any load; what is on
  // it is a candidate or immovable. Dropping one candidate can drop its neighbours, so repeat
  // until nothing changes.
  for (bool changed = true; changed;) {
    changed = false;
    for (const VerticalPoint& p : points) {
      if (candidate[p.top] && !candidate[p.bottom] && stable[p.bottom] == kUnstable) {
        candidate[p.top] = 0;
        changed = true;
      }
      if (candidate[p.bottom] && !candidate[p.top] && !world.bodies[p.top].immovable) {
        candidate[p.bottom] = 0;
        changed = true;
      }
    }
  }
  report.candidates = static_cast<int>(std::count(candidate.begin(), candidate.end(), 1));
  if (report.candidates == 0) return report;

  // Components: candidates joined by their contacts with each other.
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const VerticalPoint& p : points)
    if (candidate[p.top] && candidate[p.bottom]) {
      const int a = root(parent, p.top), b = root(parent, p.bottom);
      parent[std::max(a, b)] = std::min(a, b);
    }
  // Each component's boxes (ascending: the first is its root) and points (in input order), in one
  // pass over each: components are numbered by their first box.
  std::vector<int> componentOf(n, -1);
  std::vector<std::vector<int>> bodies;
  std::vector<std::vector<VerticalPoint>> own;
  for (int i = 0; i < n; ++i) {
    if (!candidate[i]) continue;
    int& c = componentOf[root(parent, i)];
    if (c < 0) {
      c = static_cast<int>(bodies.size());
      bodies.emplace_back();
      own.emplace_back();
    }
    bodies[c].push_back(i);
  }
  for (const VerticalPoint& p : points) {
    const int side = candidate[p.top] ? p.top : candidate[p.bottom] ? p.bottom : -1;
    if (side >= 0) own[componentOf[root(parent, side)]].push_back(p);
  }
  for (std::size_t c = 0; c < bodies.size(); ++c) {
    ++report.components;
    if (!componentHolds(world, bodies[c], own[c], params.cornerTolerance, report)) continue;
    ++report.stableComponents;
    for (int i : bodies[c]) stable[i] = kStableUnderLoad;
    report.bodiesAdded += static_cast<int>(bodies[c].size());
  }
  return report;
}

}  // namespace boxsim
