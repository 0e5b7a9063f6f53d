"""Catalogue mutants decided by a miter that compares only what the top's contract defines
(``irnuc mutate --decide ID``; docs/mutation.md, "Equivalence decided by a contract miter").

The automatic mutants' miter (:func:`irnuc.cosim.formal.equivalence`) drives both netlists
with free inputs and compares every output bit at every cycle. That asks more than the
design promises: a stream's payload means nothing while its valid is 0, and an input that
breaks the top's input contract (a frame of height 0) has no specified answer. A "different"
from it is not a counterexample to a written equivalence argument. The miter here
(:func:`harness`) differs in two ways:

* **masked by valid**: each output stream's payload (``m_<s>_*_o`` besides its valid) is
  compared only in a cycle where the original's valid is 1; valids, readies and every other
  output (``frame_err_o``) are compared at every cycle out of reset (AXI4-Stream, ARM
  IHI0051 2.2.1: TDATA, TUSER, TLAST are meaningful only with TVALID);
* **legal inputs** (the environment's assumptions):

  - reset in the first cycle, free afterwards (``irnuc_fv_reset``);
  - each input stream ``s_<s>``: valid held until ready, payload stable while stalled,
    valid low in reset (``irnuc_fv_stream`` with ``Assume = 1``, the property module of
    ``irnuc formal``; the ready it sees is the original's);
  - the frame size (a top with ``frame_width_i`` / ``frame_height_i``, docs/rtl.md "Frame
    size rule"): 1..MaxWidth x 1..MaxHeight whenever a pixel is taken at ``s_pix``, and
    unchanged while a pixel taken there has not left at ``m_pix`` (a count of the pixels
    in flight: the top gives one output pixel per input pixel). This is the rule's
    "simplest" form, and a little looser than the rule: a size may change whenever nothing
    is in flight. Looser assumptions can only add counterexamples, never hide one;
  - every other input free: the markers (only checked, ``frame_err_o``), ``m_*_ready_i``,
    every payload bit.

Both netlists (:func:`irnuc.cosim.netlist.write_netlist`, flat, ``SYNTHESIS``: no
checkers; the same passes as the automatic mutants') start with every flop at 0, as
:func:`irnuc.cosim.formal.equivalence` does. The decision (:func:`decide`):
ABC's ``scorr`` + ``dprove`` (signal correspondence by induction, then the rest), else
property-directed reachability (ABC ``pdr``, unbounded), else a bounded search (``bmc3``)
to say how far no difference exists; a failure is replayed by yosys-smtbmc on the same
model for the failed assertion's label and a VCD. Results of catalogue mutants
(:func:`decide_mutant`) are cached by the digest of the RTL the top elaborates, the mutant,
the parameters, this module and the property modules, and the tool versions.
"""

from __future__ import annotations

import json
import re
import shutil
import tempfile
import time
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path

from irnuc.common.cache import cache_dir, read_cached_json
from irnuc.common.digest import digest, files_digest
from irnuc.common.errors import UserError
from irnuc.common.io import write_text_atomic
from irnuc.verif.mutant import Mutant

#: Wall-time budget of one decision (seconds; under the formal lane's 25-minute hold).
BUDGET = 1200.0
#: The bound of the closing bounded search when neither induction nor PDR decided.
DEPTH = 40
#: The tops whose input contract :func:`harness` knows: their frame size follows the
#: "Frame size rule" of docs/rtl.md with ``s_pix`` in and ``m_pix`` out (one output pixel
#: per input pixel). Other tops are refused before any work.
FRAME_TOPS = ("nuc_dpc_top", "method_dpc_top")
#: The harness module's name.
HARNESS = "eq_contract"

Port = tuple[str, str, int]  # (name, direction, width)


@dataclass(frozen=True)
class Stream:
    """A valid/ready stream of a top found by its port names: ``<name>_valid_i`` (input
    stream, ``s_*``) or ``_o`` (output stream, ``m_*``), ``<name>_ready_o`` / ``_i``, and
    the payload: the other ports ``<name>_*`` in the valid's direction."""

    name: str
    output: bool
    valid: str
    ready: str
    payload: tuple[str, ...]


def streams(ports: Sequence[Port]) -> list[Stream]:
    """The valid/ready streams among ``ports`` (see :class:`Stream`), in port order."""
    names = {n: d for n, d, _ in ports}
    out = []
    for n, d, _ in ports:
        m = re.fullmatch(r"(\w+)_valid_([io])", n)
        if not m:
            continue
        base, output = m.group(1), d == "output"
        ready = f"{base}_ready_{'i' if output else 'o'}"
        if names.get(ready) != ("input" if output else "output"):
            continue
        payload = tuple(p for p, pd, _ in ports if p.startswith(f"{base}_")
                        and p not in (n, ready) and pd == d)
        out.append(Stream(base, output, n, ready, payload))
    return out


def _cat(names: Sequence[str], prefix: str = "") -> str:
    return "{" + ", ".join(f"{prefix}{n}" for n in names) + "}"


def harness(top: str, ports: Sequence[Port], frame: Mapping[str, int] | None = None) -> str:
    """SystemVerilog of the contract miter of netlists ``<top>__gold`` and ``<top>__mut``
    (module :data:`HARNESS`, the top's inputs as its ports): the environment's assumptions
    and the masked comparison of the module docstring. ``frame``: ``{"MaxWidth": W,
    "MaxHeight": H}`` for a top with a run-time frame size (``frame_width_i``,
    ``frame_height_i``, streams ``s_pix`` and ``m_pix``); None: no frame-size assumption."""
    width = {n: w for n, _, w in ports}
    ins = [(n, w) for n, d, w in ports if d == "input" and n not in ("clk_i", "rst_ni")]
    outs = [n for n, d, _ in ports if d == "output"]
    strs = streams(ports)
    decl = "".join(f",\n  input logic [{w - 1}:0] {n}" for n, w in ins)
    wires = "".join(f"  logic [{width[n] - 1}:0] gold_{n}, gate_{n};\n" for n in outs)

    def inst(side: str) -> str:
        conns = [".clk_i", ".rst_ni", *[f".{n}({n})" for n, _ in ins],
                 *[f".{n}({side}_{n})" for n in outs]]
        return f"  {top}__{'gold' if side == 'gold' else 'mut'} u_{side} (" + ", ".join(conns) + ");\n"

    body = [f"// The contract miter of {top}'s original and mutated netlists (irnuc mutate "
            f"--decide,\n// irnuc.verif.miter): legal inputs assumed, each output stream's "
            f"payload compared only\n// while its valid is 1, every other output always.\n",
            f"module {HARNESS} (\n  input logic clk_i,\n  input logic rst_ni{decl}\n);\n",
            wires, inst("gold"), inst("gate"),
            "  irnuc_fv_reset u_reset (.clk_i, .rst_ni);\n"]
    for s in strs:
        if s.output:
            continue
        bits = sum(width[p] for p in s.payload)
        data = _cat(s.payload) if s.payload else "1'b0"
        body.append(f"  // {s.name}: the AXI4-Stream rules assumed of the source\n"
                    f"  irnuc_fv_stream #(.DataBits({max(bits, 1)}), .Assume(1'b1)) "
                    f"u_in_{s.name} (\n    .clk_i, .rst_ni, .valid_i({s.valid}), "
                    f".ready_i(gold_{s.ready}), .data_i({data}));\n")
    if frame is not None:
        body.append(_frame_rule(ports, frame))
    masked = {p for s in strs if s.output for p in s.payload}
    always = [n for n in outs if n not in masked]
    checks = [f"      a_control: assert ({_cat(always, 'gold_')} == {_cat(always, 'gate_')});\n"]
    for s in strs:
        if s.output and s.payload:
            checks.append(f"      if (gold_{s.valid}) begin\n"
                          f"        a_{s.name}_payload: assert ({_cat(s.payload, 'gold_')} "
                          f"== {_cat(s.payload, 'gate_')});\n      end\n")
    body.append("  always_comb begin : p_equal\n    if (rst_ni) begin\n" + "".join(checks)
                + "    end\n  end\nendmodule\n")
    return "".join(body)


def _frame_rule(ports: Sequence[Port], frame: Mapping[str, int]) -> str:
    """The frame-size assumptions (module docstring) on ``frame_width_i`` /
    ``frame_height_i``, pixels taken at ``s_pix`` and given at ``m_pix``."""
    width = {n: w for n, _, w in ports}
    need = ("frame_width_i", "frame_height_i", "s_pix_valid_i", "s_pix_ready_o",
            "m_pix_valid_o", "m_pix_ready_i")
    missing = [n for n in need if n not in width]
    if missing:
        raise UserError(f"the frame-size contract needs the ports {', '.join(missing)}")
    wb, hb = width["frame_width_i"], width["frame_height_i"]
    mw, mh = int(frame["MaxWidth"]), int(frame["MaxHeight"])
    # In flight: at most two lines and the pipelines; a wrap of the count only loosens
    # the assumption (a size change allowed early), it never hides a difference.
    cb = max(4, (4 * mw + 64).bit_length())
    return (
        f"  // The frame size (docs/rtl.md, Frame size rule): legal whenever a pixel is taken,\n"
        f"  // unchanged while a pixel taken has not left.\n"
        f"  logic take, give;\n"
        f"  logic [{cb - 1}:0] flight_q;\n"
        f"  logic [{wb - 1}:0] width_q;\n"
        f"  logic [{hb - 1}:0] height_q;\n"
        f"  assign take = s_pix_valid_i && gold_s_pix_ready_o;\n"
        f"  assign give = gold_m_pix_valid_o && m_pix_ready_i;\n"
        f"  always_ff @(posedge clk_i or negedge rst_ni) begin : p_flight\n"
        f"    if (!rst_ni) flight_q <= '0;\n"
        f"    else flight_q <= flight_q + {cb}'(take) - {cb}'(give);\n"
        f"  end\n"
        f"  always_ff @(posedge clk_i) begin : p_size\n"
        f"    width_q  <= frame_width_i;\n"
        f"    height_q <= frame_height_i;\n"
        f"  end\n"
        f"  always_comb begin : p_frame_rule\n"
        f"    if (rst_ni && take) begin\n"
        f"      m_size_legal: assume (frame_width_i >= {wb}'d1 && frame_width_i <= {wb}'d{mw}\n"
        f"                            && frame_height_i >= {hb}'d1 && frame_height_i <= {hb}'d{mh});\n"
        f"    end\n"
        f"    if (rst_ni && flight_q != '0) begin\n"
        f"      m_size_held: assume (frame_width_i == width_q && frame_height_i == height_q);\n"
        f"    end\n"
        f"  end\n")


def _check(res, verdict: str, engine: str, t0: float, message: str) -> dict:
    return {"verdict": verdict, "engine": engine,
            "seconds": round(time.perf_counter() - t0, 2), "step": res.step,
            "failed": list(res.failed), "vcd": res.vcd, "message": message}


def decide(gold: Path, gate: Path, top: str, ports: Sequence[Port], workdir: Path, *,
           frame: Mapping[str, int] | None = None, budget: float = BUDGET,
           depth: int = DEPTH) -> dict:
    """Decide the netlists ``gold`` (module ``<top>__gold``) and ``gate``
    (``<top>__mut``) under the contract miter (:func:`harness`) within ``budget`` seconds:
    ``scorr`` + ``dprove`` (a third of it), else PDR, else ``bmc3`` to ``depth`` cycles.

    Returns ``{"verdict": "equivalent" | "different" | "undecided", "engine", "seconds",
    "step", "failed" (the assertions a counterexample breaks), "vcd", "message"}``."""
    from irnuc.cosim import formal

    wd = Path(workdir)
    wd.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    text = harness(top, ports, frame)
    (wd / f"{HARNESS}.sv").write_text(text)
    srcs = [Path(gold), Path(gate), formal.FORMAL_DIR / "irnuc_fv_reset.sv",
            formal.FORMAL_DIR / "irnuc_fv_stream.sv", wd / f"{HARNESS}.sv"]
    models = formal.write_models(srcs, HARNESS, {}, wd / "miter", defines=("FORMAL",),
                                 extra=["setundef -zero -init"])

    def left() -> float:
        return max(10.0, budget - (time.perf_counter() - t0))

    res = formal.dprove(models["aig"], wd / "dprove", timeout=max(10.0, budget / 3))
    if res.status == "proved":
        return _check(res, "equivalent", "scorr+dprove", t0,
                      "the outputs the contract defines proved equal in every reachable "
                      "state (signal correspondence, then dprove)")
    if res.status == "failed":
        res = formal.check(models, "bmc3", (res.step or 0) + 2, wd / "miter", timeout=left())
        if res.status == "failed":
            return _check(res, "different", "dprove+bmc3", t0,
                          f"{', '.join(res.failed) or 'an output'} differs {res.step} cycles "
                          f"after reset on legal inputs")
    res = formal.check(models, "pdr", depth, wd / "miter", timeout=left() * 0.85)
    if res.status == "proved":
        return _check(res, "equivalent", "pdr", t0,
                      "the outputs the contract defines proved equal in every reachable "
                      "state (PDR)")
    if res.status != "failed":
        res = formal.check(models, "bmc3", depth, wd / "miter", timeout=left(),
                           budget=left() * 0.9)
    if res.status == "failed":
        return _check(res, "different", res.engine, t0,
                      f"{', '.join(res.failed) or 'an output'} differs {res.step} cycles "
                      f"after reset on legal inputs")
    bound = res.depth if res.status == "passed" else 0
    return _check(res, "undecided", res.engine, t0,
                  f"no verdict in the {budget:g}-s budget; "
                  + (f"the outputs agree for {bound} cycles from reset" if bound else
                     f"the bounded search neither ({res.status})"))


# ---- catalogue mutants ---------------------------------------------------------------------

#: The property modules the harness instantiates (part of the cache key).
_PROPS = ("irnuc_fv_reset.sv", "irnuc_fv_stream.sv")


def _key(m: Mutant, params: Mapping[str, int]) -> str:
    from irnuc.cosim import formal
    from irnuc.verif.mutate import top_digest

    return digest({"rtl": top_digest(m.top), "mutant": asdict(m), "params": dict(params),
                   "code": files_digest([Path(__file__),
                                         *(formal.FORMAL_DIR / p for p in _PROPS)]),
                   "tools": formal.tool_versions()})


def _cache(m: Mutant, params: Mapping[str, int]) -> Path:
    return cache_dir("mutate", "decided") / f"{m.id}-{_key(m, params)}.json"


def mutant(mid: str) -> Mutant:
    """The catalogue mutant ``mid`` whose top has a known contract (a one-line error naming
    ``--decide`` otherwise)."""
    from irnuc.common.schema import nearest
    from irnuc.verif.catalogue import CATALOGUE

    by_id = {m.id: m for m in CATALOGUE}
    if mid not in by_id:
        raise UserError(f"--decide {mid}: no such mutant{nearest(mid, list(by_id))} "
                        f"(irnuc mutate --list)")
    m = by_id[mid]
    if m.top not in FRAME_TOPS:
        raise UserError(f"--decide {mid}: its top {m.top} has no input contract for the miter "
                        f"(known: {', '.join(FRAME_TOPS)})")
    return m


def parameters(m: Mutant, frame_max: tuple[int, int] | None = None) -> dict[str, int]:
    """The top's parameters on the mutant's configuration; ``frame_max`` (W, H): with its
    ``max_width`` x ``max_height`` replaced (a smaller model of the same design)."""
    from irnuc.cosim.sources import top_parameters

    cfg = m.pipeline()
    if frame_max is not None:
        cfg = cfg.replace(max_width=int(frame_max[0]), max_height=int(frame_max[1]))
    return top_parameters(m.top, cfg)


def cached(m: Mutant) -> dict | None:
    """The cached decision of ``m`` on the current sources, or None (nothing run): on the
    configuration's own frame size if there is one, else the one at the largest size
    (``--frame-max``); a verdict before an ``undecided``."""
    found = []
    for path in cache_dir("mutate", "decided").glob(f"{m.id}-*.json"):
        res = read_cached_json(path)
        if not isinstance(res, dict) or not isinstance(res.get("params"), dict):
            continue
        try:
            if path.stem != f"{m.id}-{_key(m, res['params'])}":
                continue  # decided on other sources
        except Exception:  # a configuration that no longer builds
            continue
        own = res.get("frame_max") is None
        size = res["params"].get("MaxWidth", 0) * res["params"].get("MaxHeight", 0)
        found.append(((res.get("verdict") != "undecided", own, size), res))
    return max(found, key=lambda x: x[0])[1] if found else None


def decide_mutant(m: Mutant, *, budget: float = BUDGET, use_cache: bool = True,
                  frame_max: tuple[int, int] | None = None) -> dict:
    """Decide a catalogue mutant (text change) by the contract miter on its own
    configuration (``frame_max``: its frame size limits replaced, :func:`parameters`):
    the original's and the mutated copy's netlists, :func:`decide`; the trace kept in the
    cache (``mutate/traces``). Cached; an ``undecided`` result is run again when
    ``budget`` is larger than the one it had."""
    from irnuc.cosim import netlist
    from irnuc.cosim.sources import HDL_DIR, hdl_sources

    params = parameters(m, frame_max)
    cache = _cache(m, params)
    old = read_cached_json(cache) if use_cache else None
    if isinstance(old, dict) and (old.get("verdict") != "undecided"
                                  or old.get("budget", 0) >= budget):
        return old | {"cached": True}
    work = Path(tempfile.mkdtemp(prefix=f"decide.{m.id}.", dir=cache_dir("mutate", "work")))
    try:
        hdl = work / "hdl"
        shutil.copytree(HDL_DIR, hdl, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
        f = hdl / m.file
        f.write_text(m.apply(f.read_text()))
        t0 = time.perf_counter()
        gold = netlist.write_netlist(hdl_sources(m.top), m.top, params,
                                     work / "gold" / "gold.v", "gold")
        gate = netlist.write_netlist(hdl_sources(m.top, hdl), m.top, params,
                                     work / "mut" / "mut.v", "mut")
        build = round(time.perf_counter() - t0, 2)
        res = decide(gold, gate, m.top, netlist.ports(gold), work / "decide",
                     frame={k: params[k] for k in ("MaxWidth", "MaxHeight")},
                     budget=budget)
        if res.get("vcd") and Path(res["vcd"]).is_file():
            dest = cache_dir("mutate", "traces") / f"{m.id}-contract-{cache.stem[-16:]}.vcd"
            shutil.copyfile(res["vcd"], dest)
            res["vcd"] = str(dest)
        res |= {"id": m.id, "top": m.top, "config": m.config, "budget": budget,
                "frame_max": list(frame_max) if frame_max is not None else None,
                "params": params, "netlist_seconds": build,
                "miter": "masked by valid, legal inputs (irnuc.verif.miter)"}
    finally:
        shutil.rmtree(work, ignore_errors=True)
    write_text_atomic(cache, json.dumps(res, indent=1))
    return res


def label(res: Mapping) -> str:
    """One line for a decision: how the report and ``irnuc mutate`` name it."""
    v = res.get("verdict")
    how = f"{res.get('engine')}, {res.get('seconds', 0):.0f} s"
    if res.get("frame_max"):
        w, h = res["frame_max"]
        how += f", at MaxWidth {w} x MaxHeight {h}"
    if v == "equivalent":
        return f"proved equivalent (miter, masked by valid, legal inputs; {how})"
    if v == "different":
        return (f"different on legal inputs ({how}): {res.get('message', '')}"
                + (f"; trace {res['vcd']}" if res.get("vcd") else ""))
    return f"undecided by the miter ({how}): {res.get('message', '')}"


__all__ = ["BUDGET", "DEPTH", "FRAME_TOPS", "HARNESS", "Stream", "cached", "decide",
           "decide_mutant", "harness", "label", "mutant", "parameters", "streams"]
