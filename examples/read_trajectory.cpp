// Reads a trajectory file (written by `boxsim run`, shoot_pyramid or any Recorder) and prints
// how it was made, when its kinetic energy peaked, and the body that ends farthest from where
// it started.
//
//   read_trajectory file.dat
#include <cstdio>
#include <exception>

#include "boxsim/io/trajectory.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: read_trajectory file.dat\n");
    return 2;
  }
  try {
    const boxsim::Trajectory run = boxsim::readTrajectory(argv[1]);  // throws naming file and line
    for (const char* key : {"scene", "method", "dt", "duration"})  // all of them: run.meta
      if (run.meta.count(key)) std::printf("%-9s %s\n", key, run.meta.at(key).c_str());
    if (run.frames.empty()) return 0;

    const boxsim::TrajectoryFrame& last = run.frames.back();
    std::size_t peak = 0, farthest = 0;
    double farthestDistance = 0.0;  // m
    for (std::size_t k = 0; k < run.frames.size(); ++k) {
      const boxsim::TrajectoryFrame& frame = run.frames[k];
      if (frame.kinetic > run.frames[peak].kinetic) peak = k;
    }
    for (std::size_t i = 0; i < run.bodies.size(); ++i) {
      const double distance = (last.x[i] - run.frames.front().x[i]).norm();  // m
      if (distance > farthestDistance) {
        farthestDistance = distance;
        farthest = i;
      }
    }
    std::printf("%zu frames over %.3f s; kinetic energy peaks at %.3f J at t = %.3f s\n",
                run.frames.size(), last.t, run.frames[peak].kinetic, run.frames[peak].t);
    std::printf("%s ends %.3f m from where it started; kinetic energy at the end %.3f J\n",
                run.bodies[farthest].name.c_str(), farthestDistance, last.kinetic);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "read_trajectory: %s\n", e.what());
    return 1;
  }
}
