# The harnesses linked into the replay tool must be the ones
# fuzz/CMakeLists.txt lists (and so tests and fuzzes): a harness added to a
# *_fuzz.cpp file but not to the list would otherwise never run.
execute_process(COMMAND ${REPLAY} --list OUTPUT_VARIABLE linked RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${REPLAY} --list failed (${rc})")
endif()
string(STRIP "${linked}" linked)
string(REPLACE "\n" ";" linked "${linked}")
list(SORT linked)
set(expected ${EXPECTED})
list(SORT expected)
if(NOT linked STREQUAL expected)
  message(FATAL_ERROR "linked harnesses '${linked}' differ from the list '${expected}'")
endif()
