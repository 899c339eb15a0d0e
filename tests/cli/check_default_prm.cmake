# SPDX-License-Identifier: LGPL-2.1-or-later

# parameters/default.prm must be what 'soft-robot --print-parameters' prints.
execute_process(COMMAND ${PROGRAM} --print-parameters OUTPUT_FILE ${GENERATED}
                RESULT_VARIABLE exit_code)
if(NOT exit_code EQUAL 0)
  message(FATAL_ERROR "--print-parameters failed with ${exit_code}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${GENERATED} ${REFERENCE}
                RESULT_VARIABLE different)
if(different)
  message(FATAL_ERROR "parameters/default.prm is out of date: regenerate it "
                      "with 'soft-robot --print-parameters > parameters/default.prm'")
endif()
