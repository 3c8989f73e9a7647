// The interactive scene of the thesis' Fig. 6.6: a pyramid of unit cubes, one box deep, and at
// t = 2 s a cube shot from the eye point towards it at 20 m/s. Runs 6 s under damped
// integration, writes the trajectory file (read_trajectory reads it; `boxsim render` draws it)
// and prints how many cubes the shot moved.
//
//   shoot_pyramid [out.dat]     default pyramid.dat
#include <cstdio>
#include <exception>
#include <string>

#include "boxsim/io/recorder.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/io/simulate.hpp"
#include "boxsim/techniques.hpp"

int main(int argc, char** argv) {
  try {
    boxsim::World world;
    world.addGround(0.0, 30.0);
    boxsim::PyramidSpec pyramid;  // a base of 10 cubes of 1 m and 1 kg: 55 cubes
    const int cubes = boxsim::addPyramid(world, pyramid);
    boxsim::RigidBody shot = boxsim::RigidBody::box(boxsim::Vec3::Constant(0.5), 1.0);
    shot.s.x = {0.5, 4.5, 12.0};           // m, the eye point
    shot.setVelocity({0.0, 0.0, -20.0});   // m/s, towards the pyramid
    world.addLaunched(shot, "shot", 2.0);  // waits, immovable, until t = 2 s
    const boxsim::WorldState before = world.saveState();

    auto stepper = boxsim::makeStepper("damped");
    boxsim::SimulateOptions options;  // dt 1/60 s
    options.duration = 6.0;           // s
    const std::string out = argc > 1 ? argv[1] : "pyramid.dat";
    boxsim::Recorder recorder(
        world, boxsim::runParameters(*stepper, world, "shoot_pyramid", options.dt, options.duration));
    boxsim::simulate(world, *stepper, options, recorder);
    recorder.write(out);  // whole or not at all

    int moved = 0;  // cubes of the pyramid now more than half a cube from where they stood
    for (int i = 1; i <= cubes; ++i)
      if ((world.bodies[i].s.x - before.bodies[i].x).norm() > 0.5) ++moved;
    std::printf("%d of %d cubes moved by the shot; trajectory in %s\n", moved, cubes, out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shoot_pyramid: %s\n", e.what());
    return 1;
  }
}
