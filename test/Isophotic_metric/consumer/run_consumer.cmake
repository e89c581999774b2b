# Copyright (c) 2026 The Isophotic_metric developers.
# This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds and runs a project that uses the package as a user would (ctest runs it with cmake -P):
#   MODE=installed     installs the package into a prefix inside the build directory, moves the
#                      prefix (the config must be relocatable), then builds the getting-started
#                      program against it with find_package(Isophotic_metric)
#   MODE=subdirectory  builds subdirectory/, which adds the package's source tree with add_subdirectory
# Both check the compile commands: no flag of the package's own build (-march=native, warnings)
# reaches the user's program, and CGAL_LINKED_WITH_TBB does exactly when TBB is found (WITH_TBB).
# Inputs: MODE, SOURCE_DIR, BUILD_DIR (the package's build), WORK_DIR, MESH, WITH_TBB.
cmake_minimum_required(VERSION 3.16)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${output}")
  endif()
  set(last_output "${output}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
set(configure_options -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
if(MODE STREQUAL "installed")
  run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/staging")
  file(RENAME "${WORK_DIR}/staging" "${WORK_DIR}/prefix")
  set(project_dir "${SOURCE_DIR}/examples/Isophotic_metric/getting_started")
  set(program getting_started)
  list(APPEND configure_options "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix")
elseif(MODE STREQUAL "subdirectory")
  set(project_dir "${SOURCE_DIR}/test/Isophotic_metric/consumer/subdirectory")
  set(program consumer)
  list(APPEND configure_options "-DISOPHOTIC_METRIC_SOURCE_DIR=${SOURCE_DIR}")
else()
  message(FATAL_ERROR "MODE must be installed or subdirectory, not '${MODE}'")
endif()

run(${CMAKE_COMMAND} -S "${project_dir}" -B "${WORK_DIR}/build" ${configure_options})
run(${CMAKE_COMMAND} --build "${WORK_DIR}/build" -j 1)

file(READ "${WORK_DIR}/build/compile_commands.json" commands)
foreach(forbidden "-march=native" "-Wall" "-Wextra" "CGAL_DATA_DIR" "CGAL_ISOPHOTIC_METRIC_SOURCE_DIR")
  string(FIND "${commands}" "${forbidden}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the package pushes ${forbidden} into its user's program:\n${commands}")
  endif()
endforeach()
string(FIND "${commands}" "CGAL_LINKED_WITH_TBB" at)
if(WITH_TBB AND at EQUAL -1)
  message(FATAL_ERROR "TBB is found but the user's program is not built with CGAL_LINKED_WITH_TBB")
elseif(NOT WITH_TBB AND NOT at EQUAL -1)
  message(FATAL_ERROR "TBB is not found but the user's program has CGAL_LINKED_WITH_TBB")
endif()
if(MODE STREQUAL "installed")
  string(FIND "${commands}" "${SOURCE_DIR}/include" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the installed package points back to the source tree:\n${commands}")
  endif()
endif()

run("${WORK_DIR}/build/${program}" "${MESH}" "${WORK_DIR}/out.ply")
message(STATUS "${last_output}")
if(MODE STREQUAL "installed")
  # the PLY holds the distance per vertex and the colours per face
  file(STRINGS "${WORK_DIR}/out.ply" header LIMIT_COUNT 40)
  foreach(expected "property double distance" "property uchar red")
    if(NOT header MATCHES "${expected}")
      message(FATAL_ERROR "${WORK_DIR}/out.ply lacks '${expected}':\n${header}")
    endif()
  endforeach()
endif()
