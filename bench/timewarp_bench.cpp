/// \file
/// Timing of the modified timewarp (\thesis{§5.1}, chapters/timewarp) against the basic
/// colliding technique on k independent head-on collisions far apart (addApproachingPairs):
/// basic colliding rolls every body back at each collision, the timewarp only the two that
/// collide (\thesis{§2.4.3}). Names: pairs/<method>/<k>; one iteration is the 6 frames of
/// 1/60 s in which every pair collides once; counters give body integrations and roll-backs
/// per frame.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "boxsim/io/scene_builders.hpp"
#include "boxsim/techniques.hpp"

namespace {

using namespace boxsim;

void pairs(benchmark::State& state, const std::string& method) {
  World start;
  start.gravity = Vec3::Zero();
  start.restitution = 1.0;
  addApproachingPairs(start, static_cast<int>(state.range(0)));
  const std::unique_ptr<Stepper> stepper = makeStepper(method);
  StepStats total;
  long frames = 0;
  for (auto _ : state) {
    World world = start;
    for (int k = 0; k < 6; ++k) total += stepper->step(world, 1.0 / 60.0);
    frames += 6;
  }
  state.counters["integrations_per_frame"] = static_cast<double>(total.bodyIntegrations) / frames;
  state.counters["rollbacks_per_frame"] = static_cast<double>(total.bodyRollbacks) / frames;
}

}  // namespace

BENCHMARK_CAPTURE(pairs, basic_colliding, std::string("basic_colliding"))
    ->RangeMultiplier(4)->Range(1, 64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pairs, timewarp_simple, std::string("timewarp_simple"))
    ->RangeMultiplier(4)->Range(1, 64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pairs, timewarp_safer, std::string("timewarp_safer"))
    ->RangeMultiplier(4)->Range(1, 64)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pairs, timewarp_swept, std::string("timewarp_swept"))
    ->RangeMultiplier(4)->Range(1, 64)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
