"""The hardware cost of sweep points (``irnuc.reports.studies.hwcost``): block RAM counts,
the external-memory fallback, the choice of the points to synthesize, the cost model and
its stated error, the recommendation and the grid-edge warnings."""

from __future__ import annotations

import pytest

from irnuc.reports.studies import hwcost as H
from irnuc.reports.studies.sweep import SweepPoint


def test_bram_blocks_pick_the_best_aspect_ratio() -> None:
    # 29-bit words, 1024 deep: one 1K x 36 RAMB36E1; 2048 deep: two (2K x 18 needs 2 x 2).
    assert H.bram_blocks(29, 1024, H.XC7_BRAM36_SHAPES) == 1
    assert H.bram_blocks(29, 2048, H.XC7_BRAM36_SHAPES) == 2
    # 1-bit words: 32K deep per block.
    assert H.bram_blocks(1, 65536, H.XC7_BRAM36_SHAPES) == 2
    assert H.bram_blocks(18, 1024, H.ECP5_DP16KD_SHAPES) == 1
    assert H.bram_blocks(19, 1024, H.ECP5_DP16KD_SHAPES) == 2


def test_vga_coefficients_go_to_external_memory_a_tiny_frame_fits() -> None:
    vga = H.coefficient_memory(29, 480, 640, frame_rate_hz=60.0)
    assert vga["bits_per_frame"] == 29 * 480 * 640
    assert not vga["xc7_fits"] and not vga["ecp5_fits"]
    assert vga["external_bytes_per_pixel"] == 4  # a 29-bit word on a 32-bit bus
    assert vga["external_mbyte_per_s"] == pytest.approx(4 * 480 * 640 * 60 / 1e6)
    tiny = H.coefficient_memory(14, 12, 16)
    assert tiny["xc7_fits"] and tiny["ecp5_fits"] and tiny["xc7_bram36"] == 1
    assert tiny["external_bytes_per_pixel"] == 2


def _pt(i: int, gi: int, gf: int, oi: int, of: int, err: float) -> dict:
    """A point's record as the sweep writes it (SweepPoint.record), with an error."""
    p = SweepPoint(index=i, adc_bits=14, out_bits=14, gain_int_bits=gi, gain_frac_bits=gf,
                   offset_int_bits=oi, offset_frac_bits=of, rounding="half_even",
                   coeff_rounding="half_even", pipeline="typical14")
    rec = {**p.record(), "err_max_lsb": err}
    assert rec["bits_per_pixel"] == gi + gf + oi + of + 1 and rec["label"] == f"U{gi}.{gf} / S{oi}.{of}"
    return rec


GRID = [_pt(k, 1, gf, 12, of, 2.0 ** (10 - gf) + 0.5 * 2.0 ** -of)
        for k, (gf, of) in enumerate((gf, of) for gf in range(8, 17) for of in range(5))]


def test_fit_points_are_the_corners_of_the_word_widths() -> None:
    idx = H.fit_indices(GRID, 4)
    ws = {H.widths(GRID[i]) for i in idx}
    assert ws == {(9, 12), (9, 16), (17, 12), (17, 16)}
    assert len(H.fit_indices(GRID, 6)) == 6 and len(H.fit_indices(GRID[:2], 4)) == 2


def _figs(g: int, o: int) -> dict[str, float]:
    return {k: 100.0 + 7.0 * g + 3.0 * o if k != "fmax_mhz" else 150.0 - 0.5 * g for k in H.COST_KEYS}


def test_cost_model_is_exact_on_linear_data_and_states_its_error() -> None:
    ws = [(9, 12), (9, 16), (17, 12), (17, 16)]
    model = H.CostModel.fit(ws, [_figs(*w) for w in ws])
    assert model.predict((13, 14))["xc7.lut"] == pytest.approx(100 + 7 * 13 + 3 * 14)
    assert model.loo["xc7.lut"]["max_abs"] == pytest.approx(0.0, abs=1e-9)
    # A point off the plane: the error against it is what it is off.
    off = _figs(13, 14)
    off["xc7.lut"] += 10.0
    err = model.errors([(13, 14)], [off])
    assert err["xc7.lut"]["max_abs"] == pytest.approx(10.0)
    assert err["xc7.lut"]["max_rel"] == pytest.approx(10.0 / off["xc7.lut"])
    # Leave-one-out sees a bent plane.
    bent = [_figs(*w) for w in ws]
    bent[3]["xc7.ff"] += 40.0
    assert H.CostModel.fit(ws, bent).loo["xc7.ff"]["max_abs"] > 10.0


def test_recommendation_is_the_cheapest_meeting_the_tolerance() -> None:
    pts = [_pt(0, 1, 14, 12, 1, 0.9), _pt(1, 1, 13, 12, 2, 0.95), _pt(2, 1, 12, 12, 1, 1.5),
           _pt(3, 1, 16, 12, 4, 0.3)]
    rec = H.recommend(pts, 1.0, "err_max_lsb")
    assert rec["found"] and rec["candidates"] == [0, 1] and rec["index"] == 0  # lower error
    # The datapath breaks the memory tie.
    rec = H.recommend(pts, 1.0, "err_max_lsb", {0: 700.0, 1: 650.0})
    assert rec["index"] == 1
    assert not H.recommend(pts, 0.1, "err_max_lsb")["found"]


def test_recommendation_is_synthesized_when_the_model_picks_another() -> None:
    """Three candidates at the same memory; only 0 synthesized. The model costs 2 lowest,
    its synthesis shows it dear, then 1 is chosen on its prediction and synthesized too: the
    choice ends on a synthesized point, with one synthesis per round."""
    pts = [_pt(0, 1, 14, 12, 1, 0.9), _pt(1, 1, 13, 12, 2, 0.95), _pt(2, 1, 12, 12, 3, 0.97)]
    real = {0: 700.0, 1: 650.0, 2: 900.0}
    predicted = {0: 700.0, 1: 600.0, 2: 500.0}
    synthesized: list[int] = [0]

    def costs() -> dict[int, float]:
        return {i: real[i] if i in synthesized else predicted[i] for i in real}

    rec = H.recommend_synthesized(pts, 1.0, "err_max_lsb", costs, synthesized, synthesized.append)
    assert rec["index"] == 1 and synthesized == [0, 2, 1]
    # Already synthesized: nothing more is.
    done = [0, 1, 2]
    assert H.recommend_synthesized(pts, 1.0, "err_max_lsb", costs, done, done.append)["index"] == 1
    assert done == [0, 1, 2]
    # Nothing meets the tolerance: nothing is synthesized.
    none: list[int] = []
    assert not H.recommend_synthesized(pts, 0.1, "err_max_lsb", costs, none, none.append)["found"]
    assert none == []


def test_grid_edges_name_the_axis_and_the_way_to_widen() -> None:
    axes = {"gain_frac_bits": list(range(4, 15)), "offset_frac_bits": [0, 1, 2, 3, 4],
            "gain_int_bits": ["auto"]}
    top = H.grid_edges({"gain_frac_bits": 14, "offset_frac_bits": 1}, axes)
    assert top == [{"axis": "gain_frac_bits", "edge": "top", "widen": "add gain_frac_bits above 14"}]
    assert H.grid_edges({"gain_frac_bits": 10, "offset_frac_bits": 2}, axes) == []
    low = H.grid_edges({"gain_frac_bits": 4, "offset_frac_bits": 0}, axes)
    assert [e["axis"] for e in low] == ["gain_frac_bits"]  # offset 0 has nothing below
