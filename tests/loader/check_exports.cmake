# cmake -DNM=<nm> -DLIBS=<a.so|b.so> -P check_exports.cmake
# Fails unless each library's dynamic symbol table defines exactly `nimbus_plugin_entry` (sdk-idioms.md §1.8,
# §4.2): anything else exported could interpose on, or be interposed by, another library.
string(REPLACE "|" ";" LIBS "${LIBS}")
if(NOT LIBS)
  message(FATAL_ERROR "no libraries to check")
endif()
foreach(lib IN LISTS LIBS)
  execute_process(COMMAND ${NM} -D --defined-only ${lib}
    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} failed on ${lib}: ${err}")
  endif()
  string(REGEX REPLACE "\n$" "" out "${out}")
  string(REPLACE "\n" ";" lines "${out}")
  set(symbols "")
  foreach(line IN LISTS lines)
    # "<address> <type> <name>"; versioned names carry @VERSION, which is as foreign as any other symbol.
    if(line MATCHES "^[0-9a-fA-F]* +[A-Za-z] +(.+)$")
      list(APPEND symbols "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  if(NOT symbols STREQUAL "nimbus_plugin_entry")
    message(FATAL_ERROR "${lib} exports [${symbols}], expected only nimbus_plugin_entry")
  endif()
  message(STATUS "${lib}: exports only nimbus_plugin_entry")
endforeach()
