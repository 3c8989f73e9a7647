// Drops the tilted die of the thesis' §4.2 on the ground under damped integration (§5.2) and
// prints, every half second, its height and whether it has fallen asleep (§4.5).
//
//   drop_die [method]     method: damped (default), impulse, analytic, basic_colliding, ...
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

#include "boxsim/io/scene_builders.hpp"
#include "boxsim/techniques.hpp"

int main(int argc, char** argv) {
  try {
    boxsim::World world;  // gravity −9.81 m/s² along y, restitution 0.9
    world.addGround();    // the plane y = 0
    boxsim::DieSpec die;  // a 1 m cube of 1 kg at y = 2 m, tilted 10°
    const std::size_t d = world.bodies.size();  // the die's index, stable from now on
    boxsim::addDie(world, die);

    const std::string method = argc > 1 ? argv[1] : "damped";
    std::unique_ptr<boxsim::Stepper> stepper = boxsim::makeStepper(method);
    const double dt = 1.0 / 60.0;  // s
    for (int k = 1; k <= 360; ++k) {  // 6 s
      const boxsim::StepStats stats = stepper->step(world, dt);
      if (k % 30 == 0) {
        const boxsim::RigidBody& body = world.bodies[d];
        std::printf("t = %4.1f s  height %.3f m  speed %.3f m/s  %s\n", k * dt, body.s.x.y(),
                    body.v.norm(), stats.sleeping > 0 ? "asleep" : "awake");
      }
    }
    return 0;
  } catch (const std::exception& e) {  // an unknown method, a bad specification
    std::fprintf(stderr, "drop_die: %s\n", e.what());
    return 1;
  }
}
