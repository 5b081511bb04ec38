# Who may include whom (docs/design.md §3.1), checked over every source:
#   cmake -DSOURCE_DIR=<repo> -P tests/layout/include_rules.cmake
# Fails with file:line and the rule for each include that breaks one.
cmake_minimum_required(VERSION 3.20)

set(violations "")

# check(<folder> <glob exclusion regex or ""> <forbidden include regex> <rule>)
function(check folder exclude forbidden rule)
  file(GLOB_RECURSE files "${SOURCE_DIR}/${folder}/*.h" "${SOURCE_DIR}/${folder}/*.cpp")
  foreach(f IN LISTS files)
    file(RELATIVE_PATH rel "${SOURCE_DIR}" "${f}")
    if(NOT exclude STREQUAL "" AND rel MATCHES "${exclude}")
      continue()
    endif()
    file(STRINGS "${f}" lines)
    set(n 0)
    foreach(line IN LISTS lines)
      math(EXPR n "${n} + 1")
      if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*[\"<]([^\">]+)[\">]")
        set(inc "${CMAKE_MATCH_1}")
        if(inc MATCHES "${forbidden}")
          list(APPEND violations "${rel}:${n}: #include ${inc}: ${rule}")
        endif()
      endif()
    endforeach()
  endforeach()
  set(violations "${violations}" PARENT_SCOPE)
endfunction()

set(qt "^Q[A-Za-z]*(/|$)|^Qt[A-Za-z]*/")
check(core "" "^(rt|drivers|hmi|app)/|${qt}|^(thread|mutex|modbus\\.h)$"
      "core/ is pure: no rt, drivers, hmi, app, Qt, threads or devices")
check(core/path "" "^(gcode|plan|holes|cut|decompose|dxf|kinematics|measure)/"
      "core/path/ (segments, their geometry) sits below the readers and the planner")
check(core/gcode "" "^(plan|holes|cut|decompose|kinematics|measure)/"
      "core/gcode/ (the G-code reader) sits below the planner and the applications of core")
check(rt "" "^(drivers|hmi|app)/|${qt}" "rt/ may use core alone")
check(drivers "^drivers/hal/" "^(rt|hmi|app)/|${qt}" "drivers/ may use core and libmodbus alone")
check(drivers/hal "" "^(hmi|app)/|${qt}" "the HAL component may use core and rt")
check(hmi "" "^app/|^rt/(.*[^/]*)$" "hmi/ may use core, drivers and rt/shm_interface.h alone")

# the one header of rt/ the HMI may use
list(FILTER violations EXCLUDE REGEX "^hmi/[^:]+:[0-9]+: #include rt/shm_interface\\.h:")

if(violations)
  list(JOIN violations "\n" text)
  list(LENGTH violations count)
  message(NOTICE "${text}")
  message(FATAL_ERROR "${count} includes break the include rules")
endif()

message(STATUS "include rules kept")
