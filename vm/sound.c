/* Placeholder: the sound engine is owed (engine_pending counts its uses). */
#include "rcx.h"

void sound_tone(struct rcx *b, u16 hz, u8 dur10) { (void)hz; (void)dur10; b->engine_pending++; }
void sound_system(struct rcx *b, u8 sound) { (void)sound; b->engine_pending++; }
void sound_ui(struct rcx *b, u8 sound) { (void)sound; b->engine_pending++; }
void sound_clear(struct rcx *b) { b->engine_pending++; }
void sound_mute(struct rcx *b, u8 on)
{
    b->sound.muted = on;
    if (on)
        sound_clear(b);
}
void sound_tick(struct rcx *b) { (void)b; }
