# ctest -L install: `cmake --install` into a temporary prefix, then
#   1. the installed headers are self-contained (no internal/ header, every quoted include is
#      installed) and the package files, libraries, binary and assets are where the README says;
#   2. tests/install (a separate project: find_package(topoplan)) configures, builds and runs
#      against the prefix;
#   3. the prefix is moved elsewhere (the original removed) and its topoplan binary runs from
#      another folder without TOPOPLAN_ASSETS: it must find its assets next to itself. A scenario
#      that exists only in the moved copy proves the installed tree is the one used (the source
#      tree's assets/ folder, baked in as the last fallback, does not have it). Where unshare(1)
#      may create a mount namespace, the source tree's assets/ is also hidden for one run.
# Variables: BUILD_DIR, SOURCE_ASSETS (the source tree's assets/), CONSUMER_DIR (tests/install),
# WORK_DIR, LIBDIR, CXX_COMPILER, COMPILER_LAUNCHER (may be empty), SCENARIO (a quick scenario of
# assets/scenarios, without .json).
cmake_minimum_required(VERSION 3.25)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# 1. Layout.
foreach(f
    ${LIBDIR}/cmake/topoplan/topoplanConfig.cmake
    ${LIBDIR}/cmake/topoplan/topoplanConfigVersion.cmake
    ${LIBDIR}/cmake/topoplan/topoplanTargets.cmake
    ${LIBDIR}/libtopology.a ${LIBDIR}/librender.a ${LIBDIR}/libplanning.a
    ${LIBDIR}/libplanning_physics.a
    include/topology/writhe.h include/planning/robot/kinematics.h include/render/renderer.h
    include/planning/physics/ode_runtime.h
    bin/topoplan bin/topoplan-full share/topoplan/scenarios/unwrap.json
    share/topoplan/robots/arm20_sdh.urdf)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${prefix}/${f}")
  endif()
endforeach()
file(GLOB_RECURSE headers RELATIVE ${prefix}/include ${prefix}/include/*)
foreach(h IN LISTS headers)
  if(h MATCHES "/internal/" OR NOT h MATCHES "\\.h$")
    message(FATAL_ERROR "installed although not a public header: include/${h}")
  endif()
  file(STRINGS ${prefix}/include/${h} includes REGEX "^#include \"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" inc "${line}")
    if(NOT EXISTS ${prefix}/include/${inc})
      message(FATAL_ERROR "include/${h} includes \"${inc}\", which is not installed")
    endif()
  endforeach()
endforeach()

# 2. A consumer project.
set(consumer ${WORK_DIR}/consumer)
set(launcher)
if(COMPILER_LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${COMPILER_LAUNCHER})
endif()
run(${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${consumer} -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} ${launcher})
run(${CMAKE_COMMAND} --build ${consumer})
execute_process(COMMAND ${consumer}/consumer ${prefix}/share/topoplan RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE out)
message(STATUS "consumer:\n${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer failed (${rc})")
endif()

# 3. The binary, moved away from both the build and the original prefix.
set(moved ${WORK_DIR}/moved)
file(COPY ${prefix}/ DESTINATION ${moved})
file(REMOVE_RECURSE ${prefix})
file(COPY_FILE ${moved}/share/topoplan/scenarios/${SCENARIO}.json
     ${moved}/share/topoplan/scenarios/installed_copy_only.json)
file(MAKE_DIRECTORY ${WORK_DIR}/elsewhere)
unset(ENV{TOPOPLAN_ASSETS})
execute_process(COMMAND ${moved}/bin/topoplan --help WORKING_DIRECTORY ${WORK_DIR}/elsewhere
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "plan")
  message(FATAL_ERROR "topoplan --help failed (${rc}):\n${out}")
endif()
run(${moved}/bin/topoplan plan installed_copy_only -o ${WORK_DIR}/elsewhere/plan
    WORKING_DIRECTORY ${WORK_DIR}/elsewhere)
if(NOT EXISTS ${WORK_DIR}/elsewhere/plan/report.json)
  message(FATAL_ERROR "topoplan plan wrote no report.json")
endif()
file(MAKE_DIRECTORY ${WORK_DIR}/no_assets)
# Where a private mount namespace is allowed, also hide the source tree's assets/ outright (an
# empty folder mounted over it, for this one process) and plan a scenario of the installed tree.
find_program(UNSHARE unshare)
set(hide [[mount --bind "$1" "$2" && cd "$3" && shift 3 && exec "$@"]])
set(rc 1)
if(UNSHARE)
  execute_process(COMMAND ${UNSHARE} -rm sh -c "${hide}" sh ${WORK_DIR}/no_assets ${SOURCE_ASSETS}
                          ${WORK_DIR} ls -A ${SOURCE_ASSETS}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_QUIET)
endif()
if(rc EQUAL 0 AND out STREQUAL "")
  run(${UNSHARE} -rm sh -c "${hide}" sh ${WORK_DIR}/no_assets ${SOURCE_ASSETS}
      ${WORK_DIR}/elsewhere ${moved}/bin/topoplan plan ${SCENARIO} -o ${WORK_DIR}/elsewhere/hidden)
  message(STATUS "topoplan plan ${SCENARIO} ran with ${SOURCE_ASSETS} hidden")
else()
  message(STATUS "no private mount namespace: ${SOURCE_ASSETS} not hidden (the check with a "
                 "scenario only the installed tree has holds regardless)")
endif()
# $TOPOPLAN_ASSETS comes first: an empty asset folder hides the installed one.
set(ENV{TOPOPLAN_ASSETS} ${WORK_DIR}/no_assets)
execute_process(COMMAND ${moved}/bin/topoplan plan installed_copy_only -o ${WORK_DIR}/elsewhere/x
                WORKING_DIRECTORY ${WORK_DIR}/elsewhere RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE out)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "TOPOPLAN_ASSETS=<empty folder>: expected exit 2, got ${rc}:\n${out}")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
