"""Small frames from the physics model (``model/``), calibrated by ``nuc_fixed``.

The default camera preset is shrunk to a frame that fits the configuration's line buffers,
its ADC width is the configuration's, and its defect rates are raised so that a small frame
carries defects (isolated and clustered). Two blackbody stacks give the two-point
calibration; the frames to correct are a non-uniform scene in between.
"""

from __future__ import annotations

import numpy as np

from irnuc.nuc_fixed import PipelineConfig, pack_words


def calibrated_model_frames(cfg: PipelineConfig, seed: int = 1, rows: int = 12,
                            cols: int = 20, n_frames: int = 2
                            ) -> tuple[list[np.ndarray], np.ndarray]:
    """Raw scene frames (each (H, W) int64) and their coefficient words (H, W) uint64."""
    from irnuc import model
    from irnuc.nuc_fixed.calibrate import calibrate

    rows, cols = min(rows, cfg.max_height), min(cols, cfg.max_width)
    rates = {"dead": 0.01, "stuck_high": 0.005, "stuck_low": 0.005, "hot": 0.01,
             "cold": 0.01, "low_resp": 0.01, "high_resp": 0.005, "noisy": 0.0}
    overrides = {"fpa.active_rows": rows, "fpa.active_cols": cols,
                 "adc.bits": cfg.adc_bits,
                 **{f"fpa.defects.rates.{k}": v for k, v in rates.items()}}
    mcfg = model.load_preset("default", overrides)
    lo = model.simulate(mcfg, [290.0], "uniform", seed=seed, repeats=4).codes
    hi = model.simulate(mcfg, [330.0], "uniform", seed=seed, repeats=4).codes
    cal = calibrate(lo, hi, cfg)
    words = pack_words(cal.gain_code, cal.offset_code, cal.bad, cfg)
    scene = model.simulate(mcfg, np.linspace(295.0, 325.0, n_frames), "gradient", seed=seed)
    frames = [np.asarray(f, dtype=np.int64) for f in scene.codes]
    return frames, words
