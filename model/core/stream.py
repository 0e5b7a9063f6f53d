"""Kernels of the per-frame passes of the pipeline, one pass over the pixels each.

* :func:`power`: the absorbed power of frames, Q = k L_scene + q_env with a fixed housing
  term, or with q_env = eps A pi ((1 - seen) L_cam - net L_s) per frame (the skimming
  pixels under a substrate shield: eps A pi (L_s - net L_s)); then times the defects'
  responsivity over the active area. The same operations in the same order as the numpy
  expressions they replace, so the same bits;
* :func:`integrate_frames`: the integrator, v_reset + gain (v_ref - v_bolo);
* :func:`frame_statistics`: the diagnostics of frames (temperature-rise range and sum over
  the active area, codes at either end of the ADC range).

The inner loops run over one row without branches and with IEEE arithmetic
(``error_model='numpy'``) so that the compiler vectorizes them.
"""

import math

import numpy as np
from numba import njit, prange

from irnuc.model.core.bolometer import STATUS_INVALID, STATUS_OK
from irnuc.model.core.rng import normal_row


@njit(cache=True, error_model="numpy")
def _scale_active(row, resp_row, c0):
    """row[c0 + j] *= resp_row[j]: the defects' responsivity over the active columns."""
    for j in range(resp_row.shape[0]):
        row[c0 + j] *= resp_row[j]


@njit(cache=True, error_model="numpy")
def _row_static(out, k, L, L_row, uniform, q):
    if uniform:
        for j in range(out.shape[0]):
            out[j] = k[j] * L + q[j]
    else:
        for j in range(out.shape[0]):
            out[j] = k[j] * L_row[j] + q[j]


@njit(cache=True, error_model="numpy")
def _row_frames(out, k, L, L_row, uniform, seen, blind, base, net, substrate_shield, lc, ls):
    shield = base * (ls - net * ls)
    for j in range(out.shape[0]):  # the housing term, then the scene
        q = base * ((1.0 - seen[j]) * lc - net * ls)
        out[j] = shield if substrate_shield and blind[j] else q
    _row_static(out, k, L, L_row, uniform, out)


@njit(cache=True, parallel=True, error_model="numpy")
def power(k_scene, L_scene, uniform, q_env, per_frame, seen, blind, base, net,
          substrate_shield, L_cam, L_s, resp, r0, c0, out):
    """Absorbed power (N, rows, cols), W: k L_scene plus the housing term, times the
    defects' responsivity ``resp`` (H, W) over the active area at (r0, c0) (an empty array:
    none).

    k_scene (rows, cols): scene coupling (W per W m^-2 sr^-1); L_scene (N, 1, 1) for a
    uniform scene (``uniform``), else (N, rows, cols), W m^-2 sr^-1. The housing term is
    q_env (rows, cols), W, or with ``per_frame`` the frame's own: eps A pi ((1 - seen)
    L_cam - net L_s) with seen (rows, cols) the scene fraction of the hemisphere, base =
    eps A pi (m^2 sr), net 1 with net radiation (else 0), L_cam and L_s (N,) the housing
    and substrate radiance (W m^-2 sr^-1), and the skimming pixels (``blind``) under a
    ``substrate_shield``: eps A pi (L_s - net L_s).
    """
    n_frames, rows, _ = out.shape
    has_resp = resp.size > 0
    H = resp.shape[0]
    for i in prange(rows):
        ia = i - r0
        for n in range(n_frames):
            L_row = L_scene[n, 0] if uniform else L_scene[n, i]
            if per_frame:
                _row_frames(out[n, i], k_scene[i], L_scene[n, 0, 0], L_row, uniform, seen[i],
                            blind[i], base, net, substrate_shield, L_cam[n], L_s[n])
            else:
                _row_static(out[n, i], k_scene[i], L_scene[n, 0, 0], L_row, uniform,
                            q_env[i])
            if has_resp and 0 <= ia < H:
                _scale_active(out[n, i], resp[ia], c0)


@njit(cache=True, error_model="numpy")
def _row_integrate(out, v_row, c0, ref, ref_row, per_col, gain, v_reset):
    if per_col:
        for j in range(out.shape[0]):
            out[j] = (ref_row[j] - v_row[c0 + j]) * gain + v_reset
    else:
        for j in range(out.shape[0]):
            out[j] = (ref - v_row[c0 + j]) * gain + v_reset


@njit(cache=True, parallel=True, error_model="numpy")
def integrate_frames(v_bolo, r0, c0, v_ref, gain, v_reset, out):
    """Integrator output (N, H, W), V: v_reset + gain (v_ref - v_bolo) over the active
    area starting at (r0, c0) of the full array; v_ref (N, H, 1), (N, 1, W) or (N, 1, 1)
    broadcasts over the rows and columns (:func:`model.readout.integrate`, same bits)."""
    n_frames, rows, _ = out.shape
    per_row = v_ref.shape[1] > 1
    per_col = v_ref.shape[2] > 1
    for i in prange(rows):
        ri = i if per_row else i - i  # one integer type (prange counts unsigned)
        for n in range(n_frames):
            _row_integrate(out[n, i], v_bolo[n, r0 + i], c0, v_ref[n, ri, 0], v_ref[n, ri],
                           per_col, gain, v_reset)


@njit(cache=True)
def frame_statistics(dT, status, r0, r1, c0, c1, codes, top):
    """(min, max, sum, count of dT over rows r0:r1, cols c0:c1 of the pixels whose status
    is not STATUS_INVALID (they hold 0 K, no rise of their own) and finite; codes == 0;
    codes == top) of (N, rows, cols) rises (K) and status, and (N, H, W) codes."""
    lo = math.inf
    hi = -math.inf
    total = 0.0
    count = 0
    for n in range(dT.shape[0]):
        for i in range(r0, r1):
            for j in range(c0, c1):
                x = dT[n, i, j]
                if status[n, i, j] != STATUS_INVALID and math.isfinite(x):
                    lo = min(lo, x)
                    hi = max(hi, x)
                    total += x
                    count += 1
    n_low = 0
    n_high = 0
    flat = codes.reshape(-1)
    for k in range(flat.shape[0]):
        c = flat[k]
        n_low += c == 0
        n_high += c == top
    return lo, hi, total, count, n_low, n_high


@njit(cache=True, error_model="numpy")
def _row_draws(key_w, has_slow, vals, total, octave, key_f, base, x_tab, f_tab, w, new_row):
    """A row's white normals (``w``, of key_w) and, with ``has_slow``, octave ``octave`` of
    its Voss generator drawn anew (of key_f; the running sum ``total`` kept)."""
    normal_row(key_w, base, w, x_tab, f_tab)
    if not has_slow or octave < 0:
        return
    normal_row(key_f, base, new_row, x_tab, f_tab)
    for j in range(new_row.shape[0]):
        total[j] += new_row[j] - vals[octave, j]
        vals[octave, j] = new_row[j]


@njit(cache=True, parallel=True, error_model="numpy")
def bolometer_noise(v, dT, status, T_s, I, t_int, johnson, kf_white, slow_amp, keys_w,
                    keys_f, octave, vals, total, x_tab, f_tab, out):
    """The bolometer's own noise added to its voltage, (N, rows, cols), V: white with
    variance 2 k T R / t_int (Johnson over the bandwidth 1/(2 t_int), ``johnson``) plus
    kf_white v^2 (the 1/f octaves above the frame rate), from the standard normal of
    (keys_w[n], i cols + j); plus slow_amp v (sum of the Voss generator's octaves) /
    sqrt(octaves), the generator ``vals`` (K, rows, cols) with its running sum ``total``
    (rows, cols) updated in place: octave[n] >= 0 is drawn anew from keys_f[n] first.
    T = T_s[n] + dT and R = v / I. Pixels whose solve failed keep their voltage (they read
    the rail)."""
    n_frames, rows, cols = v.shape
    two_k_t = 2.0 * 1.380649e-23 / t_int
    inv_I = 1.0 / I if I > 0.0 else 0.0
    jf = 1.0 if johnson else 0.0
    norm = 1.0 / math.sqrt(vals.shape[0]) if vals.shape[0] > 0 else 0.0
    has_slow = slow_amp > 0.0 and vals.shape[0] > 0
    for i in prange(rows):
        w = np.empty(cols)
        new_row = np.empty(cols)
        base = np.uint64(i) * np.uint64(cols)
        for n in range(n_frames):
            _row_draws(keys_w[n], has_slow, vals[:, i], total[i], octave[n], keys_f[n], base,
                       x_tab, f_tab, w, new_row)
            Ts = T_s[n]
            for j in range(cols):
                vv = v[n, i, j]
                T = max(Ts + dT[n, i, j], 0.0)
                var = kf_white * vv * vv + jf * two_k_t * T * abs(vv) * inv_I
                o = vv + math.sqrt(var) * w[j]
                if has_slow:
                    o += slow_amp * vv * total[i, j] * norm
                out[n, i, j] = o if status[n, i, j] == STATUS_OK else vv


@njit(cache=True, parallel=True, error_model="numpy")
def output_noise(v, sigma, keys, flicker_sigma, octave, keys_f, vals, total, x_tab, f_tab,
                 out):
    """White noise of standard deviation ``sigma`` ((H, W), or (1, 1) for all) from the
    normals of (keys[n], i W + j), plus flicker_sigma times a Voss generator (``vals``,
    ``total`` updated in place as :func:`bolometer_noise`), added to (N, H, W) voltages."""
    n_frames, rows, cols = v.shape
    per_pixel = sigma.shape[0] > 1 or sigma.shape[1] > 1
    norm = 1.0 / math.sqrt(vals.shape[0]) if vals.shape[0] > 0 else 0.0
    has_slow = flicker_sigma > 0.0 and vals.shape[0] > 0
    for i in prange(rows):
        w = np.empty(cols)
        new_row = np.empty(cols)
        base = np.uint64(i) * np.uint64(cols)
        for n in range(n_frames):
            _row_draws(keys[n], has_slow, vals[:, i], total[i], octave[n], keys_f[n], base,
                       x_tab, f_tab, w, new_row)
            for j in range(cols):
                sg = sigma[i, j] if per_pixel else sigma[0, 0]
                o = v[n, i, j] + sg * w[j]
                if has_slow:
                    o += flicker_sigma * total[i, j] * norm
                out[n, i, j] = o
