# Shared build settings for every semchain target.

function(semchain_set_warnings target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  # Unity builds: the files of a target are compiled in batches, so that the heavy headers they
  # share (Eigen, OpenCV, Ceres, gtest, CLI11, spdlog, ROS) are parsed and their inline code
  # compiled once per batch, not once per file; a fresh build (CI's) takes half the time.
  # -DSEMCHAIN_UNITY_BUILD=OFF compiles file by file (faster for small incremental changes).
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF UNITY_BUILD ${SEMCHAIN_UNITY_BUILD}
                                             UNITY_BUILD_BATCH_SIZE 8)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    # GCC 12 reports -Wrestrict false positives inside libstdc++'s std::string at -O3 (GCC bug
    # 105329), the more often the more code a file inlines (unity batches).
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(SEMCHAIN_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# semchain_add_module(NAME SOURCES ... DEPS ...): one static library per folder under src/.
function(semchain_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(semchain_${name} STATIC ${ARG_SOURCES})
  add_library(semchain::${name} ALIAS semchain_${name})
  target_include_directories(semchain_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(semchain_${name} PUBLIC ${ARG_DEPS})
  semchain_set_warnings(semchain_${name})
endfunction()

# semchain_add_test(NAME SOURCES ... DEPS ...): a GoogleTest program registered with CTest.
function(semchain_add_test name)
  if(NOT BUILD_TESTING)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    SEMCHAIN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SEMCHAIN_SHARED_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/data")
  semchain_set_warnings(${name})
  # Label "unit" for the tests beside the code in src/, "e2e" for tests/ (ctest -L / -LE).
  string(FIND "${CMAKE_CURRENT_SOURCE_DIR}/" "${PROJECT_SOURCE_DIR}/src/" in_src)
  if(in_src EQUAL 0)
    set(label unit)
  else()
    set(label e2e)
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600 LABELS ${label})
endfunction()

# semchain_add_benchmark(NAME SOURCES ... DEPS ...): a Google Benchmark program under bench/.
function(semchain_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark)
  target_compile_definitions(${name} PRIVATE SEMCHAIN_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  semchain_set_warnings(${name})
endfunction()

# SEMCHAIN_FUZZ=ON: every library is instrumented for libFuzzer's coverage and built with
# AddressSanitizer and UndefinedBehaviorSanitizer (undefined behaviour aborts, so that the fuzzer
# sees it as a crash); the app, tests and benchmarks are left out (fuzz/README.md). ROS stays in
# where it is found, for the bag_import target (ROS's own libraries are not instrumented).
macro(semchain_enable_fuzzing)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "SEMCHAIN_FUZZ needs clang (CXX=clang++ cmake ...; scripts/fuzz.sh does this)")
  endif()
  set(BUILD_TESTING OFF CACHE BOOL "" FORCE)
  set(BUILD_BENCHMARKS OFF CACHE BOOL "" FORCE)
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                      -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=address,undefined)
endmacro()

# SEMCHAIN_SANITIZE=ON: the libraries, their unit tests and the fuzz replays with AddressSanitizer
# and UndefinedBehaviorSanitizer (GCC or clang), at -O1 so that the tests stay fast; undefined
# behaviour aborts the test. The app, the end-to-end tests, benchmarks and ROS are left out. No
# debug information, so that it compiles and links faster: reports name the functions; for file
# and line numbers add it (scripts/test_sanitizers.sh -DCMAKE_CXX_FLAGS_DEBUG=-g).
macro(semchain_enable_sanitizers)
  set(BUILD_TESTING ON CACHE BOOL "" FORCE)
  set(BUILD_BENCHMARKS OFF CACHE BOOL "" FORCE)
  set(SEMCHAIN_WITH_ROS OFF CACHE BOOL "" FORCE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all
                      -fno-omit-frame-pointer -O1)
  add_link_options(-fsanitize=address,undefined)
endmacro()

# semchain_add_fuzz_target(NAME DEPS ...): fuzz/NAME_fuzzer.cc as the libFuzzer program
# fuzz_NAME (SEMCHAIN_FUZZ=ON), or else as fuzz_replay_NAME, a test that replays the target's
# corpus and kept crashes (fuzz/corpus/NAME, fuzz/crashes/NAME) under the normal build.
function(semchain_add_fuzz_target name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  set(sources ${name}_fuzzer.cc fuzz_input.cc)
  if(SEMCHAIN_FUZZ)
    set(program fuzz_${name})
    add_executable(${program} ${sources})
    target_link_options(${program} PRIVATE -fsanitize=fuzzer)
  elseif(BUILD_TESTING)
    set(program fuzz_replay_${name})
    add_executable(${program} ${sources} replay_main.cc)
    add_test(NAME ${program} COMMAND ${program} ${CMAKE_CURRENT_SOURCE_DIR}/corpus/${name}
                                                ${CMAKE_CURRENT_SOURCE_DIR}/crashes/${name})
    set_tests_properties(${program} PROPERTIES LABELS "unit;fuzz_replay" TIMEOUT 120)
  else()
    return()
  endif()
  target_include_directories(${program} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(${program} PRIVATE ${ARG_DEPS})
  semchain_set_warnings(${program})
  set_target_properties(${program} PROPERTIES UNITY_BUILD OFF)
endfunction()
