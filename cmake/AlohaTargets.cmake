# Helpers that give every ALOHA layer the same settings: aloha:: alias, include paths for the
# build and install trees, warnings as errors for our own code, install into the export set.
set(ALOHA_LAYER_TARGETS "" CACHE INTERNAL "")

function(aloha_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Werror)
  endif()
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # GCC 12 at -O3 reports std::string copies as overlapping memcpy (GCC bug 105329): a false positive.
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
endfunction()

# aloha_library_defaults(<target> <short-name>): alias aloha::<short-name>, includes, warnings, install.
function(aloha_library_defaults target short)
  add_library(aloha::${short} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${short} OUTPUT_NAME aloha_${short})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<BUILD_INTERFACE:${ALOHA_PREFIXED_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/aloha>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  aloha_warnings(${target})
  # A build with sanitizers (the asan-ubsan preset's CMAKE_CXX_FLAGS) installs libraries that call their
  # runtimes: the installed targets carry the link option, so a consumer of the package links them.
  if(CMAKE_CXX_FLAGS MATCHES "-fsanitize=([a-z,]+)")
    target_link_options(${target} INTERFACE $<INSTALL_INTERFACE:-fsanitize=${CMAKE_MATCH_1}>)
  endif()
  install(TARGETS ${target} EXPORT alohaTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  set(ALOHA_LAYER_TARGETS ${ALOHA_LAYER_TARGETS} ${target} CACHE INTERNAL "")
endfunction()

# aloha_interface_defaults(<target> <short-name>): the same for header-only layers.
function(aloha_interface_defaults target short)
  add_library(aloha::${short} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${short})
  target_include_directories(${target} INTERFACE
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<BUILD_INTERFACE:${ALOHA_PREFIXED_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/aloha>)
  target_compile_features(${target} INTERFACE cxx_std_20)
  install(TARGETS ${target} EXPORT alohaTargets)
  set(ALOHA_LAYER_TARGETS ${ALOHA_LAYER_TARGETS} ${target} CACHE INTERNAL "")
endfunction()

# aloha_test_asset_defaults(<target>): what tests and benchmarks share. ALOHA_SOURCE_DIR is the repository;
# ALOHA_DEFAULT_TEST_ASSETS the folder of third-party test assets (CMU BVH, Khronos glTF samples), which
# are never in the repository (tests/common/test_assets.hpp; $ALOHA_TEST_ASSETS overrides it at run time).
# The repository root is on the include path for "tests/common/..." helpers.
function(aloha_test_asset_defaults target)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR})
  target_compile_definitions(${target} PRIVATE
    ALOHA_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    ALOHA_DEFAULT_TEST_ASSETS="${PROJECT_SOURCE_DIR}/../shared/assets")
endfunction()

# aloha_test(<name> SOURCES ... LIBS ...): a GoogleTest executable registered with CTest; its main() is
# tests/common/test_main.cpp (target aloha_test_main, made in tests/CMakeLists.txt).
function(aloha_test name)
  cmake_parse_arguments(T "" "" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} aloha_test_main GTest::gtest)
  aloha_warnings(${name})
  aloha_test_asset_defaults(${name})
  # GoogleTest's header alone costs ~1.6 s of every test source: the common headers are compiled once per test
  # program instead (render_tests' 16 sources: 54 -> 16 s of compiler CPU). With them precompiled, GCC 12's
  # middle-end reports its known false bounds warnings on std::string's operator+ with a temporary (the inlined
  # char_traits::copy of the SSO buffer: -Warray-bounds, -Wstringop-overflow, -Wstringop-overread), so test
  # programs built by GCC do without those three; product code keeps them.
  # The first test program compiles the header once; every later one reuses it (same flags and definitions:
  # they differ only in macros the header does not use, and -Winvalid-pch with -Werror fails a build whose
  # reuse GCC rejects). ~6-8 s of compiler CPU per test program saved.
  get_property(pch_host GLOBAL PROPERTY ALOHA_TEST_PCH_HOST)
  if(pch_host)
    target_precompile_headers(${name} REUSE_FROM ${pch_host})
  else()
    set_property(GLOBAL PROPERTY ALOHA_TEST_PCH_HOST ${name})
    target_precompile_headers(${name} PRIVATE <gtest/gtest.h> <glm/glm.hpp> <cstdint> <memory> <span> <string> <vector>)
  endif()
  target_compile_options(${name} PRIVATE $<$<CXX_COMPILER_ID:GNU>:-Wno-array-bounds -Wno-stringop-overflow -Wno-stringop-overread>)
  include(GoogleTest)
  # One label per test binary: gtest_discover_tests cannot pass a list through PROPERTIES.
  set(label "")
  if(T_LABELS)
    list(GET T_LABELS 0 label)
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${label}")
endfunction()

# aloha_bench(<name> SOURCES ... LIBS ...): a Google Benchmark program (built, not run by CI).
function(aloha_bench name)
  cmake_parse_arguments(B "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${B_SOURCES})
  target_link_libraries(${name} PRIVATE ${B_LIBS} benchmark::benchmark)
  aloha_warnings(${name})
  aloha_test_asset_defaults(${name})
endfunction()
