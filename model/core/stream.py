"""Kernels of the per-frame passes of a drift sequence, one pass over the pixels each.

* :func:`power_frames`: the absorbed power of frames whose housing and substrate
  temperatures change from frame to frame, Q = k L_scene + eps A pi ((1 - seen) L_cam -
  net L_s) (the skimming pixels under a substrate shield: eps A pi (L_s - net L_s)), the
  same operations in the same order as the pipeline's static path, so the same bits;
* :func:`frame_statistics`: the diagnostics of frames (temperature-rise range and sum over
  the active area, codes at either end of the ADC range).
"""

import math

from numba import njit, prange


@njit(cache=True)
def _responsive(q, resp, has_resp, ia, ja, H, W):
    """Power q (W) times the defects' responsivity of active pixel (ia, ja), if any."""
    if has_resp and 0 <= ia < H and 0 <= ja < W:
        return q * resp[ia, ja]
    return q


@njit(cache=True, parallel=True)
def power_frames(k_scene, L_scene, uniform, seen, blind, base, net, substrate_shield, L_cam,
                 L_s, resp, r0, c0, out):
    """Absorbed power (N, rows, cols), W.

    k_scene, seen (rows, cols): scene coupling (W per W m^-2 sr^-1) and scene fraction of
    the hemisphere; blind (rows, cols) bool: skimming pixels; base: eps A pi (m^2 sr); net:
    1 with net radiation, else 0; L_scene: (N, 1, 1) radiance of a uniform scene
    (``uniform``) or (N, rows, cols); L_cam, L_s (N,): housing and substrate radiance,
    W m^-2 sr^-1; resp (H, W): the defects' responsivity factor over the active area at
    (r0, c0), applied after the sum (an empty array: none).
    """
    n_frames, rows, cols = out.shape
    has_resp = resp.size > 0
    H, W = resp.shape
    for i in prange(rows):
        ia = i - r0
        for n in range(n_frames):
            lc = L_cam[n]
            ls = L_s[n]
            shield = base * (ls - net * ls)
            for j in range(cols):
                if substrate_shield and blind[i, j]:
                    q = shield
                else:
                    q = base * ((1.0 - seen[i, j]) * lc - net * ls)
                L = L_scene[n, 0, 0] if uniform else L_scene[n, i, j]
                out[n, i, j] = _responsive(k_scene[i, j] * L + q, resp, has_resp, ia, j - c0,
                                           H, W)


@njit(cache=True)
def frame_statistics(dT, r0, r1, c0, c1, codes, top):
    """(min, max, sum, count of finite dT over rows r0:r1, cols c0:c1; codes == 0; codes ==
    top) of (N, rows, cols) rises (K) and (N, H, W) codes."""
    lo = math.inf
    hi = -math.inf
    total = 0.0
    count = 0
    for n in range(dT.shape[0]):
        for i in range(r0, r1):
            for j in range(c0, c1):
                x = dT[n, i, j]
                if math.isfinite(x):
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


@njit(cache=True, parallel=True)
def integrate_frames(v_bolo, r0, c0, v_ref, gain, v_reset, out):
    """Integrator output (N, H, W), V: v_reset + gain (v_ref - v_bolo) over the active
    area starting at (r0, c0) of the full array; v_ref (N, H, 1), (N, 1, W) or (N, 1, 1)
    broadcasts over the rows and columns (:func:`model.readout.integrate`, same bits)."""
    n_frames, rows, cols = out.shape
    per_row = v_ref.shape[1] > 1
    per_col = v_ref.shape[2] > 1
    for i in prange(rows):
        ri = i if per_row else i - i  # one integer type (prange counts unsigned)
        for n in range(n_frames):
            for j in range(cols):
                cj = j if per_col else j - j
                out[n, i, j] = (v_ref[n, ri, cj] - v_bolo[n, r0 + i, c0 + j]) * gain + v_reset


@njit(cache=True, parallel=True)
def power_static(k_scene, L_scene, uniform, q_env, resp, r0, c0, out):
    """Absorbed power (N, rows, cols), W, with a fixed housing term: k L_scene + q_env,
    times the defects' responsivity ``resp`` (H, W) over the active area at (r0, c0) (an
    empty array: none); the pipeline's numpy expression in one pass, the same bits."""
    n_frames, rows, cols = out.shape
    has_resp = resp.size > 0
    H, W = resp.shape
    for i in prange(rows):
        ia = i - r0
        for n in range(n_frames):
            for j in range(cols):
                L = L_scene[n, 0, 0] if uniform else L_scene[n, i, j]
                out[n, i, j] = _responsive(k_scene[i, j] * L + q_env[i, j], resp, has_resp,
                                           ia, j - c0, H, W)
