/// \file
/// Stability under load: the generalisation of geometric stability (\thesis{§5.4}) that
/// \thesis{§6.3.1} asks for with Figs. 6.4 and 6.5, as a feasibility problem over the support
/// forces in the spirit of Mattikalli et al., whom §5.4 cites.
///
/// §5.4's rule asks every corner of a box's bottom face to rest on a stable body, so that a
/// load of any size anywhere on the box cannot tip it. Many resting boxes fail it and still
/// cannot move: a staircase of blocks each overhanging the one below, whose upper blocks
/// together are "one heavier object" over the lower one (Fig. 6.4), and a heavy block whose
/// weight holds down two supports that would each tip alone (Fig. 6.5). Whether such boxes hold
/// depends on their loads. With gravity along −y, frictionless contacts whose normals are all
/// along ±y, and bodies at rest, a set of boxes stays at rest exactly when non-negative normal
/// forces at its contact points balance every box's weight and turning moments: then zero
/// accelerations solve the frictionless contact LCP, whose accelerations are unique (Baraff
/// 1994, §3: the LCP's matrix is positive semi-definite), and otherwise some box accelerates.
///
/// So the loads must be known. A component here is a set of boxes joined by contacts such that
/// everything that can press on it is known: each of its boxes is level (a face down), all its
/// contact normals are along ±y, everything under it is in the component or stable by §5.4
/// (which holds under any load), and everything on it is in the component or immovable. Each
/// component's equilibrium is one linear program (GLPK's simplex); a feasible one makes all its
/// boxes stable under load. A box touched by anything else (a falling or tilted box, a side
/// contact) is not judged, and neither is the rest of its component: the test answers for the
/// loads it sees, and a new load next step is judged then.
#pragma once

#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim {

struct GeometricStabilityParams;

/// The verdicts of setGeometricallyStable: a flag per body, read as a truth value by the
/// techniques (any stable body is treated alike) and by value by the figures.
enum StabilityFlag : char {
  kUnstable = 0,
  kGeometricallyStable = 1,  ///< \thesis{§5.4}'s rule: stable under any load
  kStableUnderLoad = 2,      ///< this file's test: stable under the loads it has
};

/// What one call of addStableUnderLoad examined and decided.
struct LoadStabilityReport {
  int candidates = 0;        ///< level resting boxes not stable by §5.4 whose loads are all known
  int components = 0;        ///< linear programs solved (one a component)
  int stableComponents = 0;  ///< of those, feasible ones
  int bodiesAdded = 0;       ///< boxes marked kStableUnderLoad
  int largestRows = 0;       ///< largest program: equations (3 a box)
  int largestColumns = 0;    ///< largest program: unknown forces (one a contact point)
};

/// Marks kStableUnderLoad the boxes that are not stable by §5.4's rule but whose component (see
/// the file comment) has non-negative contact forces holding each of its boxes in equilibrium,
/// with a margin: the equilibrium must also exist with every box's weight moved by
/// params.cornerTolerance × its bottom face's smaller half extent along +x, −x, +z and −z in
/// turn (0.5 mm on a unit cube: a centre of mass exactly over an edge is not stable).
/// \param world     bodies with up-to-date R; gravity along −y (otherwise nothing is added)
/// \param contacts  every contact manifold, as for setGeometricallyStable (small margin)
/// \param params    normalTolerance (along ±y, level) and cornerTolerance (the margin)
/// \param stable    in: setGeometricallyStable's flags under §5.4's rule, one per body;
///                  out: the same, with the boxes found stable under load set to kStableUnderLoad
/// \return the counts of what was examined. Independent of the order of bodies and contacts
///         up to rounding in the programs.
/// \throws std::invalid_argument when stable.size() differs from the number of bodies;
///         std::runtime_error when the program cannot be solved (GLPK is absent, as in the
///         WebAssembly build).
/// \thesis{§6.3.1} Figs. 6.4 and 6.5; equilibrium as linear feasibility: Mattikalli, Baraff,
/// Khosla and Repetto, "Gravitational stability of frictionless assemblies", IEEE Trans.
/// Robotics and Automation 11(3), 1995.
LoadStabilityReport addStableUnderLoad(const World& world,
                                       const std::vector<ContactManifold>& contacts,
                                       const GeometricStabilityParams& params,
                                       std::vector<char>& stable);

}  // namespace boxsim
