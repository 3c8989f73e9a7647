#include "boxsim/io/recorder.hpp"

#include <utility>

namespace boxsim {

Recorder::Recorder(const World& world, std::map<std::string, std::string> meta) {
  trajectory_.meta = std::move(meta);
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    trajectory_.bodies.push_back(
        {world.names[i], world.bodies[i].halfExtents, world.bodies[i].immovable});
}

Recorder::Recorder(const World& world, std::map<std::string, std::string> meta, FrameSink& sink)
    : Recorder(world, std::move(meta)) {
  sink_ = &sink;
  sink_->begin(trajectory_.meta, trajectory_.bodies);
}

void Recorder::capture(const World& world, double t, const StepStats& stats) {
  TrajectoryFrame f;
  f.t = t;
  f.kinetic = world.kineticEnergy();
  f.potential = world.potentialEnergy();
  f.contacts = stats.contacts;
  f.events = stats.events;
  f.bisections = stats.bisections;
  f.x.reserve(world.bodies.size());
  f.q.reserve(world.bodies.size());
  for (const RigidBody& b : world.bodies) {
    f.x.push_back(b.s.x);
    f.q.push_back(b.s.q);
  }
  if (sink_ != nullptr)
    sink_->push(f);
  else
    trajectory_.frames.push_back(std::move(f));
}

}  // namespace boxsim
