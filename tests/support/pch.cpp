// The source of bounce_test_pch (cmake/Bounce.cmake): that target exists to build the tests'
// precompiled header; this file compiles to nothing.
