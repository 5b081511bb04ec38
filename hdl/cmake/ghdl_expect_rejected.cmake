# Runs a testbench that must be stopped — illegal generics at elaboration, or
# a design-rule assertion during simulation — and passes only when it stops
# with the expected message at the expected stage (cmake -P).
#   -DGHDL=ghdl -DWORKDIR=dir -DTB=tb_x "-DARGS=-gfoo=1 -gbar=2" "-DEXPECT=regex"
#   [-DSTAGE=elaboration|simulation]  (default elaboration)
if(NOT STAGE)
  set(STAGE elaboration)
endif()
separate_arguments(args UNIX_COMMAND "${ARGS}")
execute_process(
  COMMAND "${GHDL}" -r --std=08 --workdir=${WORKDIR} ${TB} ${args}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(log "${out}${err}")
if(rc EQUAL 0)
  message(FATAL_ERROR "${TB} ${ARGS}: ran to the end, but must be stopped\n${log}")
endif()
if(NOT log MATCHES "${EXPECT}")
  message(FATAL_ERROR "${TB} ${ARGS}: stopped, but not with '${EXPECT}':\n${log}")
endif()
if(STAGE STREQUAL "elaboration" AND NOT log MATCHES "error during elaboration")
  message(FATAL_ERROR "${TB} ${ARGS}: stopped, but not at elaboration:\n${log}")
endif()
if(STAGE STREQUAL "simulation" AND NOT log MATCHES "simulation failed")
  message(FATAL_ERROR "${TB} ${ARGS}: stopped, but not during simulation:\n${log}")
endif()
message(STATUS "stopped as expected at ${STAGE}: ${EXPECT}")
