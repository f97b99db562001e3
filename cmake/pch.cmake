# Precompiled headers for the tests and the tools (MIRROR_PCH, on by default; README.md, "Building").
#
# Two precompiled headers, each compiled once per build and shared (REUSE_FROM) by every target of
# its kind: GoogleTest, the standard library, Eigen and OpenCV's core for the test executables
# (most of a test file's compile time was reading these), and the standard library, Eigen and
# OpenCV's core for the tools. The product's libraries and `mirror` take none: their includes
# stay exactly what each file says. GCC checks that a precompiled header was made with compatible
# options (-Winvalid-pch, an error with MIRROR_WERROR): a target whose flags do not fit fails to
# build instead of silently compiling the slow way.
#
# Included at the end of the top-level CMakeLists.txt: mirror_use_pch() walks the targets already
# defined. The test executables are the targets that link GoogleTest's main; the tools' targets
# are every other target under tools/.
option(MIRROR_PCH "Precompiled headers for the tests and the tools (GCC or clang)" ON)

# Every buildsystem target defined in DIR and its subdirectories.
function(_mirror_targets_under dir out)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub ${subdirs})
    _mirror_targets_under(${sub} more)
    list(APPEND targets ${more})
  endforeach()
  set(${out} ${targets} PARENT_SCOPE)
endfunction()

# A target that compiles only the precompiled header (an empty source file, as CMake needs one).
function(_mirror_pch_host name)
  set(anchor ${CMAKE_BINARY_DIR}/pch/${name}.cpp)
  file(CONFIGURE OUTPUT ${anchor} CONTENT "// Compiles only ${name}'s precompiled header.\n")
  add_library(${name} OBJECT ${anchor})
  target_link_libraries(${name} PRIVATE mirror_warnings ${ARGN})
  target_precompile_headers(${name} PRIVATE
    <algorithm> <array> <chrono> <cmath> <cstdint> <cstdio> <cstdlib> <cstring> <filesystem>
    <fstream> <functional> <memory> <random> <sstream> <stdexcept> <string> <thread> <vector>
    <Eigen/Core> <Eigen/Geometry>)
  if(NOT MIRROR_VISION_ONLY)
    target_precompile_headers(${name} PRIVATE
      <opencv2/core.hpp> <opencv2/imgproc.hpp> <opencv2/imgcodecs.hpp>)
  endif()
endfunction()

function(mirror_use_pch)
  # Built and tested whole in the native Release build only. The sanitizer preset turns it off
  # and the arm64 cross build takes none until each has been built whole with it: GCC 12's false
  # -Warray-bounds inside libstdc++ came out in two files with it (tests/CMakeLists.txt,
  # tools/overlaygen/CMakeLists.txt), and other flags may bring others.
  if(NOT MIRROR_PCH OR CMAKE_CROSSCOMPILING)
    return()
  endif()
  _mirror_targets_under(${PROJECT_SOURCE_DIR} targets)
  set(opencv "")
  if(NOT MIRROR_VISION_ONLY)
    set(opencv opencv_core)
  endif()

  if(MIRROR_BUILD_TESTS)
    _mirror_pch_host(mirror_test_pch GTest::gtest Eigen3::Eigen ${opencv})
    target_precompile_headers(mirror_test_pch PRIVATE <gtest/gtest.h>)
    # The test code is compiled at -O1 in Release (tests/CMakeLists.txt): so is its header.
    target_compile_options(mirror_test_pch PRIVATE $<$<CONFIG:Release>:-O1>)
    foreach(t ${targets})
      get_target_property(libs ${t} LINK_LIBRARIES)
      if("GTest::gtest_main" IN_LIST libs)
        target_precompile_headers(${t} REUSE_FROM mirror_test_pch)
        list(REMOVE_ITEM targets ${t})
      endif()
    endforeach()
  endif()

  if(TARGET mirror_tool_cli AND MIRROR_BUILD_TOOLS)
    # Not CLI11: its header defines namespace-scope validator objects that every file including
    # it constructs, seconds of code generation each, precompiled or not (8 of 78 files use it).
    _mirror_pch_host(mirror_tool_pch Eigen3::Eigen ${opencv})
    foreach(t ${targets})
      get_target_property(dir ${t} SOURCE_DIR)
      get_target_property(type ${t} TYPE)
      if(dir MATCHES "^${PROJECT_SOURCE_DIR}/tools/" AND type MATCHES "EXECUTABLE|STATIC_LIBRARY")
        target_precompile_headers(${t} REUSE_FROM mirror_tool_pch)
      endif()
    endforeach()
  endif()
endfunction()
