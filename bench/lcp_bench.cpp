/// \file
/// Solve time of the contact LCP (\thesis{§3.3.1}, Baraff 1994) against the number of contacts,
/// per linear solver of fdirection, and milliseconds per step of the analytic method with and
/// without the geometric-stability exclusion (\thesis{§5.4}).
///
/// Run it with `cmake --build build --target bench` (with step_bench) or alone:
/// `build/bench/boxsim_lcp_bench`. Names: lcpSolve/<solver>/<boxes> solves the LCP of a
/// resting tower of that many unit cubes (four corner contacts per level; the counters give
/// the contacts and the pivots); analyticStep/<full|excluded>/<boxes> times one step of the
/// analytic method on the tower at rest, with the counter lcp_contacts; analyticPyramid/
/// <full|excluded> the same for the 55-cube pyramid with gaps in its rows, and
/// analyticPyramid/touching_full for it without gaps.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "boxsim/analytic_lcp/analytic_stepper.hpp"
#include "boxsim/analytic_lcp/contact_matrix.hpp"
#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/io/scene_builders.hpp"

namespace {

using namespace boxsim;

World tower(int boxes) {
  World world;
  world.addGround(0.0, 50.0);
  addTower(world, TowerSpec{boxes});
  return world;
}

void lcpSolve(benchmark::State& state, LcpLinearSolver solver) {
  const World world = tower(static_cast<int>(state.range(0)));
  const std::vector<PointContact> contacts = pointContacts(world, findContacts(world, 1e-3));
  MatX A;
  VecX b;
  contactMatrix(world, contacts, A, b);
  LcpParams params;
  params.linearSolver = solver;
  int pivots = 0;
  for (auto _ : state) {
    const LcpResult r = solveContactLcp(A, b, params);
    benchmark::DoNotOptimize(r.f.data());
    pivots = r.pivots;
  }
  state.counters["contacts"] = static_cast<double>(contacts.size());
  state.counters["pivots"] = pivots;
}

void analyticStep(benchmark::State& state, bool exclusion) {
  AnalyticParams params;
  params.useGeometricStability = exclusion;
  const World start = tower(static_cast<int>(state.range(0)));
  World world = start;
  AnalyticStepper stepper(params);
  for (auto _ : state) {
    stepper.step(world, 1.0 / 60.0);
    state.PauseTiming();
    world = start;  // a resting tower: every step times the same state
    state.ResumeTiming();
  }
  state.counters["lcp_contacts"] = stepper.lastLcpSize();
}

/// The 55-cube pyramid (base 10) at rest, with 5 cm gaps in its rows so that its boxes can be
/// geometrically stable (touching side faces would make them all unstable): one analytic step.
/// The scale the chapter compares against: ODE's direct Dantzig solver takes about 300 ms a
/// step on a 55-cube pyramid on this machine (the measurement).
/// With gap 0 (touching) side contacts make every box unstable and the exclusion finds nothing.
void analyticPyramid(benchmark::State& state, bool exclusion, double gap) {
  AnalyticParams params;
  params.useGeometricStability = exclusion;
  World start;
  start.addGround(0.0, 50.0);
  addPyramid(start, PyramidSpec{10, 1.0, 1.0, Vec3::Zero(), gap});
  World world = start;
  AnalyticStepper stepper(params);
  for (auto _ : state) {
    stepper.step(world, 1.0 / 60.0);
    state.PauseTiming();
    world = start;
    state.ResumeTiming();
  }
  state.counters["lcp_contacts"] = stepper.lastLcpSize();
}

}  // namespace

BENCHMARK_CAPTURE(analyticPyramid, full, false, 0.05)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(analyticPyramid, excluded, true, 0.05)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(analyticPyramid, touching_full, false, 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(lcpSolve, incremental_cholesky, LcpLinearSolver::IncrementalCholesky)
    ->RangeMultiplier(2)->Range(1, 64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(lcpSolve, ldlt, LcpLinearSolver::Ldlt)
    ->RangeMultiplier(2)->Range(1, 64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(lcpSolve, complete_orthogonal, LcpLinearSolver::CompleteOrthogonal)
    ->RangeMultiplier(2)->Range(1, 64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(analyticStep, full, false)->Arg(10)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(analyticStep, excluded, true)->Arg(10)->Arg(40)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
