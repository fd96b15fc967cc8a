/* Source numbers and their table (sources.def). */
#ifndef RCX_SOURCES_H
#define RCX_SOURCES_H

#include "rcx_types.h"

#define RCX_ANY 0xFFFF
#define RCX_SOURCE_COUNT 37

enum rcx_source {
#define RCX_SRC(num, id, name, max, access) RCX_SRC_##id = num,
#include "sources.def"
#undef RCX_SRC
    RCX_SRC_NONE = 0xFF
};

struct rcx_source_info {
    u16 max;      /* highest index, RCX_ANY, or 0 with writable = 0 and exists = 0 for a hole */
    u8 exists;
    u8 writable;
};

extern const struct rcx_source_info rcx_sources[RCX_SOURCE_COUNT];

#endif
