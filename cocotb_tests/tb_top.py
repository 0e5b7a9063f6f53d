"""cocotb tests of ``nuc_dpc_top`` (run through ``cocotb_tests/test_nuc_dpc_top.py``).

Every output pixel is compared bit for bit, in order, with ``nuc_fixed.nuc_dpc_top`` by
one :class:`irnuc.cosim.TopScoreboard` per check; the streams ``s_pix``, ``s_coef`` and
``m_pix`` are found by prefix (``tb_lib.top_sources``, ``tb_lib.top_sink``).
"""

from __future__ import annotations

import itertools

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles, RisingEdge

from irnuc.cocotb_tests import stimulus, tb_lib
from irnuc.cocotb_tests.directed import corner_coefficients, dpc_bad_patterns, neighbour_maps
from irnuc.cocotb_tests.streams import coverage_sample, reset, run_streams
from irnuc.cocotb_tests.tb_lib import golden_frame
from irnuc.cosim import coverage
from irnuc.nuc_fixed import nuc_core, pack_words, unpack_words

#: Tests that random configurations (configspace) leave out, with the reason.
RANDOM_CONFIG_SKIP = {"model_frames": "the physics model's frames need a sensor-like format "
                                      "(enough ADC bits and pixels for a calibration)"}

#: Pause patterns of the inputs (idle) and of the output (backpressure), all combinations
#: in ``stream_patterns`` (cocotb_tests/test_nuc_dpc_top.py makes each a pytest parameter).
IDLE = coverage.IDLE_PATTERNS
BACKPRESSURE = coverage.BACKPRESSURE_PATTERNS


async def _setup(dut, salt: int):
    """(configuration, golden configuration, rng) of a test, after clock and reset."""
    env = await tb_lib.setup(dut, salt)
    return env.cfg, env.golden, env.rng


def _clip(cfg, hw: tuple[int, int]) -> tuple[int, int]:
    """(H, W) clipped to the configuration's maximum frame (random configurations have
    maxima down to 1 x 1)."""
    return min(hw[0], cfg.max_height), min(hw[1], cfg.max_width)


def _fits(cfg, shape: tuple[int, ...]) -> bool:
    return shape[0] <= cfg.max_height and shape[1] <= cfg.max_width


def _sizes(cfg) -> list[tuple[int, int]]:
    """(H, W) frame sizes: small, single row/column/pixel and the widest line buffer."""
    return [_clip(cfg, hw) for hw in ((9, 14), (1, 1), (1, 7), (6, 1), (2, cfg.max_width),
                                       (3, 2))]


def _random_frames(rng, cfg, gcfg, n, h, w, bad_fraction=0.05):
    words = tb_lib.random_coefficients(rng, cfg, h, w, bad_fraction)
    out = []
    for _ in range(n):
        raw = rng.integers(0, 1 << cfg.adc_bits, size=(h, w), dtype=np.int64)
        out.append(golden_frame(raw, words, gcfg))
    return out


async def _check(dut, frames, rng, gcfg, **kw):
    """Stream the frames, score them; fail on a mismatch or a framing error. The sink."""
    sink, _ = await tb_lib.run_top_frames(dut, frames, rng, **kw)
    tb_lib.assert_passed(tb_lib.check_frames(frames, sink, gcfg))
    assert int(dut.frame_err_o.value) == 0, "frame_err_o set on a well-formed stream"
    return sink


@cocotb.test()
async def random_frames_full_rate(dut) -> None:
    """Back-to-back random frames at valid=1/ready=1: exact, and no bubble anywhere."""
    cfg, gcfg, rng = await _setup(dut, 0)
    tb_lib.check_top_widths(dut, cfg)
    h, w = min(cfg.max_height, 12), min(cfg.max_width, 20)
    frames = _random_frames(rng, cfg, gcfg, 3, h, w)
    sink = await _check(dut, frames, rng, gcfg)
    n = 3 * h * w
    assert sink.last_cycle - sink.first_cycle == n - 1, (
        f"{n} outputs took {sink.last_cycle - sink.first_cycle + 1} cycles: bubbles")


@cocotb.test()
async def wide_frames_full_rate(dut) -> None:
    """Back-to-back same-size frames at full rate, for a width with each bit from 2 up,
    even and odd pixel counts: no bubble. A frame's tail overlaps the next frame only
    when the DPC controller sees the next size equal to the latched one; a wrong "same"
    (a bit of the latched width disturbed, on some cycles only) flushes the tail with
    phantom pixels first: the same words, a few cycles late."""
    cfg, gcfg, rng = await _setup(dut, 13)
    base = {min(cfg.max_width, (1 << b) + 2 + int(rng.integers(0, 1 << b) & ~3))
            for b in range(2, cfg.max_width.bit_length())}
    for w in sorted(base | {min(cfg.max_width, x + 1) for x in base}):
        h = min(cfg.max_height, 3)
        frames = _random_frames(rng, cfg, gcfg, 4, h, w)
        sink = await _check(dut, frames, rng, gcfg)
        n = 4 * h * w
        assert sink.last_cycle - sink.first_cycle == n - 1, (
            f"4 frames of {h}x{w}: {n} outputs took "
            f"{sink.last_cycle - sink.first_cycle + 1} cycles: bubbles")


@cocotb.test()
async def random_gaps_backpressure(dut) -> None:
    """Random idle cycles on both inputs and random output backpressure, many sizes."""
    cfg, gcfg, rng = await _setup(dut, 1)
    for i, (h, w) in enumerate(_sizes(cfg)):
        frames = _random_frames(rng, cfg, gcfg, 2, h, w, bad_fraction=0.2)
        idle = (0.3, 0.1, 0.5)[i % 3]
        await _check(dut, frames, rng, gcfg, idle_pix=idle, idle_coef=(0.2, 0.4, 0.0)[i % 3],
                     backpressure=(0.3, 0.5, 0.1)[i % 3])


@cocotb.test()
async def corner_codes(dut) -> None:
    """Largest code x largest gain, saturation at both ends, rounding ties."""
    cfg, gcfg, rng = await _setup(dut, 2)
    x, g, o, kinds = corner_coefficients(cfg, rng)
    w = min(cfg.max_width, 16)
    n = len(x)
    h = min(-(-n // w), cfg.max_height)
    # A small maximum frame: the corner set goes over several frames of h x w.
    nf = -(-n // (h * w))
    pad = nf * h * w - n
    x = np.concatenate([x, np.zeros(pad, np.int64)]).reshape(nf, h, w)
    g = np.concatenate([g, np.zeros(pad, np.int64)]).reshape(nf, h, w)
    o = np.concatenate([o, np.zeros(pad, np.int64)]).reshape(nf, h, w)
    frames = [golden_frame(x[i], pack_words(g[i], o[i], np.zeros((h, w), bool), cfg), gcfg)
              for i in range(nf)]
    await _check(dut, frames, rng, gcfg, idle_pix=0.1, backpressure=0.1)
    # The set really covers what it claims (golden intermediates).
    it = nuc_core(x, g, o, gcfg, intermediates=True)
    kinds_present = set(kinds)
    ymax = (1 << cfg.out_bits) - 1
    if "sat_low" in kinds_present:
        assert (it.r < 0).any()
    if "sat_high" in kinds_present:
        assert (it.r > ymax).any()
    if cfg.frac_bits > 0:
        f = cfg.frac_bits
        ties = (it.s & ((1 << f) - 1)) == (1 << (f - 1))
        assert ties.sum() >= 8, "no rounding ties in the corner set"
        ints = it.s[ties] >> f
        assert (ints % 2 == 0).any() and (ints % 2 == 1).any(), "ties lack both parities"


@cocotb.test()
async def dpc_patterns(dut) -> None:
    """Flagged pixels at borders, corners, in clusters, whole rows/columns, all bad."""
    cfg, gcfg, rng = await _setup(dut, 3)
    h, w = min(cfg.max_height, 10), min(cfg.max_width, 12)
    for bad in dpc_bad_patterns(h, w) + neighbour_maps(h, w):
        if not _fits(cfg, bad.shape):  # a maximum below 3 x 3: no such map
            continue
        hh, ww = bad.shape
        # Gain near one, small offsets: outputs spread over the range, not saturated.
        gain = 1.0 + 0.1 * rng.standard_normal((hh, ww))
        offset = rng.normal(0.0, 4.0, (hh, ww))
        words = tb_lib.unity_coefficients(cfg, gain * 2.0 ** (cfg.out_bits - cfg.adc_bits),
                                          offset, bad)
        raw = rng.integers(0, 1 << cfg.adc_bits, size=(hh, ww), dtype=np.int64)
        await _check(dut, [golden_frame(raw, words, gcfg)], rng, gcfg, idle_pix=0.2,
                     backpressure=0.2)


@cocotb.test()
async def reset_mid_frame(dut) -> None:
    """Reset in the middle of a frame, then a clean frame is exact."""
    cfg, gcfg, rng = await _setup(dut, 4)
    h, w = min(cfg.max_height, 8), min(cfg.max_width, 10)
    frames = _random_frames(rng, cfg, gcfg, 1, h, w)
    pix, coef = tb_lib.top_sources(dut, frames, 0.1, 0.1, rng)
    await run_streams(dut, [pix, coef], tb_lib.top_sink(dut, 0.2, rng, expect=(h * w) // 3))
    # Abort: reset while pixels are in flight in both cores.
    await reset(dut, 2)
    assert int(dut.m_pix_valid_o.value) == 0, "output valid right after reset"
    await ClockCycles(dut.clk_i, 3)
    frames = _random_frames(rng, cfg, gcfg, 2, h, w)
    await _check(dut, frames, rng, gcfg, idle_pix=0.1, backpressure=0.2)


@cocotb.test()
async def checker_detects_mismatch(dut) -> None:
    """The checker fails when the golden model differs (another rounding mode)."""
    cfg, _, rng = await _setup(dut, 5)
    if cfg.frac_bits > 0:
        other = cfg.replace(rounding={"truncate": "half_up"}.get(cfg.rounding, "truncate"))
    else:
        other = cfg.replace(overflow={"saturate": "wrap"}.get(cfg.overflow, "saturate"))
    h, w = min(cfg.max_height, 8), min(cfg.max_width, 16)
    # Enough pixels (several frames of a small maximum) for the other model to differ.
    frames = [f for _ in range(max(1, 128 // (h * w)))
              for f in _random_frames(rng, cfg, cfg, 1, h, w)]
    wrong = [golden_frame(f.raw, f.words, other) for f in frames]
    assert any((a.expected != b.expected).any() for a, b in zip(frames, wrong, strict=True)), \
        "the deliberately different golden model predicts the same frame"
    sink, _ = await tb_lib.run_top_frames(dut, frames, rng)
    mism = tb_lib.check_frames(wrong, sink, other)
    assert not mism.passed, "checker reported no mismatch against a different golden configuration"
    text = mism.lines[0]
    for key in ("frame", "x", "y", "raw", "gain", "offset", "expected", "got", " p ", " s ",
                " r "):
        assert key in text, f"mismatch report lacks {key!r}: {text}"
    # ... and the same outputs pass against the right configuration.
    assert tb_lib.check_frames(frames, sink, cfg).passed


@cocotb.test()
async def framing_error_flag(dut) -> None:
    """A missing end-of-line marker sets the sticky frame_err_o; reset clears it."""
    cfg, _, rng = await _setup(dut, 6)
    h, w = min(cfg.max_height, 4), min(cfg.max_width, 5)
    frames = _random_frames(rng, cfg, cfg, 1, h, w)
    pix, coef = tb_lib.top_sources(dut, frames)
    pix.toggle(w - 1, "eol")  # drop eol of row 0
    await run_streams(dut, [pix, coef], tb_lib.top_sink(dut, expect=h * w))
    assert int(dut.frame_err_o.value) == 1
    await reset(dut)
    assert int(dut.frame_err_o.value) == 0
    await RisingEdge(dut.clk_i)


@cocotb.test()
async def model_frames(dut) -> None:
    """Frames of the physics model (with defects), calibrated by nuc_fixed."""
    from irnuc.cocotb_tests.model_frames import calibrated_model_frames

    frames_raw, words = calibrated_model_frames(tb_lib.config_from_env(),
                                                seed=tb_lib.seed_from_env())
    cfg, gcfg, rng = await _setup(dut, 7)
    frames = [golden_frame(f, words, gcfg) for f in frames_raw]
    _, _, bad = unpack_words(words, cfg)
    assert bad.any(), "the model frames carry no defect"
    await _check(dut, frames, rng, gcfg, idle_pix=0.05, idle_coef=0.05, backpressure=0.05)


@cocotb.test()
async def stream_patterns(dut) -> None:
    """Every idle pattern x every backpressure pattern: exact; at full-rate input no cycle
    is lost inside the core (outputs + sink stalls = output cycles, across frames)."""
    cfg, gcfg, rng = await _setup(dut, 8)
    h, w = min(cfg.max_height, 5), min(cfg.max_width, 9)
    failures = []
    for idle in IDLE:
        for bp in BACKPRESSURE:
            frames = _random_frames(rng, cfg, gcfg, 2, h, w, bad_fraction=0.1)
            sink, _ = await tb_lib.run_top_frames(dut, frames, rng, idle_pix=idle,
                                                  idle_coef=idle, backpressure=bp)
            res = tb_lib.check_frames(frames, sink, gcfg)
            msg = "" if res.passed else res.report(3)
            if not msg and idle == "none":
                try:
                    sink.check_throughput()
                    coverage_sample("stream.back_to_back", "frames")
                except AssertionError as exc:
                    msg = str(exc)
            tb_lib.record(pattern=[idle, bp], passed=not msg, message=msg,
                          stalls=sink.stalls, outputs=len(sink.got))
            if msg:
                failures.append(f"idle {idle} / backpressure {bp}: {msg}")
    assert int(dut.frame_err_o.value) == 0, "frame_err_o set on a well-formed stream"
    assert not failures, "\n".join(failures)


@cocotb.test()
async def frame_size_changes(dut) -> None:
    """Back-to-back frames whose size changes in width only, height only, both, or not,
    and the extreme sizes (1x1, 1xN, Nx1, width = MaxWidth, height = MaxHeight), at full
    rate and under backpressure: exact, frame_err_o stays 0.

    A new size travels with its frame's first pixel. nuc_dpc_top samples the size in
    dpc_core, so the previous frame's first pixel must have reached dpc_core before the
    size changes (docs/rtl.md, frame size rule): frames changing size back to back here
    have at least 24 pixels; the small extreme frames each follow an idle input.
    """
    cfg, gcfg, rng = await _setup(dut, 9)
    h, w = min(cfg.max_height, 4), min(cfg.max_width, 6)
    back_to_back = [_clip(cfg, hw) for hw in ((h, w), (h, w + 1), (h + 1, w + 1),
                                              (h + 2, w + 1), (h, w), (h, w))]
    alone = [_clip(cfg, hw) for hw in ((1, 1), (1, 1), (1, 5), (5, 1), (2, cfg.max_width),
                                       (cfg.max_height, 1), (2, 2), (3, 3), (4, 4), (3, 2))]
    if min(a * b for a, b in back_to_back) < 24:
        # A small maximum: these frames may not change size back to back without the
        # size gate (docs/rtl.md, frame size rule; size_class_changes does that).
        alone, back_to_back = back_to_back + alone, back_to_back[:1]
    for bp in ("none", "random"):
        words = {hw: tb_lib.random_coefficients(rng, cfg, *hw, 0.2)
                 for hw in set(back_to_back + alone)}

        def frame(hw, words=words):
            return golden_frame(rng.integers(0, 1 << cfg.adc_bits, size=hw, dtype=np.int64),
                                words[hw], gcfg)

        await _check(dut, [frame(hw) for hw in back_to_back], rng, gcfg, backpressure=bp)
        prev = back_to_back[-1]
        for hw in alone:
            await _check(dut, [frame(hw)], rng, gcfg, backpressure=bp)
            # A _check of its own starts after the previous frame left the core: the
            # input was idle for at least the pipeline latency (a gap > 0).
            coverage.model("nuc_dpc_top", cfg).sample_frames([prev, hw], [1])
            prev = hw


async def _inject(dut, cfg, rng, cause: str) -> int:
    """One marker cause of frame_err_o alone (or none: ``control``), from a reset; returns
    frame_err_o after the frame."""
    await reset(dut)
    h, w = min(cfg.max_height, 3), min(cfg.max_width, 4)
    frames = _random_frames(rng, cfg, cfg, 1, h, w)
    pix, coef = tb_lib.top_sources(dut, frames)
    row = {"sof_missing": 0, "sof_unexpected": min(w + 1, h * w - 1), "eol_missing": w - 1,
           "eol_unexpected": 1 if w > 2 else 0}.get(cause)
    if row is not None:
        pix.toggle(row, cause[:3])
    await run_streams(dut, [pix, coef], tb_lib.top_sink(dut, expect=h * w))
    await ClockCycles(dut.clk_i, 2)
    return int(dut.frame_err_o.value)


SIZE_CAUSES = ("width_zero", "height_zero", "width_over_max", "height_over_max")


async def _inject_size(dut, cfg, rng, cause: str | None) -> int:
    """An illegal frame size (``cause``) seen by dpc_ctrl's check alone, or none (None: the
    same stimulus with the legal size); returns frame_err_o.

    From a reset, with the output's ready low: two 1 x 1 frames, whose two outputs fill
    dpc_core's output register, so its enable drops and dpc_ctrl stops in Idle; then frame
    B's first pixel (1 x 1, legal) passes both ``a_frame_size`` points (top and dpc_core
    input) and waits in dpc_core's input register; the size is made illegal while it
    waits, then ready rises. B's pixel carries the markers the illegal size asks for (eol
    low for a width that is not 1), so no marker check fires with it. Checked: frame_err_o
    is 0 until then, the two outputs are exact, and after them the outputs are those of a
    legal B (its output) or, with an illegal size, none (the frame never completes).
    Works on every maximum frame, 1 x 1 included.
    """
    await reset(dut)
    frames = _random_frames(rng, cfg, cfg, 3, 1, 1)
    stages = coverage.pipeline_stages("nuc_dpc_top", cfg)[:-1]
    d = stages.index("dpc_window")
    wbits, hbits = len(dut.frame_width_i), len(dut.frame_height_i)
    bad = {None: (None, None), "width_zero": (0, None), "height_zero": (None, 0),
           "width_over_max": (min(cfg.max_width + 1, (1 << wbits) - 1), None),
           "height_over_max": (None, min(cfg.max_height + 1, (1 << hbits) - 1))}[cause]
    dut.m_pix_ready_i.value = 0
    pix, coef = tb_lib.top_sources(dut, frames[:2])
    await run_streams(dut, [pix, coef], [],
                      stop=lambda c: pix.done and c >= pix.taken[-1] + len(stages) + 8)
    assert int(dut.m_pix_valid_o.value) == 1, "the first two outputs did not arrive"
    pix, coef = tb_lib.top_sources(dut, frames[2:])
    if bad[0] is not None:
        pix.toggle(0, "eol")  # an illegal width has no last column at column 0
    await run_streams(dut, [pix, coef], [], stop=lambda c: pix.done and c >= pix.taken[-1] + d + 2)
    assert int(dut.frame_err_o.value) == 0, f"{cause}: frame_err_o set before the size changed"
    if bad[0] is not None:
        dut.frame_width_i.value = bad[0]
    if bad[1] is not None:
        dut.frame_height_i.value = bad[1]
    await ClockCycles(dut.clk_i, 2)
    n = 2 if cause else 3
    sink = tb_lib.top_sink(dut, expect=n)
    await run_streams(dut, [], sink)
    dut.m_pix_ready_i.value = 1
    await ClockCycles(dut.clk_i, len(stages) + 8)
    tb_lib.assert_passed(tb_lib.check_frames(frames[:n], sink, cfg))
    assert int(dut.m_pix_valid_o.value) == 0, f"{cause}: an output after the expected {n}"
    return int(dut.frame_err_o.value)


@cocotb.test()
async def frame_error_causes(dut) -> None:
    """Every cause of frame_err_o alone sets it (sof missing or unexpected, eol missing or
    unexpected, width or height 0 or above the maximum); the same stimulus without the
    cause does not; reset clears it."""
    cfg, _, rng = await _setup(dut, 10)
    assert await _inject(dut, cfg, rng, "control") == 0, "frame_err_o set by a clean frame"
    wrong = []
    assert await _inject_size(dut, cfg, rng, None) == 0, (
        "frame_err_o set by the size-cause stimulus with a legal size")
    # Causes a small maximum cannot produce (coverage.small_maximum_removals says why).
    cannot = set(coverage.small_maximum_removals(cfg)["frame.error"])
    for cause in coverage.FRAME_ERRORS:
        if cause in cannot:
            continue
        if cause == "width_over_max" and cfg.max_width >= (1 << len(dut.frame_width_i)) - 1:
            continue
        if cause == "height_over_max" and cfg.max_height >= (1 << len(dut.frame_height_i)) - 1:
            continue
        if cause in SIZE_CAUSES:
            err = await _inject_size(dut, cfg, rng, cause)
        else:
            err = await _inject(dut, cfg, rng, cause)
        if err != 1:
            wrong.append(cause)
        else:
            coverage_sample("frame.error", cause)
    await reset(dut)
    assert int(dut.frame_err_o.value) == 0, "reset did not clear frame_err_o"
    coverage.export()
    assert not wrong, f"frame_err_o stayed 0 for: {', '.join(wrong)}"


def _stage_at(cfg, w: int, k: int) -> str:
    """The stage of the leading item (past the window: of the leading output) k cycles
    after a frame's first pixel was taken at full rate (coverage.pipeline_stages; the
    window holds the leading item for W + 1 cycles)."""
    stages = coverage.pipeline_stages("nuc_dpc_top", cfg)[:-1]
    iw = stages.index("dpc_window")
    if k < iw:
        return stages[k]
    if k <= iw + w + 1:
        return "dpc_window"
    return stages[min(k - w - 1, len(stages) - 1)]


@cocotb.test()
async def reset_each_stage(dut) -> None:
    """Reset while the leading item is in each pipeline stage, and during the DPC's flush;
    each time the next frame is exact. The stage model is checked first: the first output
    leaves len(stages) + W + 1 cycles after the first pixel was taken (docs/rtl.md)."""
    cfg, gcfg, rng = await _setup(dut, 11)
    h, w = min(cfg.max_height, 3), min(cfg.max_width, 4)
    stages = coverage.pipeline_stages("nuc_dpc_top", cfg)[:-1]
    frames = _random_frames(rng, cfg, gcfg, 1, h, w)
    pix, coef = tb_lib.top_sources(dut, frames)
    sink = tb_lib.top_sink(dut, expect=h * w)
    await run_streams(dut, [pix, coef], sink)
    latency = sink.first_cycle - pix.taken[0]
    assert latency == len(stages) + w + 1, (
        f"first output {latency} cycles after the first pixel; the stage model says "
        f"{len(stages) + w + 1}")
    for k in range(latency + 1):
        await reset(dut)
        frames = _random_frames(rng, cfg, gcfg, 1, h, w)
        pix, coef = tb_lib.top_sources(dut, frames)
        await run_streams(dut, [pix, coef], tb_lib.top_sink(dut),
                          stop=lambda c, p=pix, k=k: bool(p.taken) and c >= p.taken[0] + k)
        await reset(dut)
        coverage_sample("reset.stage", _stage_at(cfg, w, k))
        assert int(dut.m_pix_valid_o.value) == 0
        await _check(dut, _random_frames(rng, cfg, gcfg, 1, h, w), rng, gcfg)
    # During the flush: a frame, no next pixel, reset while the phantoms push it out.
    wf = min(cfg.max_width, 12)
    nuc = len(coverage.pipeline_stages("nuc_core", cfg))
    for k in range(1, 4):
        await reset(dut)
        frames = _random_frames(rng, cfg, gcfg, 1, 1, wf)
        pix, coef = tb_lib.top_sources(dut, frames)
        await run_streams(
            dut, [pix, coef], tb_lib.top_sink(dut),
            stop=lambda c, p=pix, k=k: p.done and c >= p.taken[-1] + nuc + 2
            + k * max(1, wf // 4))
        await reset(dut)
        coverage_sample("reset.stage", "flush")
        await _check(dut, _random_frames(rng, cfg, gcfg, 1, h, w), rng, gcfg)
    coverage.export()



async def _gated_run(dut, cfg, frames, stop=None):
    """Stream frames back to back at full rate, each frame of a new size offered as soon
    as the frame size rule allows (``stimulus.size_gate``, schedule mode). Returns the
    pixel source, the sink, the gate and the cycle of every output."""
    sizes = [f.raw.shape for f in frames]
    pix, coef = tb_lib.top_sources(dut, frames)
    gate = stimulus.size_gate(cfg, sizes, "schedule")
    gate.source = pix
    pix.pause = gate
    sink = tb_lib.top_sink(dut, expect=None if stop else sum(f.raw.size for f in frames))
    out_cycles: list[int] = []

    def step(c: int) -> bool:
        gate.tick(c)
        out_cycles.extend([c] * (len(sink.got) - len(out_cycles)))
        return bool(stop and stop(c, pix))

    await run_streams(dut, [pix, coef], sink, stop=step)
    return pix, sink, gate, out_cycles


@cocotb.test()
async def size_class_changes(dut) -> None:
    """Frames changing size back to back across every width class and every height class
    (1, 2, 3, small, max), each new size offered as soon as the frame size rule allows,
    so the previous frame is still in the pipeline: exact, no cycle lost (every output at
    the cycle the schedule model predicts), frame_err_o stays 0."""
    cfg, gcfg, rng = await _setup(dut, 12)
    sizes = stimulus.size_walk(cfg, rng)
    words = {hw: tb_lib.random_coefficients(rng, cfg, *hw, 0.2) for hw in set(sizes)}
    frames = [golden_frame(rng.integers(0, 1 << cfg.adc_bits, size=hw, dtype=np.int64),
                           words[hw], gcfg) for hw in sizes]
    pix, sink, gate, out_cycles = await _gated_run(dut, cfg, frames)
    tb_lib.assert_passed(tb_lib.check_frames(frames, sink, gcfg))
    assert int(dut.frame_err_o.value) == 0, "frame_err_o set on a well-formed stream"
    gate.schedule.update(pix.taken)
    gate.schedule.finish()
    predicted = gate.schedule.output_cycles()
    assert predicted == out_cycles, (
        "outputs left at other cycles than the schedule predicts; first difference at "
        f"output {next(i for i, (a, b) in enumerate(zip(predicted, out_cycles, strict=True)) if a != b)}"
        if len(predicted) == len(out_cycles) else
        f"{len(out_cycles)} outputs, the schedule predicts {len(predicted)}")
    # A frame of a new size started while the previous frame was in the pipeline when its
    # first pixel was taken before the previous frame's last output left.
    ends = np.cumsum([h * w for h, w in sizes])
    full = [pix.taken[int(e)] <= out_cycles[int(e) - 1] for e in ends[:-1]]
    if coverage.enabled():
        coverage.model("nuc_dpc_top", cfg).sample_size_changes(sizes, full)
        coverage.export()
    changed = [a != b for a, b in itertools.pairwise(sizes)]
    late = [i for i, (c, f) in enumerate(zip(changed, full, strict=True)) if c and not f]
    assert not late, f"size changes after the pipeline drained at frames {late[:10]}"


@cocotb.test()
async def reset_window(dut) -> None:
    """Reset at every cycle of a window from two cycles before a frame's last pixel until
    the next frame's (another size, back to back) first output can leave: through the
    frame's end, the DPC's flush and the next frame's start. After each, the output is
    idle and a frame of each size is exact."""
    cfg, gcfg, rng = await _setup(dut, 13)
    (ha, wa), (hb, wb), offsets = coverage.reset_window(cfg)
    last = ha * wa - 1
    for k in offsets:
        await reset(dut)
        frames = (_random_frames(rng, cfg, gcfg, 1, ha, wa)
                  + _random_frames(rng, cfg, gcfg, 1, hb, wb))

        def stop(c, pix, k=k):
            # A is taken at full rate from its first pixel on: its last pixel at
            # taken[0] + last.
            return bool(pix.taken) and c >= pix.taken[0] + last + k

        await _gated_run(dut, cfg, frames, stop=stop)
        await reset(dut)
        assert int(dut.m_pix_valid_o.value) == 0, f"output valid after a reset at {k}"
        coverage_sample("reset.window", k)
        await _check(dut, _random_frames(rng, cfg, gcfg, 1, hb, wb), rng, gcfg)
        await _check(dut, _random_frames(rng, cfg, gcfg, 1, ha, wa), rng, gcfg)
    coverage.export()


@cocotb.test()
async def dpc_arithmetic(dut) -> None:
    """Bad pixels whose good neighbours are drawn to hit every good-neighbour count x
    residue of their sum modulo the count x range of their mean (low, middle, near full
    scale), through the NUC (inputs found for the chosen NUC outputs): exact."""
    cfg, gcfg, rng = await _setup(dut, 14)
    bins = coverage.dpc_arith_bins(cfg, "nuc_dpc_top")[0]
    nb = stimulus.dpc_neighbourhoods(cfg, rng, bins, coverage.nuc_output_intervals(cfg),
                                     preimage=lambda v: stimulus.nuc_preimage(cfg, v))
    if not bins:
        # A 1 x 1 maximum: no pixel has a neighbour; bad pixels keep their NUC output.
        assert coverage.max_neighbours(cfg.max_width, cfg.max_height) == 0
        frames = [f for _ in range(32) for f in _random_frames(
            rng, cfg, gcfg, 1, cfg.max_height, cfg.max_width, bad_fraction=0.5)]
        await _check(dut, frames, rng, gcfg)
        return
    assert nb.raw, "no DPC neighbourhood frame was made"
    for i, (raw, words) in enumerate(zip(nb.raw, nb.words, strict=True)):
        frame = golden_frame(raw, words, gcfg)
        await _check(dut, [frame], rng, gcfg, idle_pix=(0.0, 0.2)[i % 2],
                     backpressure=(0.0, 0.3)[i % 2])
        if coverage.enabled():
            g, o, bad = unpack_words(words, cfg)
            y = nuc_core(raw, g, o, cfg)  # the DPC's inputs, by the golden model
            coverage.model("nuc_dpc_top", cfg).sample_dpc_arith(y, bad)
    coverage.export()
    tb_lib.record(dpc_arith_missing=[list(b) for b in nb.missing])
