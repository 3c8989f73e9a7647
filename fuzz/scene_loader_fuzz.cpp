// libFuzzer target: scene text from the fuzzer goes through checkSceneInput(), the loader
// `boxsim run` uses followed by a few steps of two techniques. A documented rejection returns
// normally; anything else (another exception type, an empty message, a state that stops being
// finite, a sanitizer report, a crash or a hang) stops the fuzzer with the input saved.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "scene_fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    boxsim::fuzz::checkSceneInput(text);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scene_loader_fuzz: finding: %s: %s\n", typeid(e).name(), e.what());
    std::abort();
  }
  return 0;
}
