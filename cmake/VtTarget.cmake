# The exit code by which a test says "skipped" (ctest SKIP_RETURN_CODE): VT_SKIP in Catch tests
# (tests/support/test_support.hpp), `exit 77` in the shell and Python tests (automake's convention).
set(VT_TEST_SKIP_CODE 77)

# The libraries below the renderer: the fuzz targets parse through them, and the real-time and
# batch hot loops run in them.
set(VT_LOWER_LIBRARIES core scene collision haptics acquisition net)

# Shared compile settings for every V-Touching target. TEST_CODE: the target's own sources are test
# code, built at -O0.
function(vt_target_settings target)
  cmake_parse_arguments(ARG "TEST_CODE" "" "" ${ARGN})
  file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  string(REGEX MATCH "^[^/]+" top "${folder}")
  if(top IN_LIST VT_LOWER_LIBRARIES)
    set(lower ON)
  else()
    set(lower OFF)
  endif()
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<CXX_COMPILER_ID:GNU>:-Wshadow=local>
                         -Wno-missing-field-initializers)
  # Debug and sanitizer builds fail loudly on broken real-time invariants; release counts them.
  if(VT_SANITIZE OR VT_SANITIZE_THREAD OR CMAKE_BUILD_TYPE STREQUAL "Debug")
    target_compile_definitions(${target} PRIVATE VT_CHECKED_INVARIANTS)
  endif()
  if(VT_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                           -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      # Tests and the leak support file know which sanitizer watches them (gcc and clang differ).
      target_compile_definitions(${target} PRIVATE VT_SANITIZER_ADDRESS)
      target_sources(${target} PRIVATE ${PROJECT_SOURCE_DIR}/cmake/lsan_suppressions.cpp)
    endif()
    if(VT_BUILD_FUZZ AND (lower OR target STREQUAL "vt_app"))
      # Coverage for libFuzzer in the libraries the fuzz targets parse through (the app's: the
      # replay of recordings), so fuzz targets and tests share one build.
      target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
    endif()
  endif()
  if(VT_SANITIZE_THREAD)
    target_compile_options(${target} PRIVATE -fsanitize=thread -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=thread)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      target_compile_definitions(${target} PRIVATE VT_SANITIZER_THREAD)
    endif()
  endif()
  # Unity builds (VT_UNITY_BUILD): see the option's comment in CMakeLists.txt.
  set_target_properties(${target} PROPERTIES UNITY_BUILD ${VT_UNITY_BUILD})
  if(ARG_TEST_CODE)
    # Test code is built to compile fast rather than to run fast: the libraries under test keep
    # their own flags, and the test sources, about half of what a build compiles, take about a
    # half of their -O3 time and a third of their sanitized -O1 time (docs/PERFORMANCE.md "CI
    # time"). Test files whose own loops do the work are named LOOP_HEAVY in vt_test (-O1).
    target_compile_options(${target} PRIVATE -O0)
  endif()
endfunction()

# vt_library(NAME <lib> [DEPS ...] [PRIVATE_DEPS ...])
# One library per top-level folder: public headers in include/vt/<lib>/, sources in src/.
function(vt_library lib)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS;SOURCES" ${ARGN})
  if(ARG_SOURCES)
    set(srcs ${ARG_SOURCES})
  else()
    file(GLOB_RECURSE srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  endif()
  add_library(vt_${lib} STATIC ${srcs})
  add_library(vt::${lib} ALIAS vt_${lib})
  target_include_directories(vt_${lib} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
                             PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(vt_${lib} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  vt_target_settings(vt_${lib})
endfunction()

# vt_test(<lib> [DEPS ...] [LOOP_HEAVY <file>...]): tests/<lib>/*.cpp -> vt_<lib>_tests, each
# TEST_CASE a ctest; LOOP_HEAVY files are optimised (-O1, outside the precompiled header).
function(vt_test lib)
  cmake_parse_arguments(ARG "" "" "DEPS;LOOP_HEAVY" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  add_executable(vt_${lib}_tests ${srcs})
  target_link_libraries(vt_${lib}_tests PRIVATE vt_catch_main vt::${lib} ${ARG_DEPS})
  target_compile_definitions(vt_${lib}_tests PRIVATE
    VT_DATASET_DIR="${VT_DATASET_DIR}" VT_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    VT_TEST_OUTPUT_DIR="${CMAKE_BINARY_DIR}/test-output")
  vt_target_settings(vt_${lib}_tests TEST_CODE)
  # Catch2 and the standard headers every test file uses, parsed once per test program.
  target_precompile_headers(vt_${lib}_tests PRIVATE <catch2/catch.hpp> <algorithm> <array> <cmath>
                            <cstdint> <filesystem> <fstream> <sstream> <string> <vector>)
  set_source_files_properties(${ARG_LOOP_HEAVY} PROPERTIES COMPILE_OPTIONS -O1 SKIP_PRECOMPILE_HEADERS ON
                              SKIP_UNITY_BUILD_INCLUSION ON)
  # Test cases tagged hidden ([.desktop], [.window], ...) need a display or a fixture: they are
  # not discovered one by one but run by the ctest that provides it (vt_display_test).
  # --warn NoTests: a ctest whose name matches no test case fails instead of passing with nothing
  # run (discovery splits a test name at ';', and seven tests had run nowhere since they were named).
  catch_discover_tests(vt_${lib}_tests TEST_PREFIX "${lib}." EXTRA_ARGS --warn NoTests
                       PROPERTIES ENVIRONMENT "VT_LOG=warn" SKIP_RETURN_CODE ${VT_TEST_SKIP_CODE})
endfunction()

# vt_skipped_test(<name> <reason>): a test that cannot run in this build, listed as skipped with
# its reason, so that it does not silently vanish from the suite.
function(vt_skipped_test name reason)
  add_test(NAME ${name} COMMAND sh -c "echo 'SKIPPED: ${reason}'; exit ${VT_TEST_SKIP_CODE}")
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE ${VT_TEST_SKIP_CODE})
endfunction()

# The ctest resource of every test that starts a virtual X server (xvfb-run).
set(VT_XVFB_LOCK vt_xvfb)

# vt_display_test(NAME <name> SCREEN <WxHxD> COMMAND <cmd...>): COMMAND on a virtual X server
# (xvfb-run). Without xvfb-run the test is still there, and skipped, so it cannot vanish unseen.
# vt_display_test(NAME <name> ON_DISPLAY_OUTPUT COMMAND <cmd...>): COMMAND checks what display
# tests wrote (FIXTURES_REQUIRED); it needs no server itself and is skipped along with them.
function(vt_display_test)
  cmake_parse_arguments(ARG "ON_DISPLAY_OUTPUT" "NAME;SCREEN" "COMMAND" ${ARGN})
  find_program(XVFB_RUN xvfb-run)
  if(NOT XVFB_RUN)
    vt_skipped_test(${ARG_NAME} "xvfb-run not found (Debian package xvfb)")
  elseif(ARG_ON_DISPLAY_OUTPUT)
    add_test(NAME ${ARG_NAME} COMMAND ${ARG_COMMAND})
  else()
    add_test(NAME ${ARG_NAME} COMMAND ${XVFB_RUN} -a -s "-screen 0 ${ARG_SCREEN}" ${ARG_COMMAND})
    # One virtual X server at a time (xvfb-run -a takes the first display number without a lock
    # file: two starting together pick the same one); tests without a display run beside it.
    set_tests_properties(${ARG_NAME} PROPERTIES RESOURCE_LOCK ${VT_XVFB_LOCK})
  endif()
  set_tests_properties(${ARG_NAME} PROPERTIES SKIP_RETURN_CODE ${VT_TEST_SKIP_CODE})
endfunction()

# vt_require_pkg(<prefix> <pkg-config module> <Debian package>): PkgConfig::<prefix>, or a
# configure-time error naming the Debian package to install (scripts/install-deps.sh lists them).
function(vt_require_pkg prefix module package)
  if(NOT TARGET PkgConfig::${prefix})
    pkg_check_modules(${prefix} QUIET IMPORTED_TARGET GLOBAL ${module})
    if(NOT ${prefix}_FOUND)
      message(FATAL_ERROR "pkg-config module '${module}' not found: install the Debian package ${package} "
                          "(scripts/install-deps.sh installs every dependency)")
    endif()
  endif()
endfunction()
