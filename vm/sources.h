/* Source numbers and their table (sources.def). */
#ifndef RCX_SOURCES_H
#define RCX_SOURCES_H

#include "rcx_types.h"

#define RCX_ANY 0x3F /* highest index: any, the index is the value */
#define RCX_SOURCE_COUNT 37

enum rcx_source {
#define RCX_SRC(num, id, name, max, access, place) RCX_SRC_##id = num,
#include "sources.def"
#undef RCX_SRC
    RCX_SRC_NONE = 0xFF
};

#endif
