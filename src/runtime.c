/* SPDX-License-Identifier: MPL-2.0 */
/* The runtime's main-loop entry points: the one place where machine, IR link and user interface meet. On the brick
 * they run from .high (linker/openrcx.ld), as IR and user interface do. */
#include "rcx_string.h"
#include "runtime.h"
#include "hal.h"

RCX_STATIC_ASSERT(vm_is_first, offsetof(struct rcx_brick, vm) == 0);

/* The port attaches its data (rcx.port) before power-on, and may be called from the init functions below. */
void rt_init(struct rcx_brick *k, u16 arena_addr)
{
    vm_init(&k->vm, arena_addr);
    /* The IR link and the user interface start from zeros (one memset for both, which follow the machine), then
     * set what is not 0. */
    memset(&k->ir, 0, sizeof *k - offsetof(struct rcx_brick, ir));
    ir_init(k);
    ui_init(k);
}

u16 rt_run(struct rcx_brick *k, u16 budget)
{
    /* A move of program memory not completed (vm/progmem.c): a step of it, and nothing that reads or writes program
     * memory, commands and tasks, until it is done. Counted as a byte code: the brick does not sleep meanwhile. */
    if (mem_step(&k->vm))
        return 1;
    if (ir_poll_due(k))
        ir_poll(k);
    /* GoIntoBootMode: the acknowledgement and its echo must be through before the ROM takes the link over, and a
     * downloader sends the next command the moment it has the reply. */
    if (k->vm.boot_mode && !ir_busy(k)) {
        k->vm.boot_mode = 0;
        hal_enter_rom(&k->vm);
        return 0;
    }
    if (k->ui.off || k->vm.turn_off)
        ui_poll(k);            /* a switch-off to carry out */
    return k->vm.runmask ? vm_run(&k->vm, budget) : 0; /* no call when no task runs */
}

/* rt_ir_byte() is in src/ir.c; rt_battery() and rt_button() are inline in src/runtime.h. */
