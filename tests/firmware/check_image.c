/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Checks a firmware image in S-record form the way the RCX ROM and the download tools will see it
 * (rcx-hardware.md 1.3, 2.1, 2.2, 2.5), and prints its size and the checksum a downloader announces.
 *
 *   check_image <image.srec>      exit status 0 when every check passes, 1 otherwise
 *
 * Checks: only S0/S1/S5/S9 records with valid record checksums, no byte given twice; one S9 whose
 * entry is 0x8000; data start at 0x8000 and stay within 0x8000-0xEE5D (the ROM keeps its variables
 * from 0xEE5E on); at most 16384 bytes from 0x8000 to the last byte; the text
 * "Do you byte, when I knock?" lies wholly inside 0x8000-0xCBFF.
 * The ROM checksum is the 16-bit sum of the bytes 0x8000-0xCBFF; the ROM clears that range before a
 * download, so bytes the image does not give count as 0.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define IMAGE_START 0x8000ul
#define IMAGE_MAX 16384ul
#define CHECKED_END 0xCC00ul /* one past the last byte the ROM sums and searches */
#define ROM_VARS 0xEE5Eul    /* one past the last byte a download may write */

static const char knock[] = "Do you byte, when I knock?";

static unsigned char mem[0x10000];
static unsigned char given[0x10000];
static int failures;

static void fail(const char *file, unsigned line, const char *what)
{
    if (line)
        fprintf(stderr, "%s:%u: %s\n", file, line, what);
    else
        fprintf(stderr, "%s: %s\n", file, what);
    failures++;
}

static int hexval(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    return -1;
}

/* The bytes of one record after "Sn"; returns their number, or -1 if the text is not hex pairs. */
static int record_bytes(const char *text, unsigned char *out, int max)
{
    int n = 0;

    while (text[0] && text[0] != '\n' && text[0] != '\r') {
        int hi = hexval(text[0]), lo = hexval(text[1]);

        if (hi < 0 || lo < 0 || n == max)
            return -1;
        out[n++] = (unsigned char)(hi * 16 + lo);
        text += 2;
    }
    return n;
}

int main(int argc, char **argv)
{
    char line[600];
    unsigned char rec[300];
    unsigned line_no = 0, s9_count = 0;
    unsigned long entry = 0, lowest = 0x10000, highest = 0, count = 0, sum = 0, addr, knock_at = 0;
    const char *file;
    FILE *in;

    if (argc != 2) {
        fprintf(stderr, "usage: %s <image.srec>\n", argv[0]);
        return 1;
    }
    file = argv[1];
    in = fopen(file, "r");
    if (!in) {
        perror(file);
        fprintf(stderr, "%s: no firmware image (build it with `make firmware`)\n", file);
        return 1;
    }

    while (fgets(line, sizeof line, in)) {
        int n, i, addr_len;
        unsigned check = 0;

        line_no++;
        if (line[0] == '\n' || line[0] == '\r' || line[0] == 0)
            continue;
        if (line[0] != 'S' || !strchr("0159", line[1]) || line[1] == 0) {
            fail(file, line_no, "not an S0, S1, S5 or S9 record (loaders take 16-bit addresses only)");
            continue;
        }
        n = record_bytes(line + 2, rec, (int)sizeof rec);
        addr_len = 2;
        if (n < 1 + addr_len + 1 || rec[0] != n - 1) {
            fail(file, line_no, "malformed record (length)");
            continue;
        }
        for (i = 0; i < n - 1; i++)
            check += rec[i];
        if ((unsigned char)~check != rec[n - 1]) {
            fail(file, line_no, "record checksum wrong");
            continue;
        }
        addr = (unsigned long)rec[1] << 8 | rec[2];
        if (line[1] == '1') {
            for (i = 1 + addr_len; i < n - 1; i++, addr++) {
                if (addr > 0xFFFF) {
                    fail(file, line_no, "data run past 0xFFFF");
                    break;
                }
                if (given[addr]) {
                    fail(file, line_no, "byte given twice");
                    break;
                }
                given[addr] = 1;
                mem[addr] = rec[i];
                count++;
                if (addr < lowest)
                    lowest = addr;
                if (addr > highest)
                    highest = addr;
            }
        } else if (line[1] == '9') {
            s9_count++;
            entry = addr;
        }
    }
    fclose(in);

    if (count == 0) {
        fail(file, 0, "no data");
        return 1;
    }
    if (s9_count != 1)
        fail(file, 0, "needs exactly one S9 (entry) record");
    else if (entry != IMAGE_START)
        fail(file, 0, "entry (S9) is not 0x8000");
    if (lowest != IMAGE_START)
        fail(file, 0, "image does not start at 0x8000");
    if (lowest < IMAGE_START || highest >= ROM_VARS)
        fail(file, 0, "data outside 0x8000-0xEE5D");
    if (highest + 1 - IMAGE_START > IMAGE_MAX)
        fail(file, 0, "image larger than 16384 bytes");

    for (addr = IMAGE_START; addr + sizeof knock - 1 <= CHECKED_END; addr++) {
        if (memcmp(mem + addr, knock, sizeof knock - 1) == 0) {
            knock_at = addr;
            break;
        }
    }
    if (!knock_at)
        fail(file, 0, "knock string \"Do you byte, when I knock?\" not inside 0x8000-0xCBFF");

    for (addr = IMAGE_START; addr < CHECKED_END; addr++)
        sum += mem[addr];

    printf("%s:\n", file);
    printf("  image        0x%04lX-0x%04lX, %lu bytes (%lu given), %ld left of 16384\n", lowest, highest,
           highest + 1 - lowest, count, (long)IMAGE_MAX - (long)(highest + 1 - IMAGE_START));
    printf("  entry        0x%04lX\n", entry);
    if (knock_at)
        printf("  knock string 0x%04lX\n", knock_at);
    printf("  ROM checksum 0x%04lX (16-bit sum of 0x8000-0xCBFF, missing bytes 0)\n", sum & 0xFFFF);
    if (failures) {
        printf("  FAILED: %d problem(s)\n", failures);
        return 1;
    }
    printf("  OK\n");
    return 0;
}
