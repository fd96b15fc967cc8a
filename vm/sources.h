/* SPDX-License-Identifier: MPL-2.0 */
/* Source numbers and their table (sources.def). */
#ifndef RCX_SOURCES_H
#define RCX_SOURCES_H

#include "rcx_types.h"
#include "rcx_limits.h"

#define RCX_ANY 0x3F /* highest index: any, the index is the value */
#define RCX_SOURCE_COUNT (RCX_SWAN ? 45 : 37) /* 37-44: the datalog read-back and Swan's globals */

enum rcx_source {
#define RCX_SRC(num, id, name, max, access, place) RCX_SRC_##id = num,
#include "sources.def"
#undef RCX_SRC
    RCX_SRC_NONE = 0xFF
};
#if !RCX_SWAN /* not in the table (RCX_SOURCE_COUNT), but code that RCX_SWAN leaves out names them */
enum { RCX_SRC_LOG_TYPE_IND = 37, RCX_SRC_LOG_TYPE, RCX_SRC_LOG_VALUE_IND, RCX_SRC_LOG_VALUE, RCX_SRC_LOG_BYTE_IND,
       RCX_SRC_LOG_BYTE, RCX_SRC_GLOBAL, RCX_SRC_GLOBAL_IND,
       RCX_SRC_POWER_SIGNED = 5, RCX_SRC_BRAKE_POWER = 7, RCX_SRC_POWER128 = 16, RCX_SRC_POWER8 = 32 };
#endif

#endif
