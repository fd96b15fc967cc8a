/* The runtime's main-loop entry points: the one place where machine, IR link and user interface meet. */
#include "runtime.h"

RCX_STATIC_ASSERT(vm_is_first, offsetof(struct rcx_brick, vm) == 0);

void rt_init(struct rcx_brick *k, u16 arena_addr)
{
    vm_init(&k->vm, arena_addr);
    ir_init(k);
    ui_init(k);
}

void rt_tick(struct rcx_brick *k)
{
    vm_tick(&k->vm);
    ir_tick(k);
    ui_tick(k);
}

u16 rt_run(struct rcx_brick *k, u16 budget)
{
    ir_poll(k);
    ui_poll(k);
    return vm_run(&k->vm, budget);
}

void rt_ir_byte(struct rcx_brick *k, u8 byte, u8 error)
{
    ir_byte(k, byte, error);
}

void rt_sensor_sample(struct rcx_brick *k, u8 input, u16 raw10)
{
    sensor_sample(&k->vm, input, raw10);
}

void rt_battery(struct rcx_brick *k, u16 millivolts)
{
    k->vm.battery_mv = millivolts;
}

void rt_button(struct rcx_brick *k, u8 button, u8 down)
{
    ui_button(k, button, down);
}
