# cmake -DCC=<c compiler> -DCXX=<c++ compiler> -DINCLUDE=<sdk/include> -DWORK=<scratch dir> -P check_headers_compile.cmake
#
# Every public header must compile on its own, twice included (guards), as strict C99 and as C++17
# (sdk-idioms.md §1.1): a plugin author may use either, and a header that only compiles after another
# one, or only as C++, breaks them. nimbus.hpp is the C++ wrapper and is checked as C++17 only; the
# C++ kit (nimbus/cpp/*.hpp) as C++20, each header on its own.
file(GLOB headers ${INCLUDE}/nimbus/*.h)
list(LENGTH headers count)
if(count LESS 10)
  message(FATAL_ERROR "found ${count} headers in ${INCLUDE}/nimbus; expected the whole SDK")
endif()
file(MAKE_DIRECTORY ${WORK})
set(strict -pedantic -Wall -Wextra -Werror -fsyntax-only -I${INCLUDE})
set(failed "")

function(try_compile_header name compiler lang std source)
  execute_process(COMMAND ${compiler} -x ${lang} -std=${std} ${strict} ${ARGN} ${source}
    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message("FAILED: ${name} as ${std}:\n${out}${err}")
    set(failed "${failed} ${name}(${std})" PARENT_SCOPE)
  endif()
endfunction()

foreach(h IN LISTS headers)
  get_filename_component(name ${h} NAME)
  set(src ${WORK}/${name}.check)
  # A declaration after the includes: an empty translation unit is itself a -pedantic error in C.
  file(WRITE ${src} "#include <nimbus/${name}>\n#include <nimbus/${name}>\ntypedef int nimbus_header_check;\n")
  try_compile_header(${name} ${CC} c c99 ${src} -Wstrict-prototypes)
  try_compile_header(${name} ${CXX} c++ c++17 ${src})
endforeach()
set(src ${WORK}/nimbus.hpp.check)
file(WRITE ${src} "#include <nimbus/nimbus.hpp>\n#include <nimbus/nimbus.hpp>\n")
try_compile_header(nimbus.hpp ${CXX} c++ c++17 ${src})
file(GLOB kit ${INCLUDE}/nimbus/cpp/*.hpp)
list(LENGTH kit kit_count)
foreach(h IN LISTS kit)
  get_filename_component(name ${h} NAME)
  set(src ${WORK}/cpp_${name}.check)
  file(WRITE ${src} "#include <nimbus/cpp/${name}>\n#include <nimbus/cpp/${name}>\n")
  try_compile_header(cpp/${name} ${CXX} c++ c++20 ${src})
endforeach()

if(failed)
  message(FATAL_ERROR "headers that do not compile:${failed}")
endif()
message(STATUS "${count} headers compile as C99 and C++17; nimbus.hpp as C++17; ${kit_count} kit headers as C++20")
