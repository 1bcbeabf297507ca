include(GoogleTest)
# Helpers shared by every module.
#
# bounce_library(NAME SOURCES ... DEPS ...): a static library bounce_NAME whose headers are
# included from the repository root ("engine/core/error.hpp").
function(bounce_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(bounce_${name} STATIC ${ARG_SOURCES})
  target_include_directories(bounce_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(bounce_${name} PUBLIC ${ARG_DEPS})
  # GCC 12 reports a false -Wrestrict inside libstdc++ string concatenation (GCC bug 105329).
  target_compile_options(bounce_${name} PRIVATE -Wall -Wextra $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
  # No source or build path is compiled in: engine and game find shaders, content and caches at
  # run time (engine/core/paths.hpp), so a build or an installed prefix can be moved. Only tests
  # get BOUNCE_SOURCE_DIR (bounce_test below), for their data.
endfunction()

# Sanitizer builds (the asan preset): tests preload the Vulkan driver, so the loader's dlclose at
# vkDestroyInstance does not turn the blocks its globals hold into "leaks" with "<unknown module>"
# stacks, and LeakSanitizer reads tests/sanitizer/lsan.supp, which suppresses what the driver's own
# libraries leak and nothing of ours (why, and the proof: tests/sanitizer).
set(BOUNCE_SANITIZER_ENV "")
if(CMAKE_CXX_FLAGS MATCHES "-fsanitize=[^ ]*address")
  find_library(BOUNCE_VULKAN_ICD vulkan_lvp DOC "Vulkan driver preloaded by sanitizer test runs (lavapipe)")
  list(APPEND BOUNCE_SANITIZER_ENV "LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/tests/sanitizer/lsan.supp:print_suppressions=0")
  if(BOUNCE_VULKAN_ICD)
    list(APPEND BOUNCE_SANITIZER_ENV "LD_PRELOAD=${BOUNCE_VULKAN_ICD}")
  endif()
endif()

# One precompiled header for every test executable (CI time): each test TU otherwise parses ~200k
# lines of gtest, glm, Vulkan and the standard library before its own code (about half of a test
# TU's compile time in gcc; measured in README "CI time, session 19"). bounce_test_pch builds it once
# and every bounce_test target reuses it (REUSE_FROM), so it holds only what no test configures with a
# macro first (nothing in the project defines GLM_*, VK_* or GTEST_* options). Reuse needs the same
# compile options as the tests: those below. No compile definitions beyond those every test has
# (GTest's): gcc skips a PCH built with a macro its user lacks, with only a -Winvalid-pch warning
# ("not used because `MESHOPTIMIZER_API' not defined") and the full parse. BOUNCE_TEST_PCH=OFF builds
# the tests without it (to check that each test includes what it uses).
option(BOUNCE_TEST_PCH "Tests reuse one precompiled header (gtest, glm, Vulkan, std)" ON)
if(BOUNCE_TEST_PCH)
  add_library(bounce_test_pch OBJECT ${PROJECT_SOURCE_DIR}/tests/support/pch.cpp)
  target_link_libraries(bounce_test_pch PRIVATE GTest::gtest glm::glm Vulkan::Vulkan)
  target_compile_options(bounce_test_pch PRIVATE -Wall -Wextra $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    # A .pch restored from ccache's store must not be checked against the headers' mtimes (ccache
    # manual, "Precompiled headers"); gcc's .gch holds none.
    target_compile_options(bounce_test_pch PRIVATE "SHELL:-Xclang -fno-pch-timestamp")
  endif()
  target_precompile_headers(bounce_test_pch PRIVATE
    <gtest/gtest.h>
    <glm/glm.hpp> <glm/gtc/matrix_transform.hpp> <glm/gtc/quaternion.hpp>
    <vulkan/vulkan.h>
    <algorithm> <array> <cmath> <cstdio> <cstdlib> <cstring> <filesystem> <fstream> <functional>
    <limits> <map> <memory> <optional> <set> <sstream> <string> <string_view> <variant> <vector>)
endif()

# bounce_test(NAME SOURCES ... DEPS ... [GPU] [ONE_PROCESS ENTRY] [TIMEOUT s]): a GoogleTest executable
# registered with ctest, one ctest entry per TEST(). GPU tests run with Vulkan validation on (any
# validation error fails the test: see engine/gpu) and a build-local Mesa shader cache.
# ONE_PROCESS registers the whole executable as one ctest entry named ENTRY instead: for a suite whose
# SetUpTestSuite does the expensive work once for all its TESTs (AccuracyRun: one `bounce accuracy`
# run), which one process per TEST would repeat (7 × 64–98 s in release, 7 × 310–440 s under asan:
# 63 % of the asan suite's time in the CI run of session 12). A failing TEST still fails the entry and
# names itself in the output.
function(bounce_test name)
  cmake_parse_arguments(ARG "GPU" "TIMEOUT;ONE_PROCESS" "SOURCES;DEPS" ${ARGN})
  add_executable(test_${name} ${ARG_SOURCES})
  target_link_libraries(test_${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_options(test_${name} PRIVATE -Wall -Wextra $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
  target_compile_definitions(test_${name} PRIVATE
    BOUNCE_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    BOUNCE_SHARED_DIR="${BOUNCE_SHARED_DIR}"
    BOUNCE_TEST_OUT="${PROJECT_BINARY_DIR}/test-out")
  if(BOUNCE_TEST_PCH)
    target_precompile_headers(test_${name} REUSE_FROM bounce_test_pch)
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  set(env "BOUNCE_VALIDATION=1" "MESA_SHADER_CACHE_DIR=${PROJECT_BINARY_DIR}/mesa-cache" ${BOUNCE_SANITIZER_ENV})
  if(ARG_GPU)
    list(APPEND env "BOUNCE_GPU_TEST=1")
  endif()
  # The environment goes in as a launcher (`cmake -E env VAR=… test_NAME …`), not as the ENVIRONMENT
  # property: CMake 3.25's gtest_discover_tests splits list-valued PROPERTIES, so only the first
  # entry reached the tests (no driver preload or LSan suppressions under asan). GoogleTest.cmake
  # prefixes discovery and every discovered test with the target's CROSSCOMPILING_EMULATOR.
  set_property(TARGET test_${name} PROPERTY CROSSCOMPILING_EMULATOR ${CMAKE_COMMAND} -E env ${env})
  if(ARG_ONE_PROCESS)
    add_test(NAME ${ARG_ONE_PROCESS} COMMAND ${CMAKE_COMMAND} -E env ${env} $<TARGET_FILE:test_${name}>)
    set_tests_properties(${ARG_ONE_PROCESS} PROPERTIES TIMEOUT ${ARG_TIMEOUT})
    return()
  endif()
  gtest_discover_tests(test_${name}
    DISCOVERY_MODE PRE_TEST
    PROPERTIES TIMEOUT ${ARG_TIMEOUT})
endfunction()
