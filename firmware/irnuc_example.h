/*
 * irnuc_example.h - the bring-up sequence of irnuc_example.c.
 */
#ifndef IRNUC_EXAMPLE_H
#define IRNUC_EXAMPLE_H

#include "irnuc_driver.h"

/* What the bring-up sets. */
typedef struct {
    enum irnuc_method method;   /* the method the core must be built for */
    unsigned width, height;     /* the frame size */
    irnuc_calibration_t cal;    /* the calibration's registers */
    bool has_reading;           /* tc_offset, table_interp: the first frame's FPA reading */
    uint64_t reading;
    unsigned ffc_frames;        /* shutter frames of a flat-field correction; 0: none */
    unsigned max_polls;         /* FFC_STATUS reads before giving up */
} irnuc_example_t;

/* Returns IRNUC_OK or the first error; `st` holds the status read at the end. */
int irnuc_example(volatile irnuc_regs_t *regs, const irnuc_example_t *ex, irnuc_status_t *st);

#endif /* IRNUC_EXAMPLE_H */
