/*
 * irnuc_driver.c - the driver of irnuc_driver.h. Each function's register accesses, in
 * order, are those of its Python twin in irnuc/cosim/driver.py (tests/test_firmware.py
 * compares the two access by access).
 */
#include "irnuc_driver.h"

#define FIELD(value, reg, field) \
    (((value) & IRNUC_REGS__##reg##__##field##_bm) >> IRNUC_REGS__##reg##__##field##_bp)

int irnuc_probe(volatile irnuc_regs_t *regs, irnuc_info_t *info)
{
    if (IRNUC_READ32(IRNUC_REG(regs, ID)) != IRNUC_REGS__ID__VALUE_reset)
        return IRNUC_ERR_ID;
    info->version = IRNUC_READ32(IRNUC_REG(regs, VERSION));
    if (FIELD(info->version, VERSION, MAJOR) != IRNUC_REGS__VERSION__MAJOR_reset)
        return IRNUC_ERR_VERSION;
    info->config = IRNUC_READ32(IRNUC_REG(regs, CONFIG));
    info->format = IRNUC_READ32(IRNUC_REG(regs, FORMAT));
    info->frame_max = IRNUC_READ32(IRNUC_REG(regs, FRAME_MAX));
    return IRNUC_OK;
}

unsigned irnuc_info_method(const irnuc_info_t *info)
{
    return FIELD(info->config, CONFIG, METHOD);
}

bool irnuc_info_has_ffc(const irnuc_info_t *info)
{
    return FIELD(info->config, CONFIG, FFC) != 0;
}

int irnuc_configure(volatile irnuc_regs_t *regs, const irnuc_info_t *info,
                    enum irnuc_method method, unsigned width, unsigned height, uint32_t ctrl)
{
    if (irnuc_info_method(info) != (unsigned)method)
        return IRNUC_ERR_METHOD;
    if (width == 0 || width > FIELD(info->frame_max, FRAME_MAX, WIDTH)
        || height == 0 || height > FIELD(info->frame_max, FRAME_MAX, HEIGHT))
        return IRNUC_ERR_SIZE;
    IRNUC_WRITE32(IRNUC_REG(regs, FRAME_SIZE),
                  ((uint32_t)width << IRNUC_REGS__FRAME_SIZE__WIDTH_bp)
                  | ((uint32_t)height << IRNUC_REGS__FRAME_SIZE__HEIGHT_bp));
    IRNUC_WRITE32(IRNUC_REG(regs, CTRL), ctrl);
    return IRNUC_OK;
}

void irnuc_write64(volatile uint32_t *lo, volatile uint32_t *hi, uint64_t value)
{
    IRNUC_WRITE32(lo, (uint32_t)value);
    IRNUC_WRITE32(hi, (uint32_t)(value >> 32));
}

void irnuc_load_calibration(volatile irnuc_regs_t *regs, const irnuc_calibration_t *cal)
{
    if (cal->set & IRNUC_CAL_GAIN)
        irnuc_write64(IRNUC_REG(regs, GAIN.LO), IRNUC_REG(regs, GAIN.HI), cal->gain);
    if (cal->set & IRNUC_CAL_LEVEL)
        irnuc_write64(IRNUC_REG(regs, LEVEL.LO), IRNUC_REG(regs, LEVEL.HI), cal->level);
    if (cal->set & IRNUC_CAL_T_REF)
        irnuc_write64(IRNUC_REG(regs, T_REF.LO), IRNUC_REG(regs, T_REF.HI), cal->t_ref);
    if (cal->set & IRNUC_CAL_BLIND_REF)
        irnuc_write64(IRNUC_REG(regs, BLIND_REF.LO), IRNUC_REG(regs, BLIND_REF.HI), cal->blind_ref);
    if (cal->set & IRNUC_CAL_DRIFT_GAIN)
        irnuc_write64(IRNUC_REG(regs, DRIFT_GAIN.LO), IRNUC_REG(regs, DRIFT_GAIN.HI), cal->drift_gain);
    if (cal->set & IRNUC_CAL_FFC_TARGET)
        irnuc_write64(IRNUC_REG(regs, FFC_TARGET.LO), IRNUC_REG(regs, FFC_TARGET.HI), cal->ffc_target);
    if (cal->set & IRNUC_CAL_H_REF)
        irnuc_write64(IRNUC_REG(regs, H_REF.LO), IRNUC_REG(regs, H_REF.HI), cal->h_ref);
    if (cal->set & IRNUC_CAL_TABLES)
        for (unsigned k = 0; k < cal->tables && k < 16; k++)
            IRNUC_WRITE32(IRNUC_REG(regs, TABLE_READING) + k, cal->table_readings[k]);
}

void irnuc_set_reading(volatile irnuc_regs_t *regs, uint64_t reading)
{
    irnuc_write64(IRNUC_REG(regs, READING.LO), IRNUC_REG(regs, READING.HI), reading);
}

void irnuc_set_housing_reading(volatile irnuc_regs_t *regs, uint64_t reading)
{
    irnuc_write64(IRNUC_REG(regs, HOUSING_READING.LO), IRNUC_REG(regs, HOUSING_READING.HI),
                  reading);
}

void irnuc_enable_irq(volatile irnuc_regs_t *regs, uint32_t mask)
{
    IRNUC_WRITE32(IRNUC_REG(regs, IRQ_ENABLE), mask);
}

int irnuc_ffc_start(volatile irnuc_regs_t *regs, const irnuc_info_t *info, unsigned frames)
{
    if (!irnuc_info_has_ffc(info))
        return IRNUC_ERR_NO_FFC;
    IRNUC_WRITE32(IRNUC_REG(regs, FFC_CTRL),
                  IRNUC_REGS__FFC_CTRL__START_bm
                  | (((uint32_t)frames << IRNUC_REGS__FFC_CTRL__FRAMES_bp)
                     & IRNUC_REGS__FFC_CTRL__FRAMES_bm));
    return IRNUC_OK;
}

int irnuc_ffc_policy(volatile irnuc_regs_t *regs, const irnuc_info_t *info, uint32_t period,
                     uint32_t threshold)
{
    if (!irnuc_info_has_ffc(info))
        return IRNUC_ERR_NO_FFC;
    IRNUC_WRITE32(IRNUC_REG(regs, FFC_PERIOD),
                  (period << IRNUC_REGS__FFC_PERIOD__FRAMES_bp) & IRNUC_REGS__FFC_PERIOD__FRAMES_bm);
    IRNUC_WRITE32(IRNUC_REG(regs, FFC_THRESHOLD),
                  (threshold << IRNUC_REGS__FFC_THRESHOLD__CODES_bp)
                  & IRNUC_REGS__FFC_THRESHOLD__CODES_bm);
    return IRNUC_OK;
}

int irnuc_ffc_wait(volatile irnuc_regs_t *regs, unsigned max_polls)
{
    for (unsigned k = 0; k < max_polls; k++) {
        if (IRNUC_READ32(IRNUC_REG(regs, FFC_STATUS)) & IRNUC_REGS__FFC_STATUS__DONE_bm) {
            IRNUC_WRITE32(IRNUC_REG(regs, IRQ_STATUS), IRNUC_REGS__IRQ_STATUS__FFC_DONE_bm);
            return IRNUC_OK;
        }
    }
    return IRNUC_ERR_TIMEOUT;
}

void irnuc_read_status(volatile irnuc_regs_t *regs, irnuc_status_t *st)
{
    /* The sticky bits: the framing errors of STATUS and the causes of IRQ_STATUS. */
    const uint32_t errors = IRNUC_REGS__STATUS__SOF_EARLY_bm | IRNUC_REGS__STATUS__SOF_LATE_bm
        | IRNUC_REGS__STATUS__EOL_EARLY_bm | IRNUC_REGS__STATUS__EOL_LATE_bm
        | IRNUC_REGS__STATUS__COEF_EARLY_bm | IRNUC_REGS__STATUS__COEF_LATE_bm;

    st->status = IRNUC_READ32(IRNUC_REG(regs, STATUS));
    st->irq_status = IRNUC_READ32(IRNUC_REG(regs, IRQ_STATUS));
    st->frames_in = IRNUC_READ32(IRNUC_REG(regs, FRAMES_IN));
    st->frames_out = IRNUC_READ32(IRNUC_REG(regs, FRAMES_OUT));
    st->pixels_in = IRNUC_READ32(IRNUC_REG(regs, PIXELS_IN));
    st->pixels_out = IRNUC_READ32(IRNUC_REG(regs, PIXELS_OUT));
    st->dropped = IRNUC_READ32(IRNUC_REG(regs, DROPPED));
    st->padded = IRNUC_READ32(IRNUC_REG(regs, PADDED));
    st->sof_errors = IRNUC_READ32(IRNUC_REG(regs, SOF_ERRORS));
    st->eol_errors = IRNUC_READ32(IRNUC_REG(regs, EOL_ERRORS));
    st->coef_errors = IRNUC_READ32(IRNUC_REG(regs, COEF_ERRORS));
    if (st->status & errors)
        IRNUC_WRITE32(IRNUC_REG(regs, STATUS), st->status & errors);
    if (st->irq_status)
        IRNUC_WRITE32(IRNUC_REG(regs, IRQ_STATUS), st->irq_status);
}
