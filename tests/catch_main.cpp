// The one translation unit holding Catch2's main (compiled once; it is slow to compile).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
