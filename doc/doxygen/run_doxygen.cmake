# SPDX-License-Identifier: LGPL-2.1-or-later

# The commands of the target `doc` (doc/CMakeLists.txt), run in the build's
# doc/ directory:
#
#   cmake -DPYTHON=... -DDOXYGEN=... -DSOURCE_DIR=... -P run_doxygen.cmake
#
# Writes the pages (pages/), runs doxygen on them (html/) and fails if the
# converter reports a problem or doxygen a warning, which it prints with
# the file and line of the source. The stamp file doc.stamp is written on
# success only, so that a failed build is repeated.

set(_script ${SOURCE_DIR}/doc/doxygen/annotated_source.py)
file(REMOVE doc.stamp warnings.log)

execute_process(COMMAND ${PYTHON} ${_script} ${SOURCE_DIR} pages
  RESULT_VARIABLE _result)
if(NOT _result EQUAL 0)
  message(FATAL_ERROR "doc: the annotated source could not be converted (above).")
endif()

execute_process(COMMAND ${DOXYGEN} ${SOURCE_DIR}/doc/doxygen/Doxyfile
  RESULT_VARIABLE _result)
if(NOT _result EQUAL 0)
  message(FATAL_ERROR "doc: doxygen failed (exit code ${_result}).")
endif()

execute_process(COMMAND ${PYTHON} ${_script} --warnings warnings.log pages
  RESULT_VARIABLE _result)
if(NOT _result EQUAL 0)
  message(FATAL_ERROR "doc: doxygen reported the problems above.")
endif()

file(TOUCH doc.stamp)
