# The training run of profile-guided optimisation (cmake/pgo.cmake), as
# `cmake -DFACECTL=... -DRIG=... -DSHOW=... -DOUT=... -DPROFILE=... -P pgo_train.cmake`:
# fresh counts for the instrumented facectl just built. A failed run leaves no
# profile, so the build goes on without one instead of stopping (a broken
# `simulate` must not keep the tests that would show why from building).
file(REMOVE_RECURSE ${PROFILE} ${OUT})
execute_process(
  COMMAND ${FACECTL} simulate --rig ${RIG} --show ${SHOW} --duration 60 --out ${OUT} --quiet
  RESULT_VARIABLE status
  OUTPUT_QUIET
  ERROR_VARIABLE errors)
if(NOT status EQUAL 0)
  file(REMOVE_RECURSE ${PROFILE})
  message(WARNING "facectl: the profile-guided optimisation's training run failed (${status}); "
                  "building without a profile.\n${errors}")
else()
  message(STATUS "facectl: profile written to ${PROFILE}")
endif()
