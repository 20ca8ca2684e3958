// Catch2's main and the framework's implementation, the largest compile of a test program
// (40-70 s): compiled once, in snaresim_catch_main, for every test program that uses Catch2's
// own main (the plug-in's tests have their own runner).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
