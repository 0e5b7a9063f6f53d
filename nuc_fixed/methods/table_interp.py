"""table_interp: K two-point tables calibrated at K FPA readings; per frame the two nearest
the reading, interpolated by one weight (docs/methods.md, docs/datapath.md
"table_interp")."""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from irnuc.common.errors import ConfigError
from irnuc.nuc_fixed.fit import check_reading_codes, check_readings, ls_line
from irnuc.nuc_fixed.methods.bins import (
    REGION_BINS,
    ROUND_BINS,
    SIGN_BINS,
    TABLE_BAD_BINS,
    WEIGHT_BINS,
    hit,
    round_class,
)
from irnuc.nuc_fixed.plan import PlanError
from irnuc.nuc_fixed.rtl_spec import COEF_WORD
from irnuc.nuc_fixed.spec import (
    Block,
    Classes,
    FormatSpec,
    Frame,
    FrameExpressions,
    MemoryLayout,
    MethodSpec,
    ParamSpec,
    Points,
    Register,
    RegisterSlot,
    Word,
    word_memory,
)
from irnuc.nuc_fixed.tempcomp import InterpWeight, interp_coeffs, interp_exprs, interp_weight
from irnuc.nuc_fixed.widths import W, diff_unsigned, mul, sub

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig
    from irnuc.nuc_fixed.cores import CoreResult
    from irnuc.nuc_fixed.method_top import MethodCoefficients


#: Coverpoint -> bins of table_interp's selection in irnuc_axis_top (with ``axis.table.j``,
#: the configuration's 0 .. K - 2: :meth:`TableInterp.axis_points`).
TABLE_AXIS_POINTS: dict[str, tuple[str, ...]] = {
    "axis.table.weight": ("zero", "between", "one"),
    "axis.table.sel": ("computing", "valid", "error"),
    "axis.table.held": ("between_frames", "in_frame_before"),
}


def _tables(cfg: PipelineConfig) -> int:
    return int(cfg.tables or 0)


@dataclass(frozen=True)
class TableInterp(MethodSpec):
    def check(self, cfg: PipelineConfig, src: str) -> None:
        if cfg.format("weight").int_bits < 1:
            raise ConfigError(f"{src}: formats.weight = {cfg.format('weight')} cannot hold "
                              "1.0; int_bits must be at least 1")

    def memories(self, cfg: PipelineConfig) -> list[MemoryLayout]:
        # Two of the K tables are read per frame (reads_per_frame counts per memory).
        return [word_memory(COEF_WORD, f"table{k}", cfg, reads_per_frame=0)
                for k in range(_tables(cfg))]

    def registers(self, cfg: PipelineConfig) -> list[Register]:
        r = int(cfg.reading_bits or 1)
        return [Register("table_readings", r, False, f"U{r}.0", count=_tables(cfg),
                         meaning="reading of each table, strictly increasing")]

    def weight(self, c: MethodCoefficients, frame: Frame) -> InterpWeight:
        """The frame's lower table j and weight w (``interp_weight``)."""
        return interp_weight(int(frame["fpa"]), c.registers["table_readings"], c.cfg)

    def frame_coefficients(self, c: MethodCoefficients, frame: Frame) -> dict[str, Any]:
        iw = self.weight(c, frame)
        lo, hi = c.fields[f"table{iw.j}"], c.fields[f"table{iw.j + 1}"]
        g, o = interp_coeffs((lo["gain"], lo["offset"]), (hi["gain"], hi["offset"]), iw, c.cfg)
        # Its DPC replaces a pixel flagged in table j or j + 1 (docs/datapath.md).
        return {"gain": g, "offset": o, "bad": lo["bad"] | hi["bad"]}

    def frame_expressions(self, c: MethodCoefficients, frame: Frame) -> FrameExpressions:
        # The interpolation of frame_coefficients, evaluated per pixel in the fused pass.
        iw = self.weight(c, frame)
        lo, hi = c.fields[f"table{iw.j}"], c.fields[f"table{iw.j + 1}"]
        g, o = interp_exprs((lo["gain"], lo["offset"]), (hi["gain"], hi["offset"]), iw, c.cfg)
        return FrameExpressions({"gain": g, "offset": o}, (lo["bad"], hi["bad"]))

    def widths(self, cfg: PipelineConfig) -> dict[str, W | int]:
        wf = cfg.format("weight")
        r = int(cfg.reading_bits or 1)
        w = W(wf.frac_bits + 1, False)
        out: dict[str, W | int] = {"interp.num": W(r + wf.frac_bits, False),
                                   "interp.span": W(r, False), "interp.w": w}
        for kind, bits in (("g", cfg.gain_bits), ("o", cfg.offset_bits)):
            diff = (sub(W(bits, True), W(bits, True)) if kind == "o"
                    else diff_unsigned(W(bits, False), W(bits, False)))
            out |= {f"interp.{kind}.diff": diff, f"interp.{kind}.prod": mul(diff, w)}
        return out

    def check_readings(self, cfg: PipelineConfig, readings: list[int], reference: int,
                       source: str, sensor: str) -> None:
        if len(readings) != cfg.tables:
            raise PlanError(f"{source}: method table_interp with tables = {cfg.tables} needs "
                            f"{cfg.tables} FPA temperatures; the plan has {len(readings)}")
        check_reading_codes(cfg, readings, len(readings), "table_interp needs one reading "
                            "per table, each different", source, sensor)

    def fit(self, cfg: PipelineConfig, pts: Any, means: np.ndarray, t: np.ndarray,
            q: Any) -> None:
        # A two-point table per FPA point, in increasing reading order.
        readings = [pts.point_reading(p) for p in range(means.shape[0])]
        if min(readings) < 0:
            raise PlanError(f"{pts.source}: method {cfg.method!r} needs the FPA reading of "
                            "every frame (fpa_reading); the frames lack it")
        check_readings(cfg, readings, pts.reference, pts.source)
        xbar = means.mean(axis=1)  # (P, H, W)
        tbar = float(np.mean(t))
        order = np.argsort(readings)
        rs = [readings[i] for i in order]
        if len(rs) != cfg.tables:
            raise PlanError(f"{pts.source}: method table_interp with tables = {cfg.tables} "
                            f"needs {cfg.tables} FPA temperatures; the plan has {len(rs)}")
        if any(b <= a for a, b in itertools.pairwise(rs)):
            raise PlanError(f"{pts.source}: two FPA points give the same reading {rs}; "
                            "table readings must increase strictly")
        q.register("table_readings", None, rs, bits=int(cfg.reading_bits or 1))
        for k, p in enumerate(order):
            g, _ = ls_line(means[p], t)
            gq = q.field(f"table{k}.gain", "gain", g)
            q.field(f"table{k}.offset", "offset", tbar - gq * xbar[p])

    def float_correct(self, cfg: PipelineConfig, f: Mapping[str, Any], x: np.ndarray,
                      frame: Frame) -> np.ndarray:
        t = int(frame["fpa"])
        rs = list(f["table_readings"])
        j = max([i for i in range(len(rs) - 1) if rs[i] <= t] or [0])
        w = min(max((t - rs[j]) / (rs[j + 1] - rs[j]), 0.0), 1.0)
        g = (1 - w) * f[f"table{j}.gain"] + w * f[f"table{j + 1}.gain"]
        o = (1 - w) * f[f"table{j}.offset"] + w * f[f"table{j + 1}.offset"]
        return g * x + o

    # ---- RTL streams: tables j and j + 1 of the frame, its weight -------------------
    def stream_memories(self, cfg: PipelineConfig) -> list[tuple[str, MemoryLayout]]:
        table = cfg.memories["table0"]
        return [(n, dataclasses.replace(table, name=n)) for n in ("lower", "upper")]

    def stream_words(self, c: MethodCoefficients, frame: Frame
                     ) -> tuple[list[tuple[np.ndarray, int]], Any]:
        iw = self.weight(c, frame)
        words = c.words()
        bits = c.cfg.memories["table0"].word_bits
        return [(words[f"table{iw.j}"], bits), (words[f"table{iw.j + 1}"], bits)], iw

    def stream_key(self, c: MethodCoefficients, frame: Frame) -> Any:
        return self.weight(c, frame).j

    def frame_values(self, cfg: PipelineConfig, values: Mapping[str, Any]) -> dict[str, int]:
        # The weight of the reading between the table readings (irnuc_axis_table's
        # TABLE_SEL: 0 while the table readings do not increase strictly).
        rs = [int(v) for v in values["table_readings"]]
        if any(b <= a for a, b in itertools.pairwise(rs)):
            return {"weight": 0}
        return {"weight": interp_weight(int(values["reading"]), rs, cfg).w}

    def from_frame_word(self, cfg: PipelineConfig, fields: dict[str, dict[str, np.ndarray]],
                        values: Mapping[str, int]
                        ) -> tuple[dict[str, dict[str, np.ndarray]], dict[str, Any]]:
        # The frame's pair of tables and weight as a calibration read at reading 0: every
        # table the pair interpolated with the weight, table readings 0, 1, ... (j = 0,
        # weight 0), so the golden model corrects the frame as the core does (its DPC
        # replacing a pixel flagged in either table of the pair).
        lo, hi = fields["lower"], fields["upper"]
        g, o = interp_coeffs((lo["gain"], lo["offset"]), (hi["gain"], hi["offset"]),
                             InterpWeight(0, int(values["weight"])), cfg)
        table = {"gain": g, "offset": o, "bad": lo["bad"] | hi["bad"]}
        k = int(cfg.tables or 2)
        return ({f"table{i}": dict(table) for i in range(k)},
                {"table_readings": tuple(range(k)), "reading": 0})

    def dma_images(self, c: MethodCoefficients) -> dict[str, bytes]:
        # Tables j and j + 1 in one word, as irnuc_axis_top's s_axis_coef takes them.
        from irnuc.nuc_fixed.axis import table_pair_bin

        return {f"table_pair{j}.bin": table_pair_bin(c, j) for j in range(_tables(c.cfg) - 1)}

    # ---- verification ------------------------------------------------------------------
    def coverage_points(self, cfg: PipelineConfig) -> Points:
        points: dict[str, tuple[str, ...]] = {"table.weight": WEIGHT_BINS,
                                              "table.region": REGION_BINS,
                                              "table.diff": SIGN_BINS,
                                              "table.bad": TABLE_BAD_BINS}
        if cfg.format("weight").frac_bits > 0:
            points["table.round"] = ROUND_BINS
        return points, {}

    def coverage_classes(self, c: MethodCoefficients, raw: np.ndarray, frame: Frame,
                         res: CoreResult) -> Classes:
        cfg = c.cfg
        out: Classes = {}
        rs = list(c.registers["table_readings"])
        iw = self.weight(c, frame)
        wf = cfg.format("weight").frac_bits
        out["table.weight"] = {"zero" if iw.w == 0 else "one" if iw.w == 1 << wf else
                               "between"}
        t = int(frame["fpa"])
        out["table.region"] = {"below" if t < rs[0] else "above" if t > rs[-1] else "between"}
        g0 = c.fields[f"table{iw.j}"]["gain"]
        dg = c.fields[f"table{iw.j + 1}"]["gain"] - g0
        hit(out, "table.diff", SIGN_BINS, np.sign(dg) + 1)
        if wf > 0:
            hit(out, "table.round", ROUND_BINS, round_class(dg * iw.w, wf))
        lo = c.fields[f"table{iw.j}"]["bad"]
        up = c.fields[f"table{iw.j + 1}"]["bad"]
        hit(out, "table.bad", TABLE_BAD_BINS,
            np.flatnonzero([(lo & ~up).any(), (~lo & up).any(), (lo & up).any()]))
        return out

    def axis_points(self, cfg: PipelineConfig) -> dict[str, tuple[str, ...]]:
        # The selection of irnuc_axis_table (TABLE_SEL), sampled by tb_axis_table.
        return {"axis.table.j": tuple(str(j) for j in range(_tables(cfg) - 1)),
                **TABLE_AXIS_POINTS}

    def reading_marks(self, c: MethodCoefficients) -> list[int]:
        # The table readings and the midpoints between them (w = 1/2 on an even span: a
        # rounding tie).
        rs = [int(v) for v in c.registers["table_readings"]]
        return rs + [(a + b) // 2 for a, b in itertools.pairwise(rs)] + [rs[0] - 1, rs[-1] + 1]

    def corner(self, c: MethodCoefficients, raw: np.ndarray, rng: np.random.Generator,
               index: int) -> None:
        if index % 3 == 0:
            # A pixel bad in the even tables, one in the odd ones, one in every table: each
            # pair (j, j + 1) has a pixel bad in its lower table only, its upper only, both.
            for k in range(_tables(c.cfg)):
                bad = c.fields[f"table{k}"]["bad"]
                bad.flat[k % 2] = True
                bad.flat[2 % bad.size] = True

    def draw_register(self, r: Register, rng: np.random.Generator, lo: int, hi: int
                      ) -> object | None:
        if r.name != "table_readings":
            return None
        k = r.count
        span = hi - lo + 1
        gaps = rng.integers(1, max(2, span // (k + 1)), size=k)
        start = int(rng.integers(lo, max(lo + 1, span - int(gaps.sum()))))
        return tuple(int(v) for v in start + np.cumsum(gaps) - gaps[0])


METHOD = TableInterp(
    name="table_interp", doc="two tables interpolated by a weight", core="lin",
    readings=("fpa",),
    formats=(FormatSpec("weight", False, "table interpolation weight in [0, 1] (per frame)",
                        computed=True, rtl_modes=("rounding",), sv_default=(1, 15)),),
    params=(ParamSpec.range("tables", 2, 16, "tables", "K, the tables", "Tables", 3,
                            rtl_scope="wrapper"),),
    stream=(Word("lower", COEF_WORD), Word("upper", COEF_WORD)),
    frame_word=(Block("weight", "WeightBits"),),
    rtl_module="method_table_interp", rtl_front_registered=True,
    rtl_checked=("table_interp", "interp_weight", "nuc_core"),
    rtl_files=("table_interp.sv",),
    slots=(RegisterSlot("TableReadingBits", "table_readings", "ReadingBits", absent=1,
                        count="TableReadings", sv_count="Tables"),),
)
