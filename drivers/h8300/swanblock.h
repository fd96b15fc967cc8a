/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Where swanblock.S finds what it reads and writes in struct rcx (an image with Swan's programs). Plain numbers, as
 * the assembler reads this file too; vm/swanblock.c and vm/swandec.c check each against the C declarations when they
 * are compiled for the brick, so a changed struct stops the build instead of misleading the code.
 */
#ifndef RCX_SWANBLOCK_H
#define RCX_SWANBLOCK_H

#define SB_DL_ACTIVE 0xBC  /* dl.active (u8); obj_start[] (u16) is at 0 */
#define SB_DL_OBJ 0xBD     /* dl.obj (u8) */
#define SB_DL_LAST 0xC0    /* dl.last (u16) */
#define SB_DL_FILLED 0xC2  /* dl.filled (u16) */
#define SB_SWAN 0xCA       /* swan[] (u8, a slot each) */
#define SB_DL_SCAN 0x6CE   /* dl_scan (u16) */
#define SB_DL_SWAN 0x6D0   /* dl_swan (u8) */
#define SB_ARENA 0x6D4     /* arena[] */
#define SB_SLOT_OBJS 18    /* RCX_SLOT_OBJS: a slot's objects, 8 subroutines and 10 tasks */
#define SB_SWAN_FAMILIES 5 /* the rows of Swan's families of eight, first in rcx_swan_rows[] (vm/swandec.c) */

#endif
