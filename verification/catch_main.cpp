// The Catch2 (v2) test runner's main(), shared by every verification executable.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
