# SPDX-License-Identifier: MPL-2.0
# The limits of the linked image that linker/openrcx.ld cannot check itself: with --relax, ld evaluates the
# script's ASSERTs on the sizes before relaxation as well, so an image that fits only once relaxed would be
# refused. The limits are the script's own symbols (_rcx_image_max, _rcx_rom_vars), read back from the image; the
# image's size is that of the download, the S-records the packer wrote (drivers/pack: the head and the packed rest).
# RAM needs no check here: the .bss section's memory region ends at 0xF000, which ld checks after relaxing, as it
# checks that section .high (the code run at 0xF000) fits in 0xF000-0xFB7F. Checked here: .high is unpacked last,
# .bss starts where it was unpacked (crt0.s copies it away before clearing .bss), and the download's size.
#
# Usage: cmake -DNM=<nm> -DIMAGE=<linked image> -DSREC=<its S-records> -P check_link.cmake
include(${CMAKE_CURRENT_LIST_DIR}/nm_symbols.cmake)
nm_read_symbols("${NM}" "${IMAGE}" check_link)

symbol_value(_rcx_image_base base)
symbol_value(_rcx_image_end end)
symbol_value(_rcx_image_max max)
symbol_value(_rcx_rom_vars rom_vars)
symbol_value(_rcx_high_start high_start)
symbol_value(_rcx_high_end high_end)
symbol_value(_rcx_high_load high_load)
symbol_value(_rcx_bss_start bss_start)
math(EXPR high_size "${high_end} - ${high_start}")
math(EXPR high_load_end "${high_load} + ${high_size}")
if(NOT high_start EQUAL 0xF000 OR high_end GREATER 0xFB80 OR NOT high_load_end EQUAL end OR NOT bss_start EQUAL high_load
   OR high_start MATCHES "[13579]$" OR high_load MATCHES "[13579]$" OR high_end MATCHES "[13579]$")
    message(FATAL_ERROR "OpenRCX: section .high not laid out as crt0.s copies it (run ${high_start}-${high_end}, "
                        "load ${high_load}, image end ${end}, .bss ${bss_start})")
endif()
# The bytes downloaded: every S1 record's data (its count less 2 address bytes and the checksum).
file(STRINGS "${SREC}" records REGEX "^S1")
set(image 0)
foreach(record IN LISTS records)
    string(SUBSTRING "${record}" 2 2 count)
    math(EXPR image "${image} + 0x${count} - 3")
endforeach()
math(EXPR download_end "${base} + ${image}")
if(image GREATER max)
    message(FATAL_ERROR "OpenRCX: download larger than ${max} bytes (${image})")
endif()
if(download_end GREATER rom_vars)
    message(FATAL_ERROR "OpenRCX: download reaches the ROM variables at 0xEE5E")
endif()
