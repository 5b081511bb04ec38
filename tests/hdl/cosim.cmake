# The co-verification steps of one ctest (cmake -P). Any failing step fails
# the test with its output.
#
# MODE=vectors   TOOL=dda_vectors VECTORS=x.inc OUT=prefix GHDL WORKDIR
#   1. rt::Dda's pulse trains:  dda_vectors expect x.inc prefix.expected
#   2. the VHDL's, from the pins: tb_microstep_interpolator with the #! line's
#      generics, the increments replayed from x.inc -> prefix.vhdl
#   3. dda_vectors compare prefix.expected prefix.vhdl: identical, tick for tick
# MODE=job       TOOL=job_increments MACHINE PROGRAM OUT=prefix GHDL WORKDIR
#   1. the program through the core planner -> prefix.inc, prefix.totals
#   2. prefix.inc through the testbench -> prefix.vhdl_totals (Σ pulses per axis)
#   3. the totals identical: Σ pulses = commanded steps on every axis
# MODE=generate  TOOL=dda_vectors KIND VECTORS OUT: the generator writes the
#   committed VECTORS again, byte for byte.

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "FAILED (exit ${rc}): ${cmd}\n${out}${err}")
  endif()
  if("${out}${err}" MATCHES "warning")
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "warnings from: ${cmd}\n${out}${err}")
  endif()
  message("${out}${err}")
endfunction()

# The testbench's generics from a vector file's "#!" line, as -gKEY=VALUE.
function(generics_of file out_var)
  file(STRINGS "${file}" header REGEX "^#!")
  if(NOT header)
    message(FATAL_ERROR "${file}: no #! line of generics")
  endif()
  list(GET header 0 header)
  string(REGEX REPLACE "^#![ ]*" "" header "${header}")
  separate_arguments(pairs UNIX_COMMAND "${header}")
  set(g "")
  foreach(kv ${pairs})
    list(APPEND g "-g${kv}")
  endforeach()
  set(${out_var} ${g} PARENT_SCOPE)
endfunction()

set(tb_run "${GHDL}" -r --std=08 --workdir=${WORKDIR} tb_microstep_interpolator)

if(MODE STREQUAL "vectors")
  run("${TOOL}" expect "${VECTORS}" "${OUT}.expected")
  generics_of("${VECTORS}" g)
  run(${tb_run} ${g} -gvector_in=${VECTORS} -gpulses_out=${OUT}.vhdl
      -gtotals_out=${OUT}.vhdl_totals -gexpect_clean=true -gcheck_uniform=true
      --assert-level=error)
  run("${TOOL}" compare "${OUT}.expected" "${OUT}.vhdl")
elseif(MODE STREQUAL "job")
  set(timing reset_divider=2 min_divider=2 pulse_width=1 dir_setup=0 dir_hold=0
             response_ns=2000 port_ns=1000)
  run("${TOOL}" "${MACHINE}" "${PROGRAM}" "${OUT}.inc" "${OUT}.totals" ${timing})
  generics_of("${OUT}.inc" g)
  string(TIMESTAMP t0 "%s%f")
  run(${tb_run} ${g} -gvector_in=${OUT}.inc -gtotals_out=${OUT}.vhdl_totals
      -greference_model=false -gexpect_clean=true --assert-level=error)
  string(TIMESTAMP t1 "%s%f")
  # simulation speed: periods (data lines) and ticks (N per period) per second
  file(STRINGS "${OUT}.inc" data REGEX "^[0-9]")
  list(LENGTH data periods)
  string(REGEX MATCH "-gcapacity=([0-9]+)" _ "${g}")
  set(capacity ${CMAKE_MATCH_1})
  math(EXPR dt_ms "(${t1} - ${t0}) / 1000")
  math(EXPR per_s "${periods} * 1000 / ${dt_ms}")
  math(EXPR ticks_s "${periods} * ${capacity} * 1000 / ${dt_ms}")
  message("GHDL replay: ${periods} periods of ${capacity} ticks in ${dt_ms} ms: "
          "${per_s} periods/s, ${ticks_s} ticks/s")
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUT}.totals" "${OUT}.vhdl_totals"
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    file(READ "${OUT}.totals" e)
    file(READ "${OUT}.vhdl_totals" a)
    message(FATAL_ERROR "MISMATCH: Σ pulses per axis (axis total)\ncommanded:\n${e}GHDL:\n${a}")
  endif()
  file(READ "${OUT}.totals" e)
  message("Σ pulses = commanded steps on every axis (axis steps):\n${e}")
elseif(MODE STREQUAL "generate")
  run("${TOOL}" generate ${KIND} "${OUT}")
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${VECTORS}" "${OUT}" RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${VECTORS} differs from what `dda_vectors generate ${KIND}` writes (${OUT}); "
                        "regenerate it and commit")
  endif()
else()
  message(FATAL_ERROR "cosim.cmake: MODE=${MODE}?")
endif()
