# Profile-guided optimisation of facectl (GCC 11 or later, single-configuration
# optimised native builds; docs/PERFORMANCE.md, "Offline simulation").
#
# Off by default: a first build then compiles once. `make bench` turns it on
# (-DFACECTL_PGO=ON) for the fully optimised build the benchmarks measure.
# With it, the main build first builds an instrumented facectl in a sub-build of the
# same sources and flags (build/pgo/build), runs it on 60 s of the demo show
# offline (`facectl simulate`, the default rig; cmake/pgo_train.cmake), and
# then compiles every target with the counts that run wrote (build/pgo/profile).
# With -fprofile-partial-training, functions the training never runs (the
# real-time loop's threads, the hardware drivers) are optimised as without a
# profile, not for size; inside the functions it does run, branches it never
# takes (fault and stale-input paths) are still laid out as cold code.
#
# A profile changes which code is inlined, unrolled and laid out where, never
# an operation's result: no fast-math, no reassociation, so the outputs are the
# same bytes as without it (scripts/compare_simulate_outputs.sh).
#
# The sub-build runs on every build (BUILD_ALWAYS): after an edit it recompiles
# the edited files instrumented and retrains (about a second), so the profile
# always matches the sources. If the training run fails, the build goes on
# without a profile (a warning says so).

option(FACECTL_PGO "Optimise with a profile of a simulated show (GCC, optimised builds)" OFF)
# Set only in the instrumented sub-build: where its objects write their counts.
set(FACECTL_PGO_GENERATE "" CACHE PATH "Internal: build instrumented, writing the profile here")
mark_as_advanced(FACECTL_PGO_GENERATE)

set(FACECTL_PGO_ACTIVE OFF)
get_property(facectl_multi_config GLOBAL PROPERTY GENERATOR_IS_MULTI_CONFIG)
string(TOUPPER "${CMAKE_BUILD_TYPE}" facectl_build_type)
if(FACECTL_PGO_GENERATE)
  # Object names are kept relative to the build folder, so that the main
  # build (another folder) finds each object's counts.
  add_compile_options(-fprofile-generate=${FACECTL_PGO_GENERATE} -fprofile-update=single
                      -fprofile-prefix-path=${PROJECT_BINARY_DIR})
  add_link_options(-fprofile-generate=${FACECTL_PGO_GENERATE})
elseif(NOT FACECTL_PGO)
  # Off by request.
elseif(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU" OR CMAKE_CXX_COMPILER_VERSION VERSION_LESS 11
       OR facectl_multi_config OR CMAKE_CROSSCOMPILING
       OR NOT facectl_build_type MATCHES "^(RELEASE|RELWITHDEBINFO)$")
  message(STATUS "facectl: no profile-guided optimisation (it needs GCC 11 or later, a "
                 "single-configuration generator, a native build and Release or RelWithDebInfo)")
else()
  set(FACECTL_PGO_ACTIVE ON)
  set(facectl_pgo_dir ${PROJECT_BINARY_DIR}/pgo)
  # A list travels to the sub-build with | between its items (LIST_SEPARATOR).
  string(REPLACE ";" "|" facectl_prefix_path "${CMAKE_PREFIX_PATH}")
  # The same compiler and flags as this build, so that every function's
  # control flow, and so its profile, matches.
  set(facectl_pgo_args
      -DCMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE}
      -DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}
      "-DCMAKE_CXX_FLAGS=${CMAKE_CXX_FLAGS}"
      "-DCMAKE_CXX_FLAGS_${facectl_build_type}=${CMAKE_CXX_FLAGS_${facectl_build_type}}"
      "-DCMAKE_PREFIX_PATH=${facectl_prefix_path}"
      -DFACECTL_PGO=OFF
      -DFACECTL_LTO=OFF
      -DFACECTL_BUILD_TESTS=OFF
      -DFACECTL_WERROR=${FACECTL_WERROR}
      -DFACECTL_PGO_GENERATE=${facectl_pgo_dir}/profile)
  if(CMAKE_CXX_COMPILER_LAUNCHER)
    list(APPEND facectl_pgo_args -DCMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER})
  endif()
  include(ExternalProject)
  ExternalProject_Add(facectl_pgo_profile
    SOURCE_DIR ${PROJECT_SOURCE_DIR}
    BINARY_DIR ${facectl_pgo_dir}/build
    PREFIX ${facectl_pgo_dir}/prefix
    CMAKE_GENERATOR ${CMAKE_GENERATOR}
    LIST_SEPARATOR |
    CMAKE_ARGS ${facectl_pgo_args}
    BUILD_COMMAND ${CMAKE_COMMAND} --build ${facectl_pgo_dir}/build --target facectl
    BUILD_ALWAYS ON
    INSTALL_COMMAND ${CMAKE_COMMAND}
        -DFACECTL=${facectl_pgo_dir}/build/firmware-host/facectl
        -DRIG=${PROJECT_SOURCE_DIR}/config/rigs/default.yaml
        -DSHOW=${PROJECT_SOURCE_DIR}/config/shows/demo.yaml
        -DOUT=${facectl_pgo_dir}/run
        -DPROFILE=${facectl_pgo_dir}/profile
        -P ${PROJECT_SOURCE_DIR}/cmake/pgo_train.cmake
    USES_TERMINAL_BUILD ON)
  # A missing profile (an object the training does not link, a failed
  # training) or a stale one is a reason to optimise less, not to stop.
  add_compile_options(-fprofile-use=${facectl_pgo_dir}/profile -fprofile-partial-training
                      -fprofile-prefix-path=${PROJECT_BINARY_DIR} -Wno-missing-profile
                      -Wno-error=coverage-mismatch)
endif()

# Every target compiles after the training run (call after the targets exist).
function(facectl_after_pgo_training)
  if(NOT FACECTL_PGO_ACTIVE)
    return()
  endif()
  get_property(dirs DIRECTORY ${PROJECT_SOURCE_DIR} PROPERTY SUBDIRECTORIES)
  set(targets)
  while(dirs)
    list(POP_FRONT dirs dir)
    get_property(sub DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
    get_property(own DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
    list(APPEND dirs ${sub})
    list(APPEND targets ${own})
  endwhile()
  foreach(t IN LISTS targets)
    get_target_property(type ${t} TYPE)
    if(type MATCHES "^(STATIC_LIBRARY|SHARED_LIBRARY|OBJECT_LIBRARY|MODULE_LIBRARY|EXECUTABLE)$")
      add_dependencies(${t} facectl_pgo_profile)
    endif()
  endforeach()
endfunction()
