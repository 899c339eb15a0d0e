# SPDX-License-Identifier: LGPL-2.1-or-later

# Runs a scene three times and checks that a restart continues a run as if
# it had not been interrupted:
#   full/  the uninterrupted run;
#   part/  the same run, interrupted by a test hook (a signal after a step,
#          or a kill in the middle of writing a checkpoint), then continued
#          with --restart part/checkpoint.
# The continued run must end with the uninterrupted run's files
# (compare_restart.py); or, with EXPECTED_RESTART_EXIT, the restart must be
# refused with that exit code and EXPECTED_MESSAGE.
#
#   cmake -DPROGRAM=<soft-robot> -DPARAMETER_FILE=<prm> -DWORK_DIRECTORY=<dir>
#         -DINTERRUPT=<NAME=value> -DINTERRUPTED_EXIT=<code|killed>
#         [-DOVERRIDES=<Subsection/Entry=value|...>]
#         [-DRESTART_OVERRIDES=<...>] [-DEXPECTED_RESTART_EXIT=<code>]
#         [-DEXPECTED_MESSAGE=<regex>] [-DLAUNCHER=<command|...>]
#         [-DRESTART_SERIAL=ON]
#         [-DCOMPARE=<command|...>] -P check_restart.cmake
#
# INTERRUPT is the environment variable of the test hook, set for the
# interrupted run only. OVERRIDES are passed to all runs as --set options,
# RESTART_OVERRIDES to the restart only; '%' stands for ';'. LAUNCHER
# (mpiexec -n 2) runs the program, except the restart with RESTART_SERIAL.
# COMPARE is run in the work directory with the arguments 'full part'.
file(REMOVE_RECURSE ${WORK_DIRECTORY})
file(MAKE_DIRECTORY ${WORK_DIRECTORY})

function(overrides_of list result)
  set(options)
  string(REPLACE "|" ";" entries "${list}")
  foreach(entry IN LISTS entries)
    if(NOT entry STREQUAL "")
      string(REPLACE "%" "\\;" entry "${entry}")
      list(APPEND options --set "${entry}")
    endif()
  endforeach()
  set(${result} "${options}" PARENT_SCOPE)
endfunction()

set(launcher)
if(DEFINED LAUNCHER)
  string(REPLACE "|" ";" launcher "${LAUNCHER}")
endif()
overrides_of("${OVERRIDES}" common)
overrides_of("${RESTART_OVERRIDES}" restart_only)

function(run_program label directory expected_exit)
  execute_process(COMMAND ${launcher} ${PROGRAM} ${PARAMETER_FILE} ${common}
                    --set "Problem/Output directory=${directory}" ${ARGN}
                  WORKING_DIRECTORY ${WORK_DIRECTORY}
                  RESULT_VARIABLE exit_code
                  OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message("--- ${label}:\n${output}")
  if(expected_exit STREQUAL "killed")
    if(exit_code MATCHES "^[0-9]+$" AND exit_code LESS 128)
      message(FATAL_ERROR "${label}: exit code ${exit_code}, expected a kill")
    endif()
  elseif(NOT exit_code EQUAL expected_exit)
    message(FATAL_ERROR "${label}: exit code ${exit_code}, expected ${expected_exit}")
  endif()
  set(last_output "${output}" PARENT_SCOPE)
endfunction()

run_program("uninterrupted run" full 0)

string(FIND "${INTERRUPT}" "=" equals)
string(SUBSTRING "${INTERRUPT}" 0 ${equals} variable)
math(EXPR equals "${equals} + 1")
string(SUBSTRING "${INTERRUPT}" ${equals} -1 value)
set(ENV{${variable}} "${value}")
run_program("interrupted run" part ${INTERRUPTED_EXIT})
unset(ENV{${variable}})
if(INTERRUPTED_EXIT EQUAL 4 AND NOT last_output MATCHES
   "The run was interrupted: SIGTERM at t = .* the checkpoint of this step is in 'part/checkpoint'. Continue the run with: soft-robot .* --restart part/checkpoint")
  message(FATAL_ERROR "the interrupted run does not say where its checkpoint is")
endif()

if(NOT DEFINED EXPECTED_RESTART_EXIT)
  set(EXPECTED_RESTART_EXIT 0)
endif()
if(RESTART_SERIAL)
  set(launcher)
endif()
run_program("restart" part ${EXPECTED_RESTART_EXIT} ${restart_only}
            --restart part/checkpoint)
if(DEFINED EXPECTED_MESSAGE AND NOT last_output MATCHES "${EXPECTED_MESSAGE}")
  message(FATAL_ERROR "the restart's output does not contain '${EXPECTED_MESSAGE}'")
endif()
if(last_output MATCHES "TimerOutput objects finalize")
  message(FATAL_ERROR "the output has deal.II's MPI banner")
endif()
if(EXPECTED_RESTART_EXIT EQUAL 0)
  # The quantities the state determines (stiffness, damping matrix,
  # Kelvin-Voigt viscosity) are assembled again at the restart; the forces
  # of the same assembly must be the stored ones, bit for bit.
  if(NOT last_output MATCHES "Restarted from the checkpoint of step [0-9]+ at t = [0-9.e-]+ s in 'part/checkpoint'; the forces of its state assembled again differ from the stored ones by 0\\.")
    message(FATAL_ERROR "the restart does not report its checkpoint, or its "
      "forces assembled again are not the stored ones")
  endif()
  string(REPLACE "|" ";" compare "${COMPARE}")
  execute_process(COMMAND ${compare} full part WORKING_DIRECTORY ${WORK_DIRECTORY}
                  RESULT_VARIABLE compare_code OUTPUT_VARIABLE compare_output
                  ERROR_VARIABLE compare_output)
  message("${compare_output}")
  if(NOT compare_code EQUAL 0)
    message(FATAL_ERROR "the continued run differs from the uninterrupted one")
  endif()
endif()
