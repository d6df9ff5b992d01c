# Writes the shared libraries that MODULE brings in, one path per line, in the order the
# dynamic linker loads them (ldd's), to OUT. scene/image_io.cpp links them one dlopen call at
# a time before the module itself; the reason is there. Without ldd, OUT is empty and the
# module is loaded in one call.
# Usage: cmake -DMODULE=path -DOUT=path -P ModuleLibraries.cmake
execute_process(COMMAND ldd "${MODULE}" OUTPUT_VARIABLE listing RESULT_VARIABLE failed
                ERROR_QUIET)
set(paths "")
if(NOT failed)
  string(REPLACE "\n" ";" lines "${listing}")
  foreach(line IN LISTS lines)
    if(line MATCHES "=> (/[^ ]+) \\(")
      string(APPEND paths "${CMAKE_MATCH_1}\n")
    endif()
  endforeach()
endif()
file(WRITE "${OUT}.tmp" "${paths}")
file(RENAME "${OUT}.tmp" "${OUT}")
