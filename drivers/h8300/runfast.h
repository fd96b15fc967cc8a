/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Where runfast.S finds what it reads and writes: offsets in struct rcx and struct rcx_task, and the byte codes it
 * runs. Plain numbers, as the assembler reads this file too; vm/interp.c checks each against the C declarations when
 * it is compiled for the brick, so a changed struct stops the build instead of misleading the loop.
 */
#ifndef RCX_RUNFAST_H
#define RCX_RUNFAST_H

#define RF_PROG 0xC4       /* struct rcx: prog (u8) */
#define RF_RR 0xC5         /* rr (u8) */
#define RF_RUNMASK 0xC6    /* runmask (u16) */
#define RF_YIELD 0xC8      /* yield (u8) */
#if RCX_SWAN               /* an image with Swan's programs (the CMake option RCX_IMAGE_SWAN, CMakeLists.txt) */
#define RF_GLOBAL 0xD0     /* global[] */
#define RF_TASK 0x2D0      /* task[] */
#define RF_ARENA 0x6D4     /* arena[]; obj_start[] is at 0 */
#define RF_TASK_SIZE 0x20  /* sizeof(struct rcx_task) */
#else
#define RF_GLOBAL 0xCC     /* global[] */
#define RF_TASK 0x24C      /* task[] */
#define RF_ARENA 0x5D4     /* arena[]; obj_start[] is at 0 */
#define RF_TASK_SIZE 0x1E  /* sizeof(struct rcx_task) */
#endif
#define RF_SUB 1           /* struct rcx_task: sub (u8) */
#define RF_PC 2            /* pc (u16) */
#define RF_LOCAL_BASE 16   /* local_base (u8) */

#define RF_TASKS 10        /* RCX_TASKS */
#define RF_SUBS 8          /* RCX_SUBS: a slot's objects are its subroutines, then its tasks */
#define RF_SLOT_OBJS 18    /* RCX_SLOT_OBJS */
#define RF_NO_SUB 0xFF     /* RCX_NO_SUB */
#define RF_GLOBALS 32      /* RCX_GLOBALS */
#define RF_LOCALS 16       /* RCX_LOCALS */
#define RF_TOGGLE 0x08     /* RCX_TOGGLE */
#define RF_RUN_CHUNK 40    /* RCX_RUN_CHUNK */
#define RF_OP_SET_VAR 0x14
#define RF_OP_SUM_VAR 0x24
#define RF_OP_SUB_VAR 0x34
#define RF_OP_SJUMP 0x27
#define RF_SRC_VAR 0
#define RF_SRC_CONST 2
#define RF_SRC_GLOBAL 43   /* Swan's global variable */
#define RF_SW_SET_GB 0x2B  /* Swan's global op= forms the loop runs (RCX_SW_*) */
#define RF_SW_SET_GW 0x2C
#define RF_SW_SET_G 0x2D
#define RF_SW_SUM_GB 0x48
#define RF_SW_SUB_GB 0x49
#define RF_SW_SUM_G 0xC8
#define RF_SW_SUB_G 0xC9

#endif
