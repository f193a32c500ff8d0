# Profile-guided optimisation of facectl (GCC, single-configuration optimised
# builds; docs/PERFORMANCE.md, "Offline simulation").
#
# The main build first builds an instrumented facectl in a sub-build of the
# same sources (build/pgo/build), runs it on 60 s of the demo show offline
# (`facectl simulate`, the default rig), and then compiles every target with
# the counts that run wrote (build/pgo/profile). With -fprofile-partial-training
# the code the training does not reach (the real-time loop's threads, the
# hardware drivers) is optimised as without a profile, not for size.
#
# A profile changes which code is inlined, unrolled and laid out where, never
# an operation's result: no fast-math, no reassociation, so the outputs are the
# same bytes as without it (scripts/compare_simulate_outputs.sh).
#
# The sub-build runs on every build (BUILD_ALWAYS): after an edit it recompiles
# the edited files instrumented and retrains (about a second), so the profile
# always matches the sources. -DFACECTL_PGO=OFF builds once, without a profile.

option(FACECTL_PGO "Optimise with a profile of a simulated show (GCC, optimised builds)" ON)
# Set only in the instrumented sub-build: where its objects write their counts.
set(FACECTL_PGO_GENERATE "" CACHE PATH "Internal: build instrumented, writing the profile here")
mark_as_advanced(FACECTL_PGO_GENERATE)

set(FACECTL_PGO_ACTIVE OFF)
if(FACECTL_PGO_GENERATE)
  # Object names are kept relative to the build folder, so that the main
  # build (another folder) finds each object's counts.
  add_compile_options(-fprofile-generate=${FACECTL_PGO_GENERATE} -fprofile-update=single
                      -fprofile-prefix-path=${CMAKE_BINARY_DIR})
  add_link_options(-fprofile-generate=${FACECTL_PGO_GENERATE})
elseif(FACECTL_PGO AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU"
       AND CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo)$")
  set(FACECTL_PGO_ACTIVE ON)
  set(facectl_pgo_dir ${CMAKE_BINARY_DIR}/pgo)
  set(facectl_pgo_args
      -DCMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE}
      -DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}
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
    CMAKE_ARGS ${facectl_pgo_args}
    BUILD_COMMAND ${CMAKE_COMMAND} --build ${facectl_pgo_dir}/build --target facectl
    BUILD_ALWAYS ON
    # The training run: fresh counts for the sources just built.
    INSTALL_COMMAND ${CMAKE_COMMAND} -E rm -rf ${facectl_pgo_dir}/profile ${facectl_pgo_dir}/run
    COMMAND ${facectl_pgo_dir}/build/firmware-host/facectl simulate
            --rig ${PROJECT_SOURCE_DIR}/config/rigs/default.yaml
            --show ${PROJECT_SOURCE_DIR}/config/shows/demo.yaml
            --duration 60 --out ${facectl_pgo_dir}/run --quiet
    USES_TERMINAL_BUILD ON)
  add_compile_options(-fprofile-use=${facectl_pgo_dir}/profile -fprofile-partial-training
                      -fprofile-prefix-path=${CMAKE_BINARY_DIR} -Wno-missing-profile)
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
