# SPDX-License-Identifier: MPL-2.0
# Refuses a helper library in which a helper calls one of gcc's helpers (__mulhi3 ... __umodsi3, the mem*
# functions): compiled from C, a helper that does so would call itself or another one endlessly.
# Usage: cmake -DOBJDUMP=<objdump> -DLIB=<librcxhelpers.a> -DSTAMP=<file to touch on success> -P check_arith.cmake
execute_process(COMMAND "${OBJDUMP}" -d -r "${LIB}" OUTPUT_VARIABLE listing RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "check_arith: ${OBJDUMP} failed on ${LIB}")
endif()
# Relocation lines of `objdump -r` read "<tab><tab><tab>offset: type<tab>symbol".
string(REGEX MATCHALL "\t\t\t[0-9a-f]+: [^\t\n]+\t(___(u?div|u?mod|mul)[hs]i3|_mem(cpy|move|set|cmp))\n" calls "${listing}")
if(calls)
    message(FATAL_ERROR "check_arith: the helpers in ${LIB} call gcc helpers themselves "
                        "(recursion; rewrite them with byte operations):\n${calls}")
endif()
file(TOUCH "${STAMP}")
