# SPDX-License-Identifier: MPL-2.0
# Reading an image's linker symbols with nm, for the scripts that check or size the link (cmake -P).
#
# nm_read_symbols(<nm> <image> <who>) loads the symbol table; symbol_value(<name> <out>) then sets <out> to the
# symbol's 16-bit value, or stops with an error naming <who> and the image when it is missing.
function(nm_read_symbols nm image who)
    execute_process(COMMAND "${nm}" "${image}" OUTPUT_VARIABLE out RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "${who}: ${nm} failed on ${image}")
    endif()
    set(nm_symbols "${out}" PARENT_SCOPE)
    set(nm_who "${who}" PARENT_SCOPE)
    set(nm_image "${image}" PARENT_SCOPE)
endfunction()

function(symbol_value name out)
    if(NOT nm_symbols MATCHES "([0-9a-fA-F]+) [A-Za-z] ${name}\n")
        message(FATAL_ERROR "${nm_who}: symbol ${name} missing from ${nm_image}")
    endif()
    math(EXPR value "0x${CMAKE_MATCH_1} & 0xFFFF")
    set(${out} ${value} PARENT_SCOPE)
endfunction()
