# Script mode: assembles one shader stage from its parts and validates it with glslangValidator.
#   -DOUT=<file.vert|file.frag> -DPARTS=<a.glsl|b.glsl> -DVARIANTS_FILE=<file> -DVALIDATOR=<exe>
# VARIANTS_FILE (written from glsl/variants.h) holds a variant per line: its defines separated
# by spaces, or NONE.
# The assembled text starts with "#version 330 core"; at run time the C++ side inserts its
# #define lines right after it. Every variant (a set of defines) is validated, so a broken
# shader fails the build rather than a user's render.
string(REPLACE "|" ";" part_list "${PARTS}")
set(text "#version 330 core\n")
foreach(part IN LISTS part_list)
  file(READ "${part}" body)
  string(APPEND text "${body}")
endforeach()
file(WRITE "${OUT}.tmp" "${text}")

file(STRINGS "${VARIANTS_FILE}" variant_list)
if(NOT variant_list)
  set(variant_list "NONE")
endif()
foreach(variant IN LISTS variant_list)
  set(define_args "")
  if(NOT variant STREQUAL "NONE")
    separate_arguments(defs UNIX_COMMAND "${variant}")
    foreach(d IN LISTS defs)
      list(APPEND define_args "-D${d}")
    endforeach()
  endif()
  get_filename_component(ext "${OUT}" LAST_EXT)
  string(SUBSTRING "${ext}" 1 -1 stage)
  if(define_args)
    list(PREPEND define_args -l)  # glslangValidator takes -D only when linking
  endif()
  execute_process(COMMAND "${VALIDATOR}" -S ${stage} ${define_args} "${OUT}.tmp"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    file(REMOVE "${OUT}.tmp")
    message(FATAL_ERROR "glslangValidator rejected ${OUT} (variant: ${variant}):\n${out}${err}")
  endif()
endforeach()
file(RENAME "${OUT}.tmp" "${OUT}")
