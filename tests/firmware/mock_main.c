/*
 * The C driver example (firmware/irnuc_example.c) against a register space served over
 * stdin / stdout by tests/test_firmware.py: every access is a line to stdout, "W <offset>
 * <value>" or "R <offset>" (hex), and a read waits for its value on stdin. The example's
 * settings come as key=value arguments; the result is a last line "END <rc> <status...>".
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "irnuc_regs.h"

static volatile irnuc_regs_t *mock_base;

static uint32_t mock_read(volatile uint32_t *reg);
static void mock_write(volatile uint32_t *reg, uint32_t value);

/* The accessors here are functions taking the register's address: gcc then tracks it
 * back to the packed irnuc_regs_t (whose members are all word aligned). */
#pragma GCC diagnostic ignored "-Waddress-of-packed-member"
#define IRNUC_READ32(reg) mock_read(reg)
#define IRNUC_WRITE32(reg, value) mock_write((reg), (uint32_t)(value))
#include "irnuc_driver.c"
#include "irnuc_example.c"

static unsigned long offset_of(volatile uint32_t *reg)
{
    return (unsigned long)((uintptr_t)reg - (uintptr_t)mock_base);
}

static uint32_t mock_read(volatile uint32_t *reg)
{
    unsigned long value;
    printf("R %03lx\n", offset_of(reg));
    fflush(stdout);
    if (scanf("%lx", &value) != 1)
        exit(3);
    return (uint32_t)value;
}

static void mock_write(volatile uint32_t *reg, uint32_t value)
{
    printf("W %03lx %08lx\n", offset_of(reg), (unsigned long)value);
    fflush(stdout);
}

int main(int argc, char **argv)
{
    static irnuc_regs_t space;  /* only its addresses are used */
    irnuc_example_t ex = {.method = IRNUC_TWO_POINT, .width = 1, .height = 1, .max_polls = 100};
    irnuc_status_t st = {0};
    mock_base = &space;
    for (int k = 1; k < argc; k++) {
        char *eq = strchr(argv[k], '=');
        if (!eq)
            return 2;
        *eq = '\0';
        const char *key = argv[k];
        unsigned long long v = strtoull(eq + 1, NULL, 0);
        if (!strcmp(key, "method")) ex.method = (enum irnuc_method)v;
        else if (!strcmp(key, "width")) ex.width = (unsigned)v;
        else if (!strcmp(key, "height")) ex.height = (unsigned)v;
        else if (!strcmp(key, "reading")) { ex.has_reading = true; ex.reading = v; }
        else if (!strcmp(key, "ffc_frames")) ex.ffc_frames = (unsigned)v;
        else if (!strcmp(key, "max_polls")) ex.max_polls = (unsigned)v;
        else if (!strcmp(key, "ffc_period")) ex.ffc_period = (uint32_t)v;
        else if (!strcmp(key, "ffc_threshold")) ex.ffc_threshold = (uint32_t)v;
        else if (!strcmp(key, "gain")) { ex.cal.set |= IRNUC_CAL_GAIN; ex.cal.gain = v; }
        else if (!strcmp(key, "level")) { ex.cal.set |= IRNUC_CAL_LEVEL; ex.cal.level = v; }
        else if (!strcmp(key, "t_ref")) { ex.cal.set |= IRNUC_CAL_T_REF; ex.cal.t_ref = v; }
        else if (!strcmp(key, "blind_ref")) { ex.cal.set |= IRNUC_CAL_BLIND_REF; ex.cal.blind_ref = v; }
        else if (!strcmp(key, "drift_gain")) { ex.cal.set |= IRNUC_CAL_DRIFT_GAIN; ex.cal.drift_gain = v; }
        else if (!strcmp(key, "ffc_target")) { ex.cal.set |= IRNUC_CAL_FFC_TARGET; ex.cal.ffc_target = v; }
        else if (!strcmp(key, "table") && ex.cal.tables < 16) {
            ex.cal.set |= IRNUC_CAL_TABLES;
            ex.cal.table_readings[ex.cal.tables++] = (uint32_t)v;
        }
        else if (!strcmp(key, "enum")) {  /* print the driver's method codes */
            printf("ENUM %d %d %d %d %d %d %d\n", IRNUC_ONE_POINT, IRNUC_TWO_POINT, IRNUC_PIECEWISE,
                   IRNUC_QUADRATIC, IRNUC_TC_OFFSET, IRNUC_TABLE_INTERP, IRNUC_TC_HOUSING);
            return 0;
        }
        else return 2;
    }
    int rc = irnuc_example((volatile irnuc_regs_t *)mock_base, &ex, &st);
    printf("END %d %lx %lx %lx %lx %lx %lx %lx %lx %lx %lx %lx\n", rc,
           (unsigned long)st.status, (unsigned long)st.irq_status, (unsigned long)st.frames_in,
           (unsigned long)st.frames_out, (unsigned long)st.pixels_in,
           (unsigned long)st.pixels_out, (unsigned long)st.dropped, (unsigned long)st.padded,
           (unsigned long)st.sof_errors, (unsigned long)st.eol_errors,
           (unsigned long)st.coef_errors);
    return 0;
}
