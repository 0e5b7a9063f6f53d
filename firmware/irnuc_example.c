/*
 * irnuc_example.c - the bring-up of irnuc_axis_top with irnuc_driver.h, as a camera's
 * firmware would run it: identify the core, set the frame size and the enables, load the
 * calibration's registers, enable the interrupts, run a flat-field correction (the
 * shutter closed), read the status and counters. irnuc_example() is the sequence; main()
 * is for a bare-metal target with the register file at IRNUC_BASE (build with
 * -DIRNUC_BASE=0x43c00000, say). tests/test_firmware.py builds it with gcc and runs it
 * against the Python register model; irnuc.cosim.driver.example is the same sequence in
 * Python.
 */
#include "irnuc_example.h"

int irnuc_example(volatile irnuc_regs_t *regs, const irnuc_example_t *ex, irnuc_status_t *st)
{
    irnuc_info_t info;
    int rc = irnuc_probe(regs, &info);
    if (rc != IRNUC_OK)
        return rc;
    rc = irnuc_configure(regs, &info, ex->method, ex->width, ex->height, IRNUC_CTRL_DEFAULT);
    if (rc != IRNUC_OK)
        return rc;
    irnuc_load_calibration(regs, &ex->cal);
    if (ex->has_reading)
        irnuc_set_reading(regs, ex->reading);
    irnuc_enable_irq(regs, IRNUC_REGS__IRQ_ENABLE__ERROR_bm
                           | (ex->ffc_frames ? IRNUC_REGS__IRQ_ENABLE__FFC_DONE_bm : 0));
    /* Here the platform starts the coefficient DMA (the memory image of irnuc calibrate,
     * one word per pixel) and the video: docs/integration.md, "DMA". */
    if (ex->ffc_frames) {
        rc = irnuc_ffc_start(regs, &info, ex->ffc_frames);
        if (rc == IRNUC_OK)
            rc = irnuc_ffc_wait(regs, ex->max_polls);
    }
    irnuc_read_status(regs, st);
    return rc;
}

#ifdef IRNUC_BASE
int main(void)
{
    static const irnuc_example_t ex = {
        .method = IRNUC_TWO_POINT, .width = 640, .height = 480, .max_polls = 1000000u,
    };
    irnuc_status_t st;
    return irnuc_example((volatile irnuc_regs_t *)(uintptr_t)IRNUC_BASE, &ex, &st) ? 1 : 0;
}
#endif
