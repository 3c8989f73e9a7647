/// \file
/// The demo's JavaScript interface (Emscripten's embind): `new Module.Demo(scene, method,
/// sleep, geometricStability, filter, friction)`, then step(), shoot(), and the poses, flags and
/// digest the page draws and checks; sceneBodies(), restitution() and gravity() hand the scene
/// to the other engines of the page (peer_engines.js), penetration() and penetrationAt(poses)
/// measure every engine with boxsim's separating-axis test. Poses are a view into the module's
/// memory, valid until the next call that steps or shoots.
#include <emscripten/bind.h>

#include "demo.hpp"

namespace {

using boxsim::web::Demo;
using boxsim::web::DemoSettings;

Demo* makeDemo(const std::string& scene, const std::string& method, bool sleep,
               bool geometricStability, const std::string& filter, double friction) {
  return new Demo(DemoSettings{scene, method, sleep, geometricStability, filter, friction});
}

emscripten::val sceneBodies(const Demo& demo) {
  const std::vector<double> bodies = demo.sceneBodies();
  // A copy: the vector dies here.
  return emscripten::val::global("Float64Array")
      .new_(emscripten::val(emscripten::typed_memory_view(bodies.size(), bodies.data())));
}

double penetrationAt(const Demo& demo, const emscripten::val& poses) {
  return demo.penetrationAt(emscripten::convertJSArrayToNumberVector<double>(poses));
}

emscripten::val poses(const Demo& demo) {
  return emscripten::val(emscripten::typed_memory_view(demo.poses().size(), demo.poses().data()));
}

emscripten::val halfExtents(const Demo& demo) {
  emscripten::val out = emscripten::val::array();
  for (double h : demo.halfExtents()) out.call<void>("push", h);
  return out;
}

emscripten::val flags(const Demo& demo) {
  emscripten::val out = emscripten::val::array();
  for (std::uint8_t f : demo.flags()) out.call<void>("push", static_cast<int>(f));
  return out;
}

bool shoot(Demo& demo, double fx, double fy, double fz, double dx, double dy, double dz) {
  return demo.shoot(boxsim::Vec3(fx, fy, fz), boxsim::Vec3(dx, dy, dz));
}

/// The message of a C++ exception caught in JavaScript (its pointer), for the page's errors.
std::string exceptionMessage(std::intptr_t pointer) {
  return reinterpret_cast<const std::exception*>(pointer)->what();
}

}  // namespace

EMSCRIPTEN_BINDINGS(boxsim_demo) {
  emscripten::class_<Demo>("Demo")
      .constructor(&makeDemo, emscripten::allow_raw_pointers())
      .function("step", &Demo::step)
      .function("shoot", &shoot)
      .function("shotsLeft", &Demo::shotsLeft)
      .function("time", &Demo::time)
      .function("bodyCount", &Demo::bodyCount)
      .function("largestDisplacement", &Demo::largestDisplacement)
      .function("stateDigest", &Demo::stateDigest)
      .function("poses", &poses)
      .function("halfExtents", &halfExtents)
      .function("flags", &flags)
      .function("sceneBodies", &sceneBodies)
      .function("restitution", &Demo::restitution)
      .function("gravity", &Demo::gravity)
      .function("penetration", &Demo::penetration)
      .function("penetrationAt", &penetrationAt);
  emscripten::constant("shotCount", Demo::kShots);
  emscripten::constant("shotSpeed", Demo::kShotSpeed);
  emscripten::function("exceptionMessage", &exceptionMessage);
}
