"""The golden model of ``irnuc_axis_top``'s framing (``irnuc.nuc_fixed.axis``) on small
hand-made streams whose frames and counts are written out here by hand (the rules of
docs/integration.md, "Frames and markers"). The RTL is checked against the same model in
``cocotb_tests/tb_axis.py``."""

from __future__ import annotations

import numpy as np
import pytest

from irnuc.nuc_fixed import load_pipeline
from irnuc.nuc_fixed.axis import FrameSettings, axis_framer, axis_top, neutral_gain
from irnuc.nuc_fixed.memimage import pack_words, unpack_words
from irnuc.nuc_fixed.top import nuc_dpc_top

CFG = load_pipeline("minimal")
S23 = FrameSettings(width=3, height=2)  # 2 lines of 3 pixels


def _words(n: int, last_at: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    """n distinct legal words (gain k + 1, offset 0, good), tlast at the given indices."""
    w = pack_words(np.arange(1, n + 1), np.zeros(n, int), np.zeros(n, bool), CFG)
    last = np.zeros(n, bool)
    last[list(last_at)] = True
    return w, last


def _run(data, sof, eol, words, settings=(S23,)):
    return axis_framer(data, sof, eol, *words, list(settings), CFG)


def test_well_formed_frame() -> None:
    fr = _run([1, 2, 3, 4, 5, 6], [1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 1], _words(6, (5,)))
    assert len(fr.frames) == 1 and not fr.open_frame
    assert fr.frames[0].raw.tolist() == [[1, 2, 3], [4, 5, 6]]
    g, _, _ = unpack_words(fr.frames[0].words, CFG)
    assert g.tolist() == [[1, 2, 3], [4, 5, 6]]
    assert fr.counts == {"sof_early": 0, "sof_late": 0, "eol_early": 0, "eol_late": 0,
                         "coef_early": 0, "coef_late": 0, "frames_in": 1, "beats": 6,
                         "dropped": 0, "padded": 0}


def test_sof_late_drops_beats_before_the_start_once_per_run() -> None:
    fr = _run([9, 9, 1, 2, 3, 4, 5, 6], [0, 0, 1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 1, 0, 0, 1],
              _words(6, (5,)))
    assert fr.frames[0].raw.tolist() == [[1, 2, 3], [4, 5, 6]]
    assert (fr.counts["sof_late"], fr.counts["dropped"], fr.counts["beats"]) == (1, 2, 8)


def test_eol_early_pads_the_line() -> None:
    # Line 0 ends after 2 pixels: one filler (raw 0, the next word) completes it.
    fr = _run([1, 2, 4, 5, 6], [1, 0, 0, 0, 0], [0, 1, 0, 0, 1], _words(6, (5,)))
    assert fr.frames[0].raw.tolist() == [[1, 2, 0], [4, 5, 6]]
    assert fr.frames[0].filler.tolist() == [[False, False, True], [False] * 3]
    assert (fr.counts["eol_early"], fr.counts["padded"], fr.counts["beats"]) == (1, 1, 5)


def test_eol_late_drops_up_to_the_next_tlast() -> None:
    # Line 0 runs 2 beats long (7, 8): they are dropped, line 1 is whole.
    fr = _run([1, 2, 3, 7, 8, 4, 5, 6], [1, 0, 0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 1, 0, 0, 1],
              _words(6, (5,)))
    assert fr.frames[0].raw.tolist() == [[1, 2, 3], [4, 5, 6]]
    assert (fr.counts["eol_late"], fr.counts["dropped"], fr.counts["padded"]) == (1, 2, 0)


def test_sof_early_completes_the_frame_then_opens_the_next() -> None:
    # Frame 0 stops after 4 pixels; 2 fillers, then frame 1 is whole.
    data = [1, 2, 3, 4, 11, 12, 13, 14, 15, 16]
    sof = [1, 0, 0, 0, 1, 0, 0, 0, 0, 0]
    eol = [0, 0, 1, 0, 0, 0, 1, 0, 0, 1]
    fr = _run(data, sof, eol, _words(12, (5, 11)))
    assert [f.raw.tolist() for f in fr.frames] == [[[1, 2, 3], [4, 0, 0]],
                                                   [[11, 12, 13], [14, 15, 16]]]
    assert (fr.counts["sof_early"], fr.counts["padded"], fr.counts["frames_in"]) == (1, 2, 2)


def test_coef_early_gives_the_rest_of_the_frame_the_neutral_word() -> None:
    words = _words(6, (3, 5))  # tlast on word 3: pixels 4 and 5 get the neutral word
    fr = _run([1, 2, 3, 4, 5, 6], [1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 1], words)
    g, o, b = unpack_words(fr.frames[0].words, CFG)
    assert g.ravel().tolist() == [1, 2, 3, 4, neutral_gain(CFG), neutral_gain(CFG)]
    assert not o[1, 1:].any() and not b.any()
    assert fr.counts["coef_early"] == 1 and fr.words_taken == 4
    assert neutral_gain(CFG) == 1 << CFG.gain_frac_bits  # 1.0 in U1.3


def test_coef_late_drops_words_up_to_the_next_tlast() -> None:
    words = _words(9, (8,))  # frame 0's image runs 3 words long
    fr = _run([1, 2, 3, 4, 5, 6], [1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 1], words)
    assert unpack_words(fr.frames[0].words, CFG)[0].ravel().tolist() == [1, 2, 3, 4, 5, 6]
    assert fr.counts["coef_late"] == 1 and fr.words_taken == 9


def test_enables_and_the_core() -> None:
    words = pack_words(np.full(6, 5), np.full(6, 3), np.array([0, 0, 0, 0, 1, 0], bool), CFG)
    last = np.arange(6) == 5
    stream = ([10, 20, 30, 40, 50, 60], [1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 1])
    off = FrameSettings(3, 2, nuc_en=False, dpc_en=False)
    fr = axis_framer(*stream, words, last, [off], CFG)
    g, o, b = unpack_words(fr.frames[0].words, CFG)
    assert (g == neutral_gain(CFG)).all() and not o.any() and not b.any()
    out = axis_top(*stream, words, last, [S23], CFG)
    want = nuc_dpc_top(np.array([[10, 20, 30], [40, 50, 60]]), words.reshape(2, 3), CFG)
    assert out.data.tolist() == want.ravel().tolist()
    assert out.sof.tolist() == [1, 0, 0, 0, 0, 0] and out.eol.tolist() == [0, 0, 1, 0, 0, 1]


def test_words_running_out_is_an_error() -> None:
    with pytest.raises(ValueError, match="ran out"):
        _run([1, 2, 3, 4, 5, 6], [1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 1], _words(4, ()))


# ---- the methods around method_dpc_top -------------------------------------------------------

def test_neutral_words_of_the_methods_by_hand() -> None:
    """The neutral word, bad mask and neutral frame word of each wrapped method, written
    out from the memory layouts by hand (docs/integration.md "Methods")."""
    from irnuc.nuc_fixed.axis import bad_mask, neutral_frame, neutral_word

    one = 1 << 14  # unity gain of U2.14
    cases = {  # name: (neutral word, bad mask, neutral frame)
        "typical14": (one, 1 << 32, 0),  # gain[15:0] offset[31:16] bad[32]
        "onepoint14": (0, 1 << 16, one),  # offset[15:0] bad[16]; the gain is the frame's
        "piecewise14": (one | one << 16, 1 << 48, 0),  # gain_lo, gain_hi, knee, bad[48]
        "quadratic14": (one, 1 << 32, 0),  # coeffs | quad[48:33] = 0
        "tcgain14": (one, 1 << 32, 0),  # coeffs | tc | tg = 0
        # table j: gain[15:0] offset[31:16] bad[32] | table j + 1 the same from bit 33;
        # the weight 0 (table j: its word is neutral too)
        "table14": (one | one << 33, 1 << 32 | 1 << 65, 0),
    }
    for name, want in cases.items():
        cfg = load_pipeline(name)
        assert (neutral_word(cfg), bad_mask(cfg), neutral_frame(cfg)) == want, name


@pytest.mark.parametrize("name", ["onepoint14", "piecewise14", "quadratic14", "tcgain14",
                                  "table14"])
def test_method_words_read_back_as_the_calibration(name: str) -> None:
    """A frame of the method's words (irnuc.cosim.stream.frame_drive: the packing the RTL
    tests drive) and frame word is read back as the same calibration and reading, and the
    wrapper's model corrects it as nuc_fixed.method_top does."""
    from irnuc.cocotb_tests.method_stim import random_coefficients, random_raw, random_reading
    from irnuc.cosim.stream import frame_drive
    from irnuc.nuc_fixed.axis import coef_beats, frame_word, video_beats
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    cfg = load_pipeline(name)
    rng = np.random.default_rng(5)
    c = random_coefficients(cfg, 3, 5, rng, bad_fraction=0.3)
    reading = random_reading(cfg, c, rng)
    raw = random_raw(cfg, 3, 5, rng)
    drive = frame_drive(c, reading)
    regs = {**c.registers, **({"reading": reading} if reading is not None else {})}
    settings = FrameSettings(5, 3, frame_word=frame_word(cfg, regs))
    assert settings.frame_word == drive.frame_word
    if drive.interp is not None:  # table_interp: the DMA's pair image is the stream
        from irnuc.nuc_fixed.axis import table_pair_words

        assert table_pair_words(c, drive.interp.j).tolist() == drive.words.tolist()
    out = axis_top(*video_beats([raw]), *coef_beats([drive.words]), [settings], cfg)
    want = method_top(raw[None], c, FrameInputs(
        reading=None if reading is None else np.array([reading]))).y[0]
    assert out.data.tolist() == want.ravel().tolist()
    # NUC off: one_point keeps no gain of its own (the frame's is 1.0), y = x before DPC
    # on good pixels of a frame without bad flags.
    off = FrameSettings(5, 3, nuc_en=False, dpc_en=False, frame_word=settings.frame_word)
    out = axis_top(*video_beats([raw]), *coef_beats([drive.words]), [off], cfg)
    assert out.data.tolist() == np.clip(raw, 0, (1 << cfg.out_bits) - 1).ravel().tolist()


def test_the_configurations_the_wrapper_is_built_around() -> None:
    """``irnuc synth --top irnuc_axis_top`` takes the named configurations of the wrapped
    base methods and of the ffc and blind_drift compositions and no other (listed by hand),
    with the method's parameters (``Ffc`` = 1 and method_ffc_top's; ``Drift`` = 1 and
    method_drift_top's)."""
    from irnuc.cosim.sources import top_parameters
    from irnuc.cosim.synth import tops_for
    from irnuc.nuc_fixed import pipeline_names

    wrapped = {n for n in pipeline_names(method=None)
               if "irnuc_axis_top" in tops_for(load_pipeline(n))}
    assert wrapped == {"typical14", "wide16", "minimal", "onepoint14", "piecewise14",
                       "quadratic14", "tcoffset14", "tcgain14", "table14", "tchousing14", "ffc14",
                       "quadffc14", "tcffc14", "drift14"}
    p = top_parameters("irnuc_axis_top", load_pipeline("drift14"))
    assert (p["Drift"], p["Method"], p["BlindMax"], p["DriftGainFracBits"]) == (1, 1, 8192, 24)
    assert "Ffc" not in p
    p = top_parameters("irnuc_axis_top", load_pipeline("quadffc14"))
    assert (p["Ffc"], p["Method"], p["FfcFrames"], p["FfcHold"]) == (1, 3, 8, 0)
    p = top_parameters("irnuc_axis_top", load_pipeline("tcoffset14"))
    assert (p["Method"], p["ReadingBits"], p["TcOrder"]) == (4, 14, 2)
    assert "Method" not in top_parameters("irnuc_axis_top", load_pipeline("typical14"))
    p = top_parameters("irnuc_axis_top", load_pipeline("table14"))
    assert (p["Method"], p["Tables"], p["WeightFracBits"], p["WeightRounding"]) == (5, 3, 15, 1)
    assert "Tables" not in top_parameters("irnuc_axis_core", load_pipeline("table14"))


def test_table_sel_by_hand() -> None:
    """table14's TABLE_SEL (j, the weight U1.15 of table j + 1, half_up) and frame word
    for readings written out by hand, table readings 100, 200, 400; non-increasing table
    readings give the error with j = weight = 0."""
    from irnuc.nuc_fixed.axis import TableSel, frame_word, table_sel

    cfg = load_pipeline("table14")
    rs = (100, 200, 400)
    cases = {  # reading: (j, w)
        50: (0, 0), 100: (0, 0), 133: (0, 10813),  # 33/100 * 32768 = 10813.44
        150: (0, 16384), 199: (0, 32440),  # 99/100 * 32768 = 32440.32
        200: (1, 0), 300: (1, 16384), 399: (1, 32604),  # 199/200 * 32768 = 32604.16
        400: (1, 32768), 500: (1, 32768), 250: (1, 8192),
    }
    for t, (j, w) in cases.items():
        regs = {"reading": t, "table_readings": rs}
        assert table_sel(cfg, regs) == TableSel(j, w), t
        assert frame_word(cfg, regs) == w, t
    # weight [23:0], j [27:24], valid [28], error [29]
    assert TableSel(1, 16384).register() == 16384 | 1 << 24 | 1 << 28
    assert TableSel(1, 16384).register(valid=False) == 0
    for bad in ((100, 100, 400), (400, 200, 100), (100, 300, 200)):
        regs = {"reading": 150, "table_readings": bad}
        assert table_sel(cfg, regs) == TableSel(0, 0, True)
        assert table_sel(cfg, regs).register() == 1 << 28 | 1 << 29
        assert frame_word(cfg, regs) == 0


def test_table_pair_image_by_hand() -> None:
    """The DMA's pair image of table j (table_pair_words / table_pair_bin): a 1 x 2 frame
    of table14 whose table words are written out by hand; 66-bit words in 9 bytes."""
    from irnuc.nuc_fixed.axis import table_pair_bin, table_pair_words
    from irnuc.nuc_fixed.method_top import MethodCoefficients

    cfg = load_pipeline("table14")
    fields = {f"table{k}": {"gain": np.array([[k + 1, 16384]]),
                            "offset": np.array([[-k, 8 * k]]),
                            "bad": np.array([[False, True]])} for k in range(3)}
    c = MethodCoefficients(cfg, fields, {"table_readings": (1, 2, 3)})
    # table k's word: gain | offset (16-bit two's complement) << 16 | bad << 32
    word = {(k, 0): (k + 1) | ((-k) & 0xFFFF) << 16 for k in range(3)}
    word |= {(k, 1): 16384 | (8 * k) << 16 | 1 << 32 for k in range(3)}
    for j in (0, 1):
        want = [[word[j, x] | word[j + 1, x] << 33 for x in (0, 1)]]
        assert table_pair_words(c, j).tolist() == want
        assert table_pair_bin(c, j) == b"".join(v.to_bytes(9, "little") for v in want[0])
    with pytest.raises(ValueError, match="no table pair"):
        table_pair_words(c, 2)


# ---- the FFC framing (irnuc_axis_top around method_ffc_top) ---------------------------------

def test_ffc_shutter_flags_from_ffc_ctrl_by_hand() -> None:
    """FFC_CTRL.start before frame 2 with frames 3: frames 2, 3, 4 are shutter frames; a
    second start before frame 3 counts again from there; frames 0: none."""
    from irnuc.nuc_fixed.axis import ffc_shutter_flags

    assert ffc_shutter_flags(7, {2: 3}) == [0, 0, 1, 1, 1, 0, 0]
    assert ffc_shutter_flags(7, {1: 2, 3: 2}) == [0, 1, 1, 1, 1, 0, 0]
    assert ffc_shutter_flags(3, {0: 0}) == [0, 0, 0]
    assert ffc_shutter_flags(3, {}) == [0, 0, 0]


def test_ffc_framing_by_hand() -> None:
    """ffc14 (N = 8, hold): two open frames, a full run of 8 shutter frames, the refresh
    frame (open), an open frame; the streams of each frame written out by hand."""
    from irnuc.nuc_fixed.axis import ffc_framing

    cfg = load_pipeline("ffc14")
    assert (cfg.ffc_frames, cfg.ffc_output) == (8, "hold")
    sh = [0, 0] + [1] * 8 + [0, 0]
    f = ffc_framing(cfg, sh, start=2)
    assert f.foff_in == (True,) * 12
    assert f.acc_out == (False,) * 2 + (True,) * 8 + (False,) * 2
    assert f.acc_in == (False,) * 3 + (True,) * 7 + (True, False)
    assert f.foff_out == (False,) * 10 + (True, False)
    assert f.shown == (True,) * 2 + (False,) * 8 + (True,) * 2
    assert f.done == 10
    # a run of 3 (no refresh): done as the next open frame starts; frames = 0: at once
    assert ffc_framing(cfg, [0, 1, 1, 1, 0, 0], start=1).done == 4
    assert ffc_framing(cfg, [0, 1, 1, 1, 0, 0], start=1).foff_out == (False,) * 6
    assert ffc_framing(cfg, [0, 0, 0], start=1).done == 1
    # shutter frames first (nothing output yet): shown even with hold
    assert ffc_framing(cfg, [1, 1, 0, 1]).shown == (True, True, True, False)


@pytest.mark.parametrize("name", ["ffc14", "quadffc14", "tcffc14"])
def test_ffc_framing_against_the_golden_run(name: str) -> None:
    """The frames that carry words on each stream, as ffc_framing says, against those of
    cosim.stages.ffc_run (the golden model's sequencer nuc_fixed.ffc.FfcState and
    method_top's held frames) on seeded random shutter sequences with short, full and long
    runs."""
    from irnuc.cocotb_tests.method_stim import random_coefficients, random_raw, random_reading
    from irnuc.cosim.stages import ffc_run
    from irnuc.nuc_fixed.axis import ffc_framing

    cfg = load_pipeline(name).replace(ffc_frames=2)
    rng = np.random.default_rng(24)
    for _ in range(4):
        sh = [bool(v) for v in rng.random(14) < 0.6]
        c = random_coefficients(cfg, 2, 3, rng)
        run = ffc_run(c, [random_raw(cfg, 2, 3, rng) for _ in sh], sh,
                      readings=[random_reading(cfg, c, rng) for _ in sh])
        f = ffc_framing(cfg, sh)
        assert f.acc_in == tuple(a is not None for a in run.acc_in), sh
        assert f.acc_out == tuple(a is not None for a in run.acc_out), sh
        assert f.foff_out == tuple(a is not None for a in run.foff_out), sh
        assert f.shown == tuple(not h for h in run.held), sh


def test_drift_frame_word_by_hand() -> None:
    """drift14 (two_point, blind sum 14 + 14 = 28 bits, drift gain S1.24): the frame word
    is {drift_gain[24:0], blind_ref[27:0], blind_sum[27:0], one unused bit}, the drift gain
    as its two's complement bits (docs/integration.md); read back as the same registers."""
    from irnuc.nuc_fixed.axis import CoreFrame, frame_method_inputs, frame_word

    cfg = load_pipeline("drift14")
    regs = {"blind_sum": 5, "blind_ref": 3, "drift_gain": -1}
    want = (5 << 1) | (3 << 29) | (((1 << 25) - 1) << 57)
    assert frame_word(cfg, regs) == want
    f = CoreFrame(raw=np.zeros((1, 1), np.int64), words=np.zeros((1, 1), np.uint64),
                  settings=FrameSettings(1, 1), filler=np.zeros((1, 1), bool),
                  frame_word=want)
    coeffs, inputs = frame_method_inputs(f, cfg)
    assert (coeffs.registers["blind_ref"], coeffs.registers["drift_gain"]) == (3, -1)
    assert inputs.blind_sums.tolist() == [5]


def test_drift_through_the_wrapper_model_matches_blind_codes() -> None:
    """drift14 through the wrapper's model (BLIND_SUM on the frame word) corrects as
    nuc_fixed.method_top does given blind codes of that sum (the other path, through
    blind_sums of the codes); NUC off gives the raw code (drift code 0, unity word)."""
    from irnuc.cocotb_tests.method_stim import random_coefficients, random_raw
    from irnuc.cosim.stages import blind_codes_for
    from irnuc.cosim.stream import frame_drive
    from irnuc.nuc_fixed.axis import coef_beats, frame_word, video_beats
    from irnuc.nuc_fixed.method_top import FrameInputs, method_top

    cfg = load_pipeline("drift14")
    rng = np.random.default_rng(7)
    c = random_coefficients(cfg, 3, 5, rng, bad_fraction=0.3)
    c.registers["drift_gain"] = -(1 << 22)  # -0.25 ADC codes per code of blind sum
    c.registers["blind_ref"] = 5 * 16383
    raw = random_raw(cfg, 3, 5, rng)
    words = frame_drive(c).words
    for bsum in (5 * 16383 + 37, 4 * 16383, 0):  # small drift either way, and saturated
        settings = FrameSettings(5, 3, frame_word=frame_word(cfg, {**c.registers,
                                                                   "blind_sum": bsum}))
        out = axis_top(*video_beats([raw]), *coef_beats([words]), [settings], cfg)
        codes = blind_codes_for(bsum, cfg)
        res = method_top(raw[None], c, FrameInputs(blind_codes=codes[None]))
        assert out.data.tolist() == res.y[0].ravel().tolist(), bsum
    off = FrameSettings(5, 3, nuc_en=False, dpc_en=False, frame_word=0)
    out = axis_top(*video_beats([raw]), *coef_beats([words]), [off], cfg)
    assert out.data.tolist() == raw.ravel().tolist()


def test_drift_from_sums_by_hand() -> None:
    """drift_from_sums on drift14 (Mf = 24, Df = 2, half_up, S14.2 saturating): bd = 100,
    m = 2^22 (0.25): 100 * 2^22 >> 22 = 100 codes of 1/4, i.e. 25 ADC codes; bd = -3,
    m = 2^23 + 1: -3 (2^23 + 1) / 2^22 = -6.0000007 -> -6; a sum far above the reference
    with m = 2^24 - 1 saturates at 2^15 - 1."""
    from irnuc.nuc_fixed.drift import drift_from_sums

    cfg = load_pipeline("drift14")
    assert drift_from_sums([1100], 1000, 1 << 22, cfg).delta.tolist() == [100]
    assert drift_from_sums([997], 1000, (1 << 23) + 1, cfg).delta.tolist() == [-6]
    assert drift_from_sums([(1 << 28) - 1], 0, (1 << 24) - 1, cfg).delta.tolist() == [32767]
