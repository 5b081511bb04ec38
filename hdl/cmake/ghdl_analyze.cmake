# Analyses the VHDL sources and testbenches into a fresh GHDL library, in
# the order given, and fails on any error or warning (cmake -P; the ctest
# fixture hdl.analyze).
#   -DGHDL=ghdl -DWORKDIR=dir -DSOURCES=a.vhd;b.vhd;...
file(REMOVE_RECURSE "${WORKDIR}")
file(MAKE_DIRECTORY "${WORKDIR}")
execute_process(
  COMMAND "${GHDL}" -a --std=08 --workdir=${WORKDIR} -Wunused -Werror ${SOURCES}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT "${out}${err}" STREQUAL "")
  message(FATAL_ERROR "ghdl analysis failed (exit ${rc}):\n${out}${err}")
endif()
list(LENGTH SOURCES n)
message(STATUS "ghdl: ${n} files analysed into ${WORKDIR}, clean")
