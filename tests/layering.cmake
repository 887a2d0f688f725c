# The include graph keeps to the floors of docs/architecture.md: a source file includes only
# headers of its own folder's floor or lower, and every folder holding sources has a floor.
#   cmake -DROOT=<project root> -P tests/layering.cmake
# Floors, bottom to top. Folders on one floor do not include each other (checked too).
set(FLOORS
  "mesh/base display/raster"
  "mesh/scene"
  "mesh/scene/readers"
  "mesh"
  "mesh/results radiosity/pathtrace"
  "radiosity/formfactors"
  "radiosity/shooting"
  "radiosity/light"
  "radiosity/gather"
  "radiosity"
  "radiosity/cli display/viewer")

set(floor 0)
foreach(line IN LISTS FLOORS)
  string(REPLACE " " ";" folders "${line}")
  foreach(folder IN LISTS folders)
    set(FLOOR_${folder} ${floor})
  endforeach()
  math(EXPR floor "${floor} + 1")
endforeach()

set(problems "")
file(GLOB_RECURSE sources RELATIVE ${ROOT} ${ROOT}/mesh/*.h ${ROOT}/mesh/*.cpp ${ROOT}/radiosity/*.h
     ${ROOT}/radiosity/*.cpp ${ROOT}/display/*.h ${ROOT}/display/*.cpp)
foreach(source IN LISTS sources)
  get_filename_component(folder ${source} DIRECTORY)
  if(NOT DEFINED FLOOR_${folder})
    list(APPEND problems "${source}: its folder ${folder} has no floor in tests/layering.cmake")
    continue()
  endif()
  file(STRINGS ${ROOT}/${source} includes REGEX "^#include \"")
  foreach(include IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]*)\".*" "\\1" header "${include}")
    get_filename_component(target ${header} DIRECTORY)
    if(NOT DEFINED FLOOR_${target})
      list(APPEND problems "${source}: includes ${header}, whose folder has no floor")
    elseif(FLOOR_${target} GREATER FLOOR_${folder})
      list(APPEND problems "${source}: includes ${header}, a floor up (${FLOOR_${target}} > ${FLOOR_${folder}})")
    elseif(FLOOR_${target} EQUAL FLOOR_${folder} AND NOT target STREQUAL folder)
      list(APPEND problems "${source}: includes ${header}, from another folder on its floor")
    endif()
  endforeach()
endforeach()

list(LENGTH sources count)
if(problems)
  list(JOIN problems "\n  " text)
  message(FATAL_ERROR "includes against the floors:\n  ${text}")
endif()
message(STATUS "${count} source files, every include on its own floor or lower")
