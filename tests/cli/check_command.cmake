# SPDX-License-Identifier: LGPL-2.1-or-later

# Runs the simulator as a user would and checks what it leaves behind.
#
#   cmake -DPROGRAM=<soft-robot> [-DPARAMETER_FILE=<prm>] -DWORK_DIRECTORY=<dir>
#         -DEXPECTED_EXIT=<code|killed> [-DEXPECTED_MESSAGE=<regex>]
#         [-DFORBIDDEN_DIRECTORY=<dir>] [-DTRAJECTORY=<csv>]
#         [-DOVERRIDES=<Subsection/Entry=value|...>] [-DARGUMENTS=<a|b|...>]
#         [-DSEEDED_DIRECTORY=<dir>] [-DFULL_FILES=<dir/file|...>]
#         [-DENVIRONMENT=<NAME=value>] [-DLAUNCHER=<command|...>]
#         [-DCHECK=<command|...>] -P check_command.cmake
#
# OVERRIDES, separated by '|', are passed to the program as --set options,
# ARGUMENTS as they are (after the parameter file, if any); in both, '%'
# stands for ';' (the separator of the components of an expression, which
# CMake would take for the separator of a list).
# EXPECTED_MESSAGE must appear in what the program printed; FORBIDDEN_DIRECTORY
# must not exist afterwards (bad input leaves nothing behind); TRAJECTORY must
# exist, have at least two data rows and contain no 'nan' or 'inf'.
# SEEDED_DIRECTORY is filled with the files of an earlier run before the
# program runs and must be byte for byte the same afterwards (a run that fails
# its input must not touch an existing output directory). FULL_FILES are made
# symbolic links to /dev/full (a full disk for that file). ENVIRONMENT is set
# for the program (the test hooks); LAUNCHER runs it (mpiexec -n 2). CHECK is
# a command run in the work directory afterwards, which must succeed.
# EXPECTED_EXIT 'killed' expects the program to be killed by a signal.
file(REMOVE_RECURSE ${WORK_DIRECTORY})
file(MAKE_DIRECTORY ${WORK_DIRECTORY})

# The files of an earlier run, and their hashes.
set(seeded_files tip_trajectory.csv solution.pvd solution_00000.0.vtu
  solution_00000.pvtu run_statistics.json)
function(directory_state directory result)
  file(GLOB_RECURSE files RELATIVE ${directory} ${directory}/*)
  list(SORT files)
  set(state "")
  foreach(file IN LISTS files)
    file(SHA256 ${directory}/${file} hash)
    string(APPEND state "${file}:${hash};")
  endforeach()
  set(${result} "${state}" PARENT_SCOPE)
endfunction()
if(DEFINED SEEDED_DIRECTORY)
  set(seeded ${WORK_DIRECTORY}/${SEEDED_DIRECTORY})
  file(MAKE_DIRECTORY ${seeded})
  foreach(file IN LISTS seeded_files)
    file(WRITE ${seeded}/${file} "# ${file} of an earlier run\n0,1,2\n")
  endforeach()
  directory_state(${seeded} state_before)
endif()
if(DEFINED FULL_FILES)
  string(REPLACE "|" ";" full_files "${FULL_FILES}")
  foreach(file IN LISTS full_files)
    get_filename_component(parent ${WORK_DIRECTORY}/${file} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    file(CREATE_LINK /dev/full ${WORK_DIRECTORY}/${file} SYMBOLIC)
  endforeach()
endif()

set(command)
if(DEFINED LAUNCHER)
  string(REPLACE "|" ";" command "${LAUNCHER}")
endif()
if(DEFINED ENVIRONMENT)
  string(FIND "${ENVIRONMENT}" "=" equals)
  string(SUBSTRING "${ENVIRONMENT}" 0 ${equals} variable)
  math(EXPR equals "${equals} + 1")
  string(SUBSTRING "${ENVIRONMENT}" ${equals} -1 value)
  set(ENV{${variable}} "${value}")
endif()
list(APPEND command ${PROGRAM})
if(DEFINED PARAMETER_FILE)
  list(APPEND command ${PARAMETER_FILE})
endif()
if(DEFINED ARGUMENTS)
  string(REPLACE "|" ";" arguments "${ARGUMENTS}")
  list(APPEND command ${arguments})
endif()
if(DEFINED OVERRIDES)
  string(REPLACE "|" ";" overrides "${OVERRIDES}")
  foreach(override IN LISTS overrides)
    if(NOT override STREQUAL "")
      string(REPLACE "%" "\\;" override "${override}")
      list(APPEND command --set "${override}")
    endif()
  endforeach()
endif()
execute_process(COMMAND ${command}
                WORKING_DIRECTORY ${WORK_DIRECTORY}
                RESULT_VARIABLE exit_code
                OUTPUT_VARIABLE output
                ERROR_VARIABLE output)
message("${output}")
if(EXPECTED_EXIT STREQUAL "killed")
  if(exit_code MATCHES "^[0-9]+$" AND exit_code LESS 128)
    message(FATAL_ERROR "exit code ${exit_code}, expected a kill")
  endif()
elseif(NOT exit_code EQUAL EXPECTED_EXIT)
  message(FATAL_ERROR "exit code ${exit_code}, expected ${EXPECTED_EXIT}")
endif()
if(DEFINED EXPECTED_MESSAGE AND NOT output MATCHES "${EXPECTED_MESSAGE}")
  message(FATAL_ERROR "the output does not contain '${EXPECTED_MESSAGE}'")
endif()
if(output MATCHES "TimerOutput objects finalize")
  message(FATAL_ERROR "the output has deal.II's MPI banner")
endif()
if(DEFINED FORBIDDEN_DIRECTORY AND EXISTS ${WORK_DIRECTORY}/${FORBIDDEN_DIRECTORY})
  message(FATAL_ERROR "bad input left '${FORBIDDEN_DIRECTORY}' behind")
endif()
if(DEFINED SEEDED_DIRECTORY)
  directory_state(${seeded} state_after)
  if(NOT state_after STREQUAL state_before)
    message(FATAL_ERROR "the output directory '${SEEDED_DIRECTORY}' was changed:\n"
      "before: ${state_before}\nafter:  ${state_after}")
  endif()
endif()
if(DEFINED TRAJECTORY)
  file(STRINGS ${WORK_DIRECTORY}/${TRAJECTORY} rows REGEX "^[0-9]")
  list(LENGTH rows n_rows)
  if(n_rows LESS 2)
    message(FATAL_ERROR "the trajectory has ${n_rows} data rows")
  endif()
  string(TOLOWER "${rows}" lower)
  if(lower MATCHES "nan|inf")
    message(FATAL_ERROR "the trajectory contains a non-finite number")
  endif()
endif()
if(DEFINED CHECK)
  string(REPLACE "|" ";" check "${CHECK}")
  execute_process(COMMAND ${check} WORKING_DIRECTORY ${WORK_DIRECTORY}
                  RESULT_VARIABLE check_code OUTPUT_VARIABLE check_output
                  ERROR_VARIABLE check_output)
  message("${check_output}")
  if(NOT check_code EQUAL 0)
    message(FATAL_ERROR "the check '${CHECK}' failed")
  endif()
endif()
