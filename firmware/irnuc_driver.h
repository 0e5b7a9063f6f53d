/*
 * irnuc_driver.h - a small driver of irnuc_axis_top's register file: an example for the
 * firmware of a camera that integrates the core (docs/integration.md, "Firmware").
 *
 * The register layout is irnuc_regs.h, generated from nuc_fixed/registers.rdl by
 * peakrdl-cheader (the struct irnuc_regs_t, IRNUC_REGS__<REGISTER>__<FIELD>_bm / _bp /
 * _reset). Its reset values are those of the map's default build (typical14): those that
 * are configuration values (CONFIG, FORMAT, FRAME_MAX, ...) are read from the hardware
 * here, not taken from the header; `irnuc regmap --pipeline NAME` writes the header of
 * one build.
 *
 * Every access is one 32-bit read or write (the register file is an AXI4-Lite slave)
 * through IRNUC_READ32 / IRNUC_WRITE32: volatile loads and stores by default; a platform,
 * or a test (tests/test_firmware.py runs this driver against the Python register model),
 * may define its own before including this header. The same sequence in Python, over the
 * register model peakrdl-python generates from the same map, is irnuc.cosim.driver; the
 * co-simulation runs it against the RTL (cocotb_tests/tb_axis_ffc.py).
 */
#ifndef IRNUC_DRIVER_H
#define IRNUC_DRIVER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "irnuc_regs.h"

/* The 32-bit register `member` of the register file at `regs` (irnuc_regs_t is packed, so
 * a member's address is formed from the base and its offset, which is word aligned). */
#define IRNUC_REG(regs, member) \
    ((volatile uint32_t *)((uintptr_t)(regs) + offsetof(irnuc_regs_t, member)))

#ifndef IRNUC_READ32
#define IRNUC_READ32(reg) (*(reg))
#define IRNUC_WRITE32(reg, value) (*(reg) = (uint32_t)(value))
#endif

/* Return codes. */
enum {
    IRNUC_OK = 0,
    IRNUC_ERR_ID = -1,       /* ID is not "IRNC": nothing of ours at that address */
    IRNUC_ERR_VERSION = -2,  /* a register map major version this driver does not know */
    IRNUC_ERR_METHOD = -3,   /* the core is built for another correction method */
    IRNUC_ERR_SIZE = -4,     /* a frame size of 0 or above FRAME_MAX */
    IRNUC_ERR_NO_FFC = -5,   /* the core has no FFC unit (CONFIG.ffc = 0) */
    IRNUC_ERR_TIMEOUT = -6   /* the FFC did not finish within the polls given */
};

/* CONFIG.method: the base correction method the core is built for (irnuc_pkg::method_e,
 * nuc_fixed/rtl_spec.py METHOD; tests/test_firmware.py compares them). */
enum irnuc_method {
    IRNUC_ONE_POINT = 0,
    IRNUC_TWO_POINT = 1,
    IRNUC_PIECEWISE = 2,
    IRNUC_QUADRATIC = 3,
    IRNUC_TC_OFFSET = 4,
    IRNUC_TABLE_INTERP = 5,
    IRNUC_TC_HOUSING = 6
};

/* What the core was built with (read once by irnuc_probe). */
typedef struct {
    uint32_t version;    /* VERSION */
    uint32_t config;     /* CONFIG: widths, method, stages, modes */
    uint32_t format;     /* FORMAT: gain and offset formats */
    uint32_t frame_max;  /* FRAME_MAX: the largest frame */
} irnuc_info_t;

/* The registers of a calibration (the method's and stage's global coefficients; the
 * per-pixel words are the memory image a DMA streams into s_axis_coef). `set` names the
 * ones to write: IRNUC_CAL_* bits. */
enum {
    IRNUC_CAL_GAIN = 1u << 0,        /* one_point */
    IRNUC_CAL_LEVEL = 1u << 1,       /* piecewise */
    IRNUC_CAL_T_REF = 1u << 2,       /* tc_offset, tc_housing */
    IRNUC_CAL_BLIND_REF = 1u << 3,   /* blind_drift */
    IRNUC_CAL_DRIFT_GAIN = 1u << 4,  /* blind_drift */
    IRNUC_CAL_FFC_TARGET = 1u << 5,  /* ffc */
    IRNUC_CAL_TABLES = 1u << 6,      /* table_interp: TABLE_READING[0 .. tables - 1] */
    IRNUC_CAL_H_REF = 1u << 7        /* tc_housing */
};

typedef struct {
    uint32_t set;
    uint64_t gain, level, t_ref, blind_ref, drift_gain, ffc_target, h_ref;
    unsigned tables;
    uint32_t table_readings[16];
} irnuc_calibration_t;

/* Status and counters (irnuc_read_status). */
typedef struct {
    uint32_t status, irq_status;
    uint32_t frames_in, frames_out, pixels_in, pixels_out, dropped, padded;
    uint32_t sof_errors, eol_errors, coef_errors;
} irnuc_status_t;

/* ID and VERSION.major checked; CONFIG, FORMAT and FRAME_MAX read into `info`. */
int irnuc_probe(volatile irnuc_regs_t *regs, irnuc_info_t *info);

unsigned irnuc_info_method(const irnuc_info_t *info);
bool irnuc_info_has_ffc(const irnuc_info_t *info);

/* The core must be built for `method`; FRAME_SIZE (width x height, each 1 .. FRAME_MAX's)
 * and CTRL written. Both are shadowed: they take effect at the next frame start. */
int irnuc_configure(volatile irnuc_regs_t *regs, const irnuc_info_t *info,
                    enum irnuc_method method, unsigned width, unsigned height, uint32_t ctrl);

/* The CTRL of normal operation: NUC and DPC on, the coefficient stream's tlast checked. */
#define IRNUC_CTRL_DEFAULT (IRNUC_REGS__CTRL__NUC_EN_bm | IRNUC_REGS__CTRL__DPC_EN_bm \
                            | IRNUC_REGS__CTRL__COEF_SYNC_bm)

/* A 64-bit method register: its LO word, then its HI word. */
void irnuc_write64(volatile uint32_t *lo, volatile uint32_t *hi, uint64_t value);

/* The calibration's registers, in map order. */
void irnuc_load_calibration(volatile irnuc_regs_t *regs, const irnuc_calibration_t *cal);

/* The FPA reading of the next frame (tc_offset, table_interp, tc_housing; shadowed). */
void irnuc_set_reading(volatile irnuc_regs_t *regs, uint64_t reading);

/* The housing sensor's reading of the next frame (tc_housing; shadowed): written each
 * frame beside the FPA reading. */
void irnuc_set_housing_reading(volatile irnuc_regs_t *regs, uint64_t reading);

/* IRQ_ENABLE: IRNUC_REGS__IRQ_ENABLE__*_bm bits. */
void irnuc_enable_irq(volatile irnuc_regs_t *regs, uint32_t mask);

/* A flat-field correction of `frames` shutter frames from the next frame start (close the
 * shutter first); irnuc_ffc_wait polls FFC_STATUS.done up to `max_polls` times and clears
 * IRQ_STATUS.ffc_done (W1C) once it is done. */
int irnuc_ffc_start(volatile irnuc_regs_t *regs, const irnuc_info_t *info, unsigned frames);
int irnuc_ffc_wait(volatile irnuc_regs_t *regs, unsigned max_polls);

/* The FFC request (docs/integration.md, "FFC requests"): IRQ_STATUS.ffc_request rises when
 * `period` frames have passed since the last FFC or the FPA reading has moved by
 * `threshold` codes since it (0: that trigger off). */
int irnuc_ffc_policy(volatile irnuc_regs_t *regs, const irnuc_info_t *info, uint32_t period,
                     uint32_t threshold);

/* STATUS, IRQ_STATUS and the counters read; the sticky bits read as 1 cleared (W1C). */
void irnuc_read_status(volatile irnuc_regs_t *regs, irnuc_status_t *st);

#endif /* IRNUC_DRIVER_H */
