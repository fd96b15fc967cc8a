/* SPDX-License-Identifier: MPL-2.0 */
/*
 * rcxpack: writes the S-records downloaded to the brick from the linked firmware image, its bytes after the head
 * packed (format: pack.h). A host tool, built and run by drivers/CMakeLists.txt.
 *
 *   rcxpack <nm> <image (COFF)> <image.bin> <unpacker.bin> <out.srec>
 *
 * <image.bin> holds the image's bytes from 0x8000 to its end as they run, <unpacker.bin> its section .unpack
 * (objcopy -O binary); the layout comes from the image's symbols (linker/openrcx.ld): _rcx_image_base,
 * _rcx_head_end, _rcx_packed_start, _rcx_image_end, _rcx_download_end, _rcx_ram_end. The output is the image's
 * head (up to _rcx_head_end: entry, knock string), the unpacker, and the packed rest of the image, as S1 records of
 * 16 bytes from 0x8000, with an S0 record naming the file and an S9 record with the entry 0x8000, as objcopy
 * writes them. It fails (status 1, no output) unless the unpacker would unpack it to the image in place
 * (pack_check_in_place), which also means that it fits the download budget.
 */
#define _POSIX_C_SOURCE 200809L /* popen */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pack.h"

static int symbol(FILE *nm_out, const char *name, unsigned long *value)
{
    char line[256], type[8], sym[128];
    unsigned long v;
    rewind(nm_out);
    while (fgets(line, sizeof line, nm_out))
        if (sscanf(line, "%lx %7s %127s", &v, type, sym) == 3 && !strcmp(sym, name)) {
            *value = v & 0xFFFF;
            return 0;
        }
    fprintf(stderr, "rcxpack: symbol %s missing\n", name);
    return -1;
}

/* The image's symbols, through a temporary copy of the nm listing (it is read once per symbol). */
static int read_layout(const char *nm, const char *image, struct pack_layout *l)
{
    char cmd[1024], buf[4096];
    FILE *p, *t = tmpfile();
    size_t n;
    int bad;

    snprintf(cmd, sizeof cmd, "'%s' '%s'", nm, image);
    p = popen(cmd, "r");
    if (!p || !t) {
        fprintf(stderr, "rcxpack: cannot run %s\n", cmd);
        return -1;
    }
    while ((n = fread(buf, 1, sizeof buf, p)) > 0)
        fwrite(buf, 1, n, t);
    bad = pclose(p) != 0;
    bad = bad || symbol(t, "_rcx_image_base", &l->base) || symbol(t, "_rcx_head_end", &l->head_end) ||
          symbol(t, "_rcx_packed_start", &l->packed_start) ||
          symbol(t, "_rcx_image_end", &l->image_end) || symbol(t, "_rcx_download_end", &l->download_end) ||
          symbol(t, "_rcx_ram_end", &l->ram_end);
    fclose(t);
    return bad ? -1 : 0;
}

static void record(FILE *f, char type, unsigned addr, const uint8_t *data, size_t n)
{
    unsigned sum = (unsigned)n + 3 + (addr >> 8) + (addr & 0xFF);
    size_t i;
    fprintf(f, "S%c%02X%04X", type, (unsigned)n + 3, addr);
    for (i = 0; i < n; i++) {
        fprintf(f, "%02X", data[i]);
        sum += data[i];
    }
    fprintf(f, "%02X\n", ~sum & 0xFF);
}

static size_t read_file(const char *path, uint8_t *buf, size_t max)
{
    size_t n;
    FILE *f = fopen(path, "rb");
    if (!f) {
        perror(path);
        return 0;
    }
    n = fread(buf, 1, max, f);
    fclose(f);
    return n;
}

int main(int argc, char **argv)
{
    static uint8_t image[0x10000], download[0x10000];
    struct pack_layout l;
    const char *why, *name, *out;
    size_t n, head, unpacker, len, i;
    FILE *f;

    if (argc != 6) {
        fprintf(stderr, "usage: %s <nm> <image> <image.bin> <unpacker.bin> <out.srec>\n", argv[0]);
        return 2;
    }
    out = argv[5];
    if (read_layout(argv[1], argv[2], &l))
        return 1;
    n = read_file(argv[3], image, sizeof image);
    head = l.head_end - l.base;
    unpacker = l.packed_start - l.head_end;
    if (n != l.image_end - l.base || l.head_end <= l.base || l.head_end >= l.image_end || l.packed_start < l.head_end ||
        l.packed_start > l.download_end || read_file(argv[4], download + head, unpacker + 1) != unpacker) {
        fprintf(stderr, "rcxpack: %s (%zu bytes) or %s is not the image 0x%04lX-0x%04lX with %zu bytes of unpacker\n",
                argv[3], n, argv[4], l.base, l.image_end, unpacker);
        return 1;
    }
    memcpy(download, image, head);
    len = pack(image + head, n - head, download + head + unpacker);
    why = len ? pack_check_in_place(&l, image, download + head, download + head + unpacker, len) : "out of memory";
    if (why) {
        fprintf(stderr, "rcxpack: %s: %s (head %zu + unpacker %zu + packed %zu bytes)\n", out, why, head, unpacker, len);
        return 1;
    }
    len += head + unpacker;

    f = fopen(out, "w");
    if (!f) {
        perror(out);
        return 1;
    }
    name = strrchr(out, '/') ? strrchr(out, '/') + 1 : out;
    record(f, '0', 0, (const uint8_t *)name, strlen(name));
    for (i = 0; i < len; i += 16)
        record(f, '1', (unsigned)(l.base + i), download + i, len - i < 16 ? len - i : 16);
    record(f, '9', (unsigned)l.base, NULL, 0);
    if (fclose(f)) {
        perror(out);
        remove(out);
        return 1;
    }
    printf("rcxpack: %s: %zu bytes downloaded (head %zu, unpacker %zu, packed %zu) for an image of %zu bytes\n", name,
           len, head, unpacker, len - head - unpacker, n);
    return 0;
}
