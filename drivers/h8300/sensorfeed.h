/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Where sensorfeed.S finds what it reads and writes: offsets in struct rcx_sensor and struct rcx. Plain numbers, as
 * the assembler reads this file too; vm/sensors.c checks each against the C declarations when it is compiled for
 * the brick, so a changed struct stops the build instead of misleading the code.
 */
#ifndef RCX_SENSORFEED_H
#define RCX_SENSORFEED_H

#define SF_SIZE 22         /* struct rcx_sensor: its size; 3 of them (RCX_SENSORS) */
#define SF_QUIET 0         /* struct rcx_sensor: quiet (u16) */
#define SF_VALUE 2         /* value (s16) */
#define SF_RAW 4           /* raw (u16) */
#define SF_PAST 6          /* past[0], past[1] (u16) */
#define SF_LO 10           /* lo (s16) */
#define SF_HI 12           /* hi (s16) */
#define SF_MODE 15         /* mode (u8) */
#define SF_BOOLEAN 16      /* boolean (u8) */
#define SF_PHASE 17        /* phase (u8) */
#define SF_WATCHED 18      /* watched (u8) */
#define SF_NUMBER 19       /* number (u8) */
#if RCX_SWAN               /* an image with Swan's programs (the CMake option RCX_IMAGE_SWAN, CMakeLists.txt) */
#define SF_SENSOR 0x496    /* struct rcx: sensor[] */
#else
#define SF_SENSOR 0x39A
#endif
#define SF_LATE (SF_SENSOR + 21) /* sensor[0].late (u8) */
#define SF_WINDOW_NONE 0x7FFF /* EVENTS_WINDOW_NONE (vm/events.h) */
#define SF_REST (SF_SENSOR + 555) /* struct rcx: sensors_rest (u8; sensor_scan in sensorfeed.S, eventwindow.S) */
#define SF_EVENT (SF_SENSOR + 66) /* struct rcx: event[], right after sensor[] (eventwindow.S) */
#define EV_SIZE 22         /* struct rcx_event: its size; 16 of them (RCX_EVENTS) */
#define EV_SOURCE 0        /* source (u8) */
#define EV_TYPE 1          /* type (u8); types 0-7 (below RCX_EVENT_LOW, 8) look at every sample */
#define EV_STATE 2         /* state (u8): 0 low, 1 normal, 2 high, above: every sample */
#define EV_UPPER 4         /* upper (s16) */
#define EV_LOWER 6         /* lower (s16) */

#endif
