"""``nuc_dpc_top``: NUC followed by DPC, fed by raw pixels and coefficient words."""

from __future__ import annotations

import numpy as np

from irnuc.nuc_fixed import _kernels
from irnuc.nuc_fixed.config import PipelineConfig
from irnuc.nuc_fixed.memimage import check_words
from irnuc.nuc_fixed.nuc import datapath_constants, out_dtype
from irnuc.nuc_fixed.validate import InputError, as_config, check_frame_shape, int_array


def nuc_dpc_top(raw: np.ndarray, words: np.ndarray, cfg: PipelineConfig | str) -> np.ndarray:
    """Corrected frames from raw ADC frames and per-pixel coefficient words.

    Equal, bit for bit, to ``dpc_core(nuc_core(raw, gain, offset), bad)`` with
    ``gain, offset, bad = unpack_words(words)``, computed in one fused pass.

    Parameters
    ----------
    raw : integer array_like, (H, W) or (N, H, W)
        ADC codes in [0, 2^A - 1].
    words : integer array_like, (H, W)
        Coefficient words (memory image version 1 layout), in [0, 2^WW - 1].
    cfg : PipelineConfig or str

    Returns
    -------
    ndarray of the shape of ``raw``, uint16 if B <= 16 else uint32.
    """
    cfg = as_config(cfg)
    x = int_array("raw", raw, 0, (1 << cfg.adc_bits) - 1)
    h, w = check_frame_shape("raw", x.shape, cfg)
    wd = check_words(words, cfg)
    if wd.shape != (h, w):
        raise InputError(f"words has shape {wd.shape} but the frames of raw are {(h, w)}")
    x3 = np.ascontiguousarray(x.reshape(-1, h, w))
    out = np.empty(x3.shape, dtype=out_dtype(cfg))
    fields = cfg.word_fields
    _kernels.nuc_words(x3, np.ascontiguousarray(wd), out, fields["gain"], fields["offset"],
                       *datapath_constants(cfg))
    lsb = np.uint64(fields["bad"][0])
    _kernels.dpc_inplace(out, np.ascontiguousarray(((wd >> lsb) & np.uint64(1)).astype(bool)))
    return out.reshape(x.shape)
