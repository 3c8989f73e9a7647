/// \file
/// web_digest: runs a demo scene natively, fires one shot from the pyramid scene's eye point
/// (0.5, 4.5, 12) m along −z after SHOT steps (never when SHOT is negative), and prints the
/// state digest after each given step count, for the check that the WebAssembly build steps the
/// same bits (web/test/browser_test.mjs).
///
///   web_digest SCENE METHOD SHOT STEP [STEP ...]    e.g. web_digest pyramid damped 30 60 300
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "demo.hpp"

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: web_digest SCENE METHOD SHOT STEP [STEP ...]\n");
    return 2;
  }
  try {
    boxsim::web::DemoSettings settings;
    settings.scene = argv[1];
    settings.method = argv[2];
    boxsim::web::Demo demo(settings);
    const long shot = std::strtol(argv[3], nullptr, 10);
    long done = 0;
    for (int a = 4; a < argc; ++a) {
      const long steps = std::strtol(argv[a], nullptr, 10);
      while (done < steps) {
        if (done == shot) demo.shoot(boxsim::Vec3(0.5, 4.5, 12.0), boxsim::Vec3(0.0, 0.0, -1.0));
        demo.step();
        ++done;
      }
      std::printf("%ld %s\n", done, demo.stateDigest().c_str());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "web_digest: %s\n", e.what());
    return 1;
  }
}
