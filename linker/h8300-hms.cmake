# SPDX-License-Identifier: MPL-2.0
# CMake toolchain for the OpenRCX firmware: Debian's gcc-h8300-hms (gcc 3.4.6, COFF) for the RCX's plain
# H8/300. Used by `make firmware`:  cmake -S . -B build/h8300 -DCMAKE_TOOLCHAIN_FILE=linker/h8300-hms.cmake
# See /work/shared/reference/toolchain.md for the compiler's quirks.

set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR h8300)

# Tells the top-level CMakeLists.txt to build the image (drivers/CMakeLists.txt) instead of the host parts.
set(RCX_TARGET_H8300 ON CACHE BOOL "Build the H8/300 firmware image" FORCE)

find_program(RCX_H8_GCC NAMES h8300-hms-gcc h8300-hitachi-coff-gcc REQUIRED)
get_filename_component(RCX_H8_BIN "${RCX_H8_GCC}" DIRECTORY)
get_filename_component(RCX_H8_GCC_NAME "${RCX_H8_GCC}" NAME)
string(REGEX REPLACE "gcc$" "" RCX_H8_PREFIX "${RCX_H8_GCC_NAME}")

set(CMAKE_C_COMPILER "${RCX_H8_GCC}")
set(CMAKE_ASM_COMPILER "${RCX_H8_GCC}")
set(CMAKE_AR "${RCX_H8_BIN}/${RCX_H8_PREFIX}ar" CACHE FILEPATH "" FORCE)
set(CMAKE_RANLIB "${RCX_H8_BIN}/${RCX_H8_PREFIX}ranlib" CACHE FILEPATH "" FORCE)
set(CMAKE_LINKER "${RCX_H8_BIN}/${RCX_H8_PREFIX}ld" CACHE FILEPATH "" FORCE)
set(CMAKE_NM "${RCX_H8_BIN}/${RCX_H8_PREFIX}nm" CACHE FILEPATH "" FORCE)
set(CMAKE_OBJCOPY "${RCX_H8_BIN}/${RCX_H8_PREFIX}objcopy" CACHE FILEPATH "" FORCE)
set(CMAKE_OBJDUMP "${RCX_H8_BIN}/${RCX_H8_PREFIX}objdump" CACHE FILEPATH "" FORCE)
set(RCX_H8_SIZE "${RCX_H8_BIN}/${RCX_H8_PREFIX}size" CACHE FILEPATH "" FORCE)

# No C library and a libgcc that does not link: the compiler checks may compile but not link.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# -Os measured smaller than -O2 for this code; no -mh/-ms (the RCX has the plain H8/300). RCX_SWAN (Swan's programs,
# issue 16) is defined in CMakeLists.txt from the cached option RCX_IMAGE_SWAN, not here: flags given here reach only
# a new build folder's cache, and an older folder would build the image with rcx_limits.h's default (1) unnoticed.
set(CMAKE_C_FLAGS_INIT "-Os -fomit-frame-pointer -std=gnu99 -ffreestanding -Wall -Werror")
# Build types must not replace -Os (the image has to fit): they only add or drop debug information.
foreach(config DEBUG RELEASE RELWITHDEBINFO MINSIZEREL)
    set(CMAKE_C_FLAGS_${config}_INIT "")
    set(CMAKE_ASM_FLAGS_${config}_INIT "")
endforeach()
set(CMAKE_C_FLAGS_DEBUG_INIT "-g")
set(CMAKE_C_FLAGS_RELWITHDEBINFO_INIT "-g")

# Link with ld itself: the script places everything; -nostdlib keeps the unusable libgcc.a out.
set(RCX_LINKER_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/openrcx.ld")
set(CMAKE_C_LINK_EXECUTABLE
    "${CMAKE_LINKER} -T ${RCX_LINKER_SCRIPT} -nostdlib <LINK_FLAGS> <OBJECTS> -o <TARGET> <LINK_LIBRARIES>")
set(CMAKE_ASM_LINK_EXECUTABLE "${CMAKE_C_LINK_EXECUTABLE}")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
