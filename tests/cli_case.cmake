# One command-line case under CTest, run by run_cli.cmake: add_cli_case(test exe dir code regex
# output args...). "OUT/" in the output and the arguments stands for the case's own folder `dir`,
# so that run_cli.cmake's check for left-over temporary files never sees the files of cases
# running in parallel. `regex` (stderr) and `output` may be "".
function(add_cli_case test exe dir code regex output)
  file(MAKE_DIRECTORY ${dir})
  string(REPLACE "OUT/" "${dir}/" output "${output}")
  list(TRANSFORM ARGN REPLACE "^OUT/" "${dir}/")
  list(JOIN ARGN "|" joined)  # run_cli.cmake splits the command at "|"
  set(args "-DCOMMAND=${exe}|${joined}" -DEXPECT_CODE=${code} -DOUTPUT_DIR=${dir})
  if(NOT regex STREQUAL "")
    list(APPEND args "-DEXPECT_STDERR=${regex}")
  endif()
  if(NOT output STREQUAL "")
    list(APPEND args -DOUTPUT=${output})
  endif()
  add_test(NAME ${test} COMMAND ${CMAKE_COMMAND} ${args} -P ${CMAKE_CURRENT_SOURCE_DIR}/run_cli.cmake)
endfunction()
