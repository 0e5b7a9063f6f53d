"""Bulk co-simulation: a C++ harness around the Verilated ``nuc_dpc_top``,
``method_dpc_top`` or a stage top (``method_drift_top``, ``method_ffc_top``).

The harness (``harness/bulk_main.cpp``, Verilator ``--cc --exe``, no cocotb, no VPI)
reads raw binary stimulus, clocks the model itself and writes raw binary outputs; the
outputs are checked by the one scoreboard (:class:`~irnuc.cosim.scoreboard.TopScoreboard`).
``run_bulk(shards=N)`` splits the frames over N harness processes running in parallel
(each resets the DUT); ``check_bulk`` compares every output of every shard, first with a
direct numpy comparison and, when anything differs, with the scoreboard's triage. The
methods' stimulus (coefficient images per frame, frame words) and check are in
:mod:`irnuc.cosim.method_bulk`, on :func:`run_frames`; the stage tops' extra streams
(blind items; the FFC accumulator and corrections written out and read back by the
harness, which plays the external memory) are given to :func:`run_frames` as a
:class:`StageStreams`.
"""

from __future__ import annotations

import json
import re
import resource
import tempfile
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from irnuc.common.cache import cache_dir
from irnuc.common.errors import UserError
from irnuc.cosim.builds import BUILD_ARGS, FAST_ARGS, Build, build_digest, cached_build
from irnuc.cosim.scoreboard import ScoreResult, TopScoreboard
from irnuc.cosim.sources import ASSERT_DEFINE, hdl_sources, top_parameters, verilator_g
from irnuc.cosim.verilator import RtlError, verilator_env, verilator_executable
from irnuc.nuc_fixed import PipelineConfig, nuc_dpc_top
from irnuc.nuc_fixed.memimage import check_words
from irnuc.nuc_fixed.validate import InputError, check_frame_shape, int_array

#: The harness source.
BULK_HARNESS = Path(__file__).resolve().with_name("harness") / "bulk_main.cpp"
#: Name of the bulk executable inside its build folder.
BULK_EXE = "nuc_dpc_bulk"
#: The tops the harness drives and what its header defines for each (bulk_main.cpp).
BULK_TOPS = {"nuc_dpc_top": "", "method_dpc_top": "#define BULK_FRAME_WORD 1\n",
             "method_drift_top": "#define BULK_FRAME_WORD 1\n#define BULK_BLIND 1\n",
             "method_ffc_top": "#define BULK_FRAME_WORD 1\n#define BULK_FFC 1\n"}
#: Verilator's optimisation levels set on make's command line: -O2 for every object. Its
#: rules put them before the user flags for the model and the runtime (FAST_ARGS' -O2 then
#: wins) but after them for the harness (which was compiled at -Os), and the precompiled
#: header of ``cosim._objcache`` serves only files compiled alike.
_MAKE_OPT = ("OPT_FAST=-O2", "OPT_GLOBAL=-O2", "OPT_SLOW=-O2")
#: Output word of the harness: bit 31 sof, bit 30 eol, low bits the corrected code; with
#: codes of at most 14 bits a 16-bit word (out16=1), bit 15 sof, bit 14 eol: half the bytes
#: the harness writes and numpy reads.
_OUT16_MAX_BITS = 14


#: gcc's profile-guided optimisation of a ``train`` build (:func:`harness_build`): the
#: instrumented compile (counters updated by the one thread), then the compile from the
#: profile; the runtime objects and any function the workload never ran have none
#: (``-fprofile-partial-training`` keeps those optimised as without a profile).
PGO_GENERATE = ("-fprofile-generate", "-fprofile-update=single")
PGO_USE = ("-fprofile-use", "-fprofile-partial-training", "-Wno-missing-profile")

#: Port access shared by both harnesses (``harness_common.h``, found next to the .cpp).
HARNESS_COMMON = BULK_HARNESS.with_name("harness_common.h")


def harness_build(cfg: PipelineConfig, top: str, harness: Path, exe: str, *, header: str,
                  header_name: str, name: str, assertions: bool = True,
                  hdl_dir: Path | None = None,
                  check: Callable[[Path, str], None] | None = None,
                  train: Callable[[Build], object] | None = None, train_key: str = "",
                  verilator_args: Sequence[str] = ()) -> Build:
    """Build (cached) a C++ harness (Verilator ``--cc --exe``) around ``top`` for ``cfg``:
    the recipe of both bulk harnesses (this module's and :mod:`irnuc.cosim.axis_bulk`'s).

    ``header`` is written to ``<build_dir>/<header_name>``, which ``harness`` includes (the
    model's class, what the top has); the cache key covers it, the harness, the shared
    ``harness_common.h``, the HDL (``hdl_dir`` instead of ``hdl/``), the parameters and the
    options. ``name`` is the build folder's prefix; the executable is
    ``<build_dir>/<exe>``. ``assertions=False`` leaves the protocol assertions out.
    ``check(build_dir, top)`` runs on Verilator's output before it is compiled.

    ``train``: a profile-guided build (gcc PGO, :data:`PGO_GENERATE` / :data:`PGO_USE`):
    the harness and the model are compiled instrumented, ``train`` runs that build once (a
    short workload; ``train_key`` names it in the cache key: a digest of its stimulus),
    then both are compiled again with the profile it left. Verilator's output, the
    options and the code's meaning are those of the plain build; only gcc's layout,
    inlining and branch decisions follow the profile. Its folder is ``<name>-pgo-<key>``.

    ``verilator_args``: more Verilator options, after :data:`FAST_ARGS` (in the cache key
    and the folder's stamp): how ``benchmarks/bench_bulk_options.py`` measures Verilator's
    own options; every test and campaign builds without them.
    """
    params = top_parameters(top, cfg)
    base = list(BUILD_ARGS) if assertions else [a for a in BUILD_ARGS
                                                if a not in ("--assert", ASSERT_DEFINE)]
    pgo = [f"pgo={train_key}", *PGO_GENERATE, *PGO_USE] if train is not None else []
    vargs = [str(a) for a in verilator_args]
    key = build_digest(top, params, [*base, *FAST_ARGS, *vargs, "--exe", *_MAKE_OPT, header,
                                     *pgo],
                       [harness, HARNESS_COMMON], hdl_dir=hdl_dir)

    def make(build_dir: Path) -> None:
        from irnuc.common.process import run_child
        from irnuc.cosim import _objcache

        log = build_dir / "build.log"
        (build_dir / header_name).write_text(header)
        cmd = [str(verilator_executable()), "--cc", "--exe", "-Mdir", str(build_dir),
               "--top-module", top, "-o", exe, *base, *FAST_ARGS, *vargs, *verilator_g(params),
               *[str(p) for p in hdl_sources(top, hdl_dir)], str(harness)]
        # Verilator, the shared runtime objects, make (as the cocotb builds do). The harness
        # finds its header through the makefile's own ``-I.`` (make runs in build_dir) and
        # harness_common.h next to itself: a ``-I<build_dir>`` flag would make every build's
        # runtime-object key differ, so each build would compile Verilator's runtime again.
        proc = run_child(cmd, env=verilator_env(), log=log)
        if proc.returncode == 0 and check is not None:
            check(build_dir, top)
        def compile_(flags: Sequence[str], log_name: str) -> int:
            _objcache.seed(build_dir)
            extra = [f"USER_CPPFLAGS={' '.join(flags)}", f"USER_LDFLAGS={' '.join(flags)}"]
            return run_child(["make", "-j", "2", "-C", str(build_dir), "-f", f"V{top}.mk",
                              *_MAKE_OPT, *(extra if flags else [])], env=verilator_env(),
                             log=build_dir / log_name).returncode

        rc = proc.returncode
        if rc == 0 and train is None:
            rc = compile_((), "make.log")
            if rc == 0:
                _objcache.store(build_dir)
        elif rc == 0 and train is not None:
            # Instrumented build, the workload (its counts land in <object>.gcda beside
            # each object), then every object compiled again from the profile. The
            # runtime objects seeded from the cache stay plain (no profile: not hot) and
            # neither build's objects go back to the cache.
            rc = compile_(PGO_GENERATE, "make-pgo-generate.log")
            if rc == 0 and (build_dir / exe).is_file():
                train(Build(top=top, cfg=cfg, build_dir=build_dir, parameters=params,
                            waves=False))
                if not list(build_dir.glob("*.gcda")):
                    raise RtlError(f"the PGO training run of {build_dir} left no profile")
                for f in [*build_dir.glob("*.o"), *build_dir.glob("*.a"), build_dir / exe]:
                    f.unlink(missing_ok=True)
                rc = compile_(PGO_USE, "make.log")
        if rc != 0 or not (build_dir / exe).is_file():
            raise RtlError(f"Verilator build of the {harness.stem} harness failed (exit "
                           f"{rc}); see {log}")

    tag = ("" if assertions else "-noassert") + ("-pgo" if train is not None else "")
    build_dir = cached_build(f"{name}{tag}-{key}",
                             {"top": top, "harness": harness.name, "config": cfg.to_dict(),
                              "params": params, "args": [*FAST_ARGS, *vargs],
                              "assertions": assertions,
                              "pgo": train_key if train is not None else None}, make)
    return Build(top=top, cfg=cfg, build_dir=build_dir, parameters=params, waves=False)


def comb_outputs(model_header: str, root_source: str) -> list[str]:
    """The output ports a Verilated model assigns in its input-combinational ("ico")
    region, i.e. that follow an input without a register between them.

    ``model_header`` is the text of ``V<top>.h`` (its ``VL_OUT*(&name, ...)`` ports),
    ``root_source`` that of ``V<top>___024root__0.cpp`` (its ``___ico_sequent``
    functions). The bulk harness reads the outputs as the previous rising edge left them
    (bulk_main.cpp "Evals"), which needs this list empty.
    """
    outs = set(re.findall(r"VL_OUT\w*\(&(\w+),", model_header))
    found: set[str] = set()
    for body in re.findall(r"___ico_sequent\w*\([^)]*\)\s*\{(.*?)\n\}", root_source, re.S):
        found |= {n for n in re.findall(r"vlSelfRef\.(\w+)\s*(?:\[[^]]*\]\s*)?=[^=]", body)
                  if n in outs}
    return sorted(found)


def _check_registered_outputs(build_dir: Path, top: str) -> None:
    root = build_dir / f"V{top}___024root__0.cpp"
    comb = comb_outputs((build_dir / f"V{top}.h").read_text(),
                        root.read_text() if root.is_file() else "")
    if comb:
        raise RtlError(f"{top}: output port(s) {', '.join(comb)} follow an input "
                       "combinationally; the bulk harness needs every output registered "
                       "(bulk_main.cpp \"Evals\")")


def build_bulk(cfg: PipelineConfig, *, assertions: bool = True, top: str | None = None,
               hdl_dir: Path | None = None, train: Callable[[Build], object] | None = None,
               train_key: str = "", verilator_args: Sequence[str] = ()) -> Build:
    """Build (cached) the bulk harness of ``top`` for ``cfg``.

    ``top`` defaults to ``nuc_dpc_top`` for the two-point method, ``method_dpc_top``
    for the other base methods and the stage's top for a method with a stage
    (:func:`irnuc.cosim.synth.default_top`). The executable is
    ``<build_dir>/nuc_dpc_bulk``; the cache key also covers the harness source. A build
    takes about 10-15 s on 2 cores. ``assertions=False`` leaves the protocol assertions
    out: for measuring what they cost and for the throughput runs of
    ``benchmarks/bench_methods_cosim.py`` (still compared bit for bit on every output;
    every other co-simulation keeps them). ``hdl_dir`` replaces ``hdl/`` (a modified copy
    of the design: a test's method); part of the cache key through the files' contents.
    ``train`` / ``train_key``: a profile-guided build trained by ``train(build)`` (see
    :func:`harness_build`; :func:`irnuc.cosim.method_drift.pgo_build` for the methods);
    the default is the plain build every test uses. ``verilator_args``: more Verilator
    options (see :func:`harness_build`).
    """
    from irnuc.cosim.synth import default_top

    top = top or default_top(cfg)
    if top not in BULK_TOPS:
        raise UserError(f"top {top!r}: the bulk harness drives {', '.join(BULK_TOPS)}")
    # The harness includes bulk_top.h: the model's header, its class and its ports, the
    # generated scheduler it calls between the public evals and the clock's previous value
    # the scheduler compares with (bulk_main.cpp "Evals").
    root = f"V{top}___024root"
    header = (f'#include "V{top}.h"\n#include "{root}.h"\nusing BulkTop = V{top};\n'
              f"void {root}___eval({root}* vlSelf);\n"
              f"#define BULK_EVAL(model) {root}___eval((model)->rootp)\n"
              "#define BULK_CLOCK_WAS_LOW(model) "
              "((model)->rootp->__Vtrigprevexpr___TOP__clk_i__0 = 0)\n" + BULK_TOPS[top])
    tag = {"nuc_dpc_top": "", "method_dpc_top": "-method"}.get(top, "-" + top.split("_")[1])
    return harness_build(cfg, top, BULK_HARNESS, BULK_EXE, header=header,
                         header_name="bulk_top.h", name=f"{cfg.name}-bulk{tag}",
                         assertions=assertions, hdl_dir=hdl_dir,
                         check=_check_registered_outputs, train=train, train_key=train_key,
                         verilator_args=verilator_args)


@dataclass(frozen=True)
class BulkResult:
    """Outputs of one bulk run, in stream order (frames back to back, raster order).

    ``data`` holds the corrected codes (int64), ``sof`` and ``eol`` the output markers
    (bool). ``cycles`` counts clock cycles from reset release to the last output;
    ``first_out_cycle``/``last_out_cycle`` bracket the outputs (at full rate without
    bubbles ``last - first + 1`` equals the number of outputs); ``extra`` counts outputs
    that still appeared in ``W + 64`` idle cycles after the last expected one (must be 0);
    ``frame_err`` is the DUT's sticky ``frame_err_o``; ``sim_seconds`` is the wall time of
    the harness process (reading stimulus, simulating, writing outputs).
    """

    data: np.ndarray
    sof: np.ndarray
    eol: np.ndarray
    frame_shape: tuple[int, int]
    cycles: int
    first_out_cycle: int
    last_out_cycle: int
    extra: int
    frame_err: bool
    inputs_taken: tuple[int, int]
    sim_seconds: float
    stall_cycles: int = 0  # output back-pressured between the first and the last output
    shards: int = 1  # harness processes that ran in parallel (run_bulk's ``shards``)
    #: Items the stage's inputs took: (s_blind, 0) or (s_foff, s_acc).
    stage_taken: tuple[int, int] = (0, 0)
    #: method_ffc_top: the m_acc and m_foff words written, in order (uint64).
    acc: np.ndarray | None = None
    foff: np.ndarray | None = None
    #: CPU time (user + system) of the harness processes, s: the cost of the run apart
    #: from the other work on a shared machine (wall time ``sim_seconds`` includes it).
    cpu_seconds: float = 0.0


def _children_cpu() -> float:
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


@dataclass(frozen=True)
class StageStreams:
    """The stage top's extra streams for :func:`run_frames` (``frame_info`` then has the
    stage's columns, docs/cosim.md "Bulk harness").

    ``blind``: method_drift_top's ``s_blind`` items (uint64), frame after frame, with each
    frame's item count in ``frame_info[:, 2]``; ``registers``: ``blind_ref`` and
    ``drift_gain`` as two's complement bit patterns. method_ffc_top: ``outputs`` m_pix
    outputs (held frames have none), ``acc_n`` / ``foff_n`` m_acc / m_foff words expected;
    ``frame_info[:, 2:5]`` hold the shutter flag and the write-back frames s_foff and s_acc
    read (k + 1, 0: none).
    """

    blind: np.ndarray | None = None
    registers: dict[str, int] = field(default_factory=dict)
    outputs: int | None = None
    acc_n: int = 0
    foff_n: int = 0

    @property
    def ffc(self) -> bool:
        return self.blind is None and self.outputs is not None


def _check_percent(name: str, value: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 99:
        raise UserError(f"{name} = {value!r} is outside the allowed range 0..99 (percent, int)")
    return value


def run_bulk(bld: Build, raw: np.ndarray, words: np.ndarray, *, idle_percent: int = 0,
             stall_percent: int = 0, seed: int = 1,
             work_dir: Path | None = None, shards: int = 1,
             public_eval: bool = False) -> BulkResult:
    """Stream frames through the bulk harness of :func:`build_bulk` and read the outputs.

    Parameters
    ----------
    bld : Build
        From :func:`build_bulk`; its configuration fixes the widths.
    raw : integer array_like, (H, W) or (N, H, W)
        Raw codes in [0, 2^A - 1]; N frames are streamed back to back.
    words : integer array_like, (H, W)
        Coefficient words (docs/datapath.md layout), sent again for every frame.
    idle_percent, stall_percent : int
        Percent (0..99) of cycles each input source stays idle / the output is
        back-pressured, drawn in the harness from ``seed``. 0 = full rate.
    seed : int
        Seed (0..2^64-1) of the harness's generator; same inputs and seed -> same cycles.
    work_dir : Path, optional
        Folder for the binary files; a temporary folder in the irnuc cache by default.
    shards : int
        Harness processes run in parallel (1..16), each on a contiguous share of the
        frames with its own reset (shard ``i`` uses seed ``seed + i``); the outputs are
        joined in stream order. With several shards ``cycles``, ``stall_cycles`` and the
        output span ``last_out_cycle - first_out_cycle + 1`` are sums over the shards (as
        if their output phases ran back to back), so ``last - first + 1 = outputs +
        stall_cycles`` still holds when no cycle is lost. At most one shard per frame.
    public_eval : bool
        Every eval through the model's public ``eval()`` (the harness's previous path, a
        quarter slower; the baseline of ``benchmarks/bench_methods_cosim.py``); the same
        outputs and cycles either way (bulk_main.cpp "Evals").

    Returns
    -------
    BulkResult
        Compare it with :func:`check_bulk`.
    """
    if not isinstance(bld, Build) or not (bld.build_dir / BULK_EXE).is_file():
        raise UserError(f"{bld!r} is not a bulk build; use cosim.build_bulk(cfg)")
    if bld.top != "nuc_dpc_top":
        raise UserError(f"{bld.top} takes its streams from irnuc.cosim.method_bulk.run_method_bulk")
    cfg = bld.cfg
    x = int_array("raw", raw, 0, (1 << cfg.adc_bits) - 1)
    h, w = check_frame_shape("raw", x.shape, cfg)
    wd = check_words(words, cfg)
    if wd.shape != (h, w):
        raise InputError(f"words has shape {wd.shape} but the frames of raw are {(h, w)}")
    frames = x.reshape(-1, h, w)
    return run_frames(bld, frames, np.asarray(wd, dtype=np.uint64)[None, :, :, None],
                      np.zeros((frames.shape[0], 2), np.uint64), idle_percent=idle_percent,
                      stall_percent=stall_percent, seed=seed, work_dir=work_dir, shards=shards,
                      public_eval=public_eval)


def run_frames(bld: Build, frames: np.ndarray, images: np.ndarray, frame_info: np.ndarray, *,
               idle_percent: int = 0, stall_percent: int = 0, seed: int = 1,
               work_dir: Path | None = None, shards: int = 1,
               stage: StageStreams | None = None, public_eval: bool = False,
               wrapper: Sequence[str] = ()) -> BulkResult:
    """The harness on checked stimulus: ``frames`` (N, H, W) raw codes, ``images``
    (M, H, W, L) coefficient words as L uint64 limbs (bit 0 first), ``frame_info`` (N, C):
    the image each frame streams, its frame word and (stage tops) the stage's columns;
    ``stage``: the stage top's streams. Other arguments as :func:`run_bulk`; the FFC
    top runs in one process (its state crosses frames). ``wrapper``: a command the harness
    runs under (a profiler: :mod:`irnuc.cosim.bulk_profile`); it must start no process of
    its own."""
    cfg = bld.cfg
    _check_percent("idle_percent", idle_percent)
    _check_percent("stall_percent", stall_percent)
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 1 << 64:
        raise UserError(f"seed = {seed!r} is outside the allowed range 0..2^64-1 (int)")
    if isinstance(shards, bool) or not isinstance(shards, int) or not 1 <= shards <= 16:
        raise UserError(f"shards = {shards!r} is outside the allowed range 1..16 (int)")
    if work_dir is None:
        with tempfile.TemporaryDirectory(dir=cache_dir("bulk")) as tmp:
            return run_frames(bld, frames, images, frame_info, idle_percent=idle_percent,
                              stall_percent=stall_percent, seed=seed, work_dir=Path(tmp),
                              shards=shards, stage=stage, public_eval=public_eval,
                              wrapper=wrapper)
    if stage is not None and stage.ffc and shards != 1:
        raise UserError(f"shards = {shards}: the FFC top's state crosses frames; use shards = 1")
    n_frames, h, w = frames.shape
    limbs = images.shape[-1]
    pix_dtype = np.uint16 if cfg.adc_bits <= 16 else np.uint32
    work_dir = Path(work_dir)
    work_dir.mkdir(parents=True, exist_ok=True)
    coef_file = work_dir / "coef.bin"
    np.ascontiguousarray(images, dtype="<u8").tofile(coef_file)
    # One pixel file and one frame file for every shard: shard i starts at its first frame
    # (the harness's skip=), so nothing is copied per shard once the clock runs.
    pix_file, info_file = work_dir / "pix.bin", work_dir / "frames.bin"
    np.ascontiguousarray(frames, dtype=pix_dtype).tofile(pix_file)
    np.ascontiguousarray(frame_info, dtype="<u8").tofile(info_file)
    parts = [p for p in np.array_split(np.arange(n_frames), shards) if p.size]
    cols = frame_info.shape[1]
    opts = [] if cols == 2 else [f"cols={cols}"]
    out16 = cfg.out_bits <= _OUT16_MAX_BITS
    if out16:
        opts.append("out16=1")
    if public_eval:
        opts.append("eval=public")
    if stage is not None:
        opts += [f"{k}={int(v)}" for k, v in stage.registers.items()]
    blind_at = None
    if stage is not None and stage.blind is not None:
        blind_at = np.concatenate([[0], np.cumsum(frame_info[:, 2].astype(np.int64))])
    from irnuc.common.process import run_child

    def one(cmd: list[str]) -> dict:
        # Its own process group; dies with irnuc. The harness starts no process itself.
        proc = run_child(cmd, capture=True, single_process=True)
        lines = proc.stdout.strip().splitlines()
        info = json.loads(lines[-1]) if lines and lines[-1].startswith("{") else {}
        if proc.returncode != 0 or "error" in info:
            raise RtlError(f"bulk harness failed (exit {proc.returncode}): "
                           f"{info or proc.stdout}\n{proc.stderr}")
        return info

    outs, jobs = [], []
    t0 = time.perf_counter()
    # Children's CPU counts once they are reaped: only the harnesses run (and are waited
    # for) between the two readings; a concurrent run in another thread would add its own.
    cpu0 = _children_cpu()
    # Threads only wait for the harnesses (a drift shard's blind file is written first).
    with ThreadPoolExecutor(len(parts)) as pool:
        for i, part in enumerate(parts):
            out_file = work_dir / f"out{i}.bin"
            out_file.unlink(missing_ok=True)  # never read a previous run's outputs
            extra = [*opts, f"skip={int(part[0])}"] if part[0] else list(opts)
            if blind_at is not None and stage is not None and stage.blind is not None:
                blind_file = work_dir / f"blind{i}.bin"
                np.ascontiguousarray(stage.blind[blind_at[part[0]]:blind_at[part[-1] + 1]],
                                     dtype="<u8").tofile(blind_file)
                extra.append(f"blind={blind_file}")
            if stage is not None and stage.ffc:
                (work_dir / "acc.bin").unlink(missing_ok=True)
                (work_dir / "foff.bin").unlink(missing_ok=True)
                extra += [f"outputs={stage.outputs}", f"acc={work_dir / 'acc.bin'}",
                          f"acc_n={stage.acc_n}", f"foff={work_dir / 'foff.bin'}",
                          f"foff_n={stage.foff_n}"]
            if i == 0:
                t0 = time.perf_counter()
            jobs.append(pool.submit(one, [
                *[str(a) for a in wrapper], str(bld.build_dir / BULK_EXE), str(pix_file),
                str(coef_file), str(out_file),
                str(part.size * h * w), str(w), str(h), str(np.dtype(pix_dtype).itemsize),
                str(idle_percent), str(stall_percent), str((seed + i) % (1 << 64)),
                str(info_file), str(limbs), *extra]))
            outs.append(out_file)
        infos = [j.result() for j in jobs]
    sim_seconds = time.perf_counter() - t0
    cpu_seconds = _children_cpu() - cpu0
    ffc = stage is not None and stage.ffc
    word = np.dtype("<u2" if out16 else "<u4")
    out = np.concatenate([np.fromfile(f, dtype=word) for f in outs])
    sof_bit = word.itemsize * 8 - 1
    mask = out.dtype.type((1 << cfg.out_bits) - 1)
    spans = sum(int(i["last_out_cycle"]) - int(i["first_out_cycle"]) for i in infos)
    first = int(infos[0]["first_out_cycle"])
    return BulkResult(
        data=(out & mask).astype(np.int64),
        sof=(out >> out.dtype.type(sof_bit)).astype(bool),
        eol=((out >> out.dtype.type(sof_bit - 1)) & out.dtype.type(1)).astype(bool),
        frame_shape=(h, w), cycles=sum(int(i["cycles"]) for i in infos),
        first_out_cycle=first, last_out_cycle=first + spans + len(infos) - 1,
        extra=sum(int(i["extra"]) for i in infos),
        frame_err=any(bool(i["frame_err"]) for i in infos),
        inputs_taken=(sum(int(i["inputs_taken"][0]) for i in infos),
                      sum(int(i["inputs_taken"][1]) for i in infos)),
        sim_seconds=sim_seconds, stall_cycles=sum(int(i.get("stall_cycles", 0)) for i in infos),
        shards=len(infos),
        stage_taken=(sum(int(i["inputs_taken"][2]) for i in infos),
                     sum(int(i["inputs_taken"][3]) for i in infos)),
        acc=np.fromfile(work_dir / "acc.bin", dtype="<u8") if ffc else None,
        foff=np.fromfile(work_dir / "foff.bin", dtype="<u8") if ffc else None,
        cpu_seconds=cpu_seconds,
    )


def exact_stream(res: BulkResult, exp: np.ndarray) -> bool:
    """The fast path of every bulk check: every code, ``sof`` exactly on each frame's first
    pixel, ``eol`` exactly on each line's last, nothing extra, no framing error."""
    h, w = res.frame_shape
    if exp.size != res.data.size or res.extra or res.frame_err:
        return False
    sof_at = np.flatnonzero(res.sof)
    eol = res.eol.reshape(-1, w)
    return bool(np.array_equal(res.data, exp)
                and np.array_equal(sof_at, np.arange(0, exp.size, h * w))
                and eol[:, -1].all() and not eol[:, :-1].any())


def flag_lines(res: BulkResult) -> list[str]:
    """Error lines of the harness's own findings (extra outputs, frame_err_o)."""
    lines = []
    if res.extra:
        lines.append(f"{res.extra} extra output(s) in the idle cycles after the stream")
    if res.frame_err:
        lines.append("frame_err_o is set (an input marker or the frame size was wrong)")
    return lines


def check_bulk(res: BulkResult, raw: np.ndarray, words: np.ndarray, golden: PipelineConfig,
               expected: np.ndarray | None = None, max_report: int = 10) -> ScoreResult:
    """Check a bulk run with the scoreboard, bit for bit.

    Every output's code, ``sof`` and ``eol`` are compared in stream order; outputs that
    came after the expected ones (also during the harness's idle tail) count as extra,
    and a set ``frame_err_o`` is reported as an error line.

    Parameters
    ----------
    res : BulkResult
    raw, words : ndarray
        The stimulus given to :func:`run_bulk`.
    golden : PipelineConfig
        Configuration of the golden model (normally the DUT's).
    expected : ndarray, optional
        ``irnuc.nuc_fixed.nuc_dpc_top(raw, words, golden)`` if already computed.
    max_report : int
        Mismatches described in full (the counts are always complete).
    """
    raw = np.asarray(raw)
    h, w = raw.shape[-2:]
    if expected is None:
        expected = nuc_dpc_top(raw.reshape(-1, h, w), words, golden)
    exp = np.asarray(expected, dtype=np.int64).ravel()
    if exact_stream(res, exp):
        return ScoreResult(compared=exp.size, mismatches=0, missing=0, extra=0, lines=[])
    sb = TopScoreboard(golden, max_report=max_report)
    sb.expect_frames(raw, words, expected)
    sb.observe_arrays(data=res.data, sof=res.sof, eol=res.eol)
    r = sb.result()
    return ScoreResult(compared=r.compared, mismatches=r.mismatches, missing=r.missing,
                       extra=r.extra + res.extra, lines=[*r.lines, *flag_lines(res)],
                       first_index=r.first_index, flag_errors=int(res.frame_err))
