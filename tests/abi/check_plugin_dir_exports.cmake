# cmake -DNM=<nm> -DDIRS=<dir|dir...> -P check_plugin_dir_exports.cmake
#
# The exports check of tests/loader/check_exports.cmake applied to every *.so found in DIRS when the test
# runs, not when CMake configured: a plugin added later (or by another module) is checked without
# anyone remembering to list it. Finding none is a failure: an empty glob would prove nothing.
string(REPLACE "|" ";" DIRS "${DIRS}")
set(LIBS "")
foreach(dir IN LISTS DIRS)
  file(GLOB found ${dir}/*.so)
  if(NOT found)
    message(FATAL_ERROR "no plugins in ${dir}: build them first")
  endif()
  list(APPEND LIBS ${found})
endforeach()
string(JOIN "|" LIBS ${LIBS})
include(${CMAKE_CURRENT_LIST_DIR}/../loader/check_exports.cmake)
