# The limits of the linked image that linker/openrcx.ld cannot check itself: with --relax, ld evaluates the
# script's ASSERTs on the sizes before relaxation as well, so an image that fits only once relaxed would be
# refused. The limits are the script's own symbols (_rcx_image_max, _rcx_rom_vars), read back from the image.
# RAM needs no check here: the .bss section's memory region ends at 0xF000, which ld checks after relaxing.
#
# Usage: cmake -DNM=<nm> -DIMAGE=<linked image> -P check_link.cmake
execute_process(COMMAND "${NM}" "${IMAGE}" OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "check_link: ${NM} failed on ${IMAGE}")
endif()

function(symbol_value name out)
    if(NOT symbols MATCHES "([0-9a-fA-F]+) [A-Za-z] ${name}\n")
        message(FATAL_ERROR "check_link: symbol ${name} missing from ${IMAGE}")
    endif()
    math(EXPR value "0x${CMAKE_MATCH_1} & 0xFFFF")
    set(${out} ${value} PARENT_SCOPE)
endfunction()

symbol_value(_rcx_image_base base)
symbol_value(_rcx_image_end end)
symbol_value(_rcx_image_max max)
symbol_value(_rcx_rom_vars rom_vars)
math(EXPR image "${end} - ${base}")
if(image GREATER max)
    message(FATAL_ERROR "OpenRCX: image larger than ${max} bytes (${image})")
endif()
if(end GREATER rom_vars)
    message(FATAL_ERROR "OpenRCX: image reaches the ROM variables at 0xEE5E")
endif()
