# Runs the simulator as a user would and checks what it leaves behind.
#
#   cmake -DPROGRAM=<soft-robot> -DPARAMETER_FILE=<prm> -DWORK_DIRECTORY=<dir>
#         -DEXPECTED_EXIT=<code> [-DEXPECTED_MESSAGE=<regex>]
#         [-DFORBIDDEN_DIRECTORY=<dir>] [-DTRAJECTORY=<csv>]
#         [-DOVERRIDES=<Subsection/Entry=value|...>] -P check_command.cmake
#
# OVERRIDES, separated by '|', are passed to the program as --set options.
# EXPECTED_MESSAGE must appear in what the program printed; FORBIDDEN_DIRECTORY
# must not exist afterwards (bad input leaves nothing behind); TRAJECTORY must
# exist, have at least two data rows and contain no 'nan' or 'inf'.
file(REMOVE_RECURSE ${WORK_DIRECTORY})
file(MAKE_DIRECTORY ${WORK_DIRECTORY})
set(arguments)
if(DEFINED OVERRIDES)
  string(REPLACE "|" ";" overrides "${OVERRIDES}")
  foreach(override IN LISTS overrides)
    list(APPEND arguments --set "${override}")
  endforeach()
endif()
execute_process(COMMAND ${PROGRAM} ${PARAMETER_FILE} ${arguments}
                WORKING_DIRECTORY ${WORK_DIRECTORY}
                RESULT_VARIABLE exit_code
                OUTPUT_VARIABLE output
                ERROR_VARIABLE output)
message("${output}")
if(NOT exit_code EQUAL EXPECTED_EXIT)
  message(FATAL_ERROR "exit code ${exit_code}, expected ${EXPECTED_EXIT}")
endif()
if(DEFINED EXPECTED_MESSAGE AND NOT output MATCHES "${EXPECTED_MESSAGE}")
  message(FATAL_ERROR "the output does not contain '${EXPECTED_MESSAGE}'")
endif()
if(DEFINED FORBIDDEN_DIRECTORY AND EXISTS ${WORK_DIRECTORY}/${FORBIDDEN_DIRECTORY})
  message(FATAL_ERROR "bad input left '${FORBIDDEN_DIRECTORY}' behind")
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
