"""The contract miter of ``irnuc mutate --decide`` (``irnuc.verif.miter``): output payload
compared only while its valid is 1, the input contract assumed.

Hand-written pairs of tiny modules (a one-stage register of a pixel stream with a frame
size, named like a top's netlists ``<top>__gold`` / ``<top>__mut``), each decided in a few
seconds:

* differ only in the payload while valid is 0: proved equivalent (and different for the
  unmasked miter of ``irnuc mutate --auto``, so the masking is what decides it);
* differ while valid is 1: different, with a trace;
* differ only when a pixel is taken with width 0 (an illegal size): equivalent; with width
  1 (legal): different;
* differ only when the source drops valid before ready (against the AXI4-Stream rule):
  equivalent.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from irnuc.verif import miter

TOP = "tiny"
PORTS = [("clk_i", "input", 1), ("rst_ni", "input", 1), ("frame_width_i", "input", 3),
         ("frame_height_i", "input", 3), ("s_pix_valid_i", "input", 1),
         ("s_pix_ready_o", "output", 1), ("s_pix_data_i", "input", 4),
         ("s_pix_eol_i", "input", 1), ("m_pix_valid_o", "output", 1),
         ("m_pix_ready_i", "input", 1), ("m_pix_data_o", "output", 4),
         ("m_pix_eol_o", "output", 1), ("frame_err_o", "output", 1)]


def tiny(tag: str, load: str = "take", data: str = "s_pix_data_i") -> str:
    """A register stage of the pixel stream (module ``tiny__<tag>``): the output register
    loads ``data`` when ``load`` is true; ``frame_err_o`` flags a width of 0 at a take
    (a sticky error, as the tops have)."""
    return f"""
module {TOP}__{tag} (
  input  wire       clk_i, rst_ni,
  input  wire [2:0] frame_width_i, frame_height_i,
  input  wire       s_pix_valid_i,
  output wire       s_pix_ready_o,
  input  wire [3:0] s_pix_data_i,
  input  wire       s_pix_eol_i,
  output reg        m_pix_valid_o,
  input  wire       m_pix_ready_i,
  output reg  [3:0] m_pix_data_o,
  output reg        m_pix_eol_o,
  output reg        frame_err_o
);
  wire take = s_pix_valid_i && s_pix_ready_o;
  reg  vq;  // the previous cycle's valid (the rule-breaking pair uses it)
  assign s_pix_ready_o = !m_pix_valid_o || m_pix_ready_i;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      m_pix_valid_o <= 1'b0; frame_err_o <= 1'b0; vq <= 1'b0;
    end else begin
      vq <= s_pix_valid_i && !s_pix_ready_o;
      if (s_pix_ready_o) m_pix_valid_o <= s_pix_valid_i;
      if (take && frame_width_i == 3'd0) frame_err_o <= 1'b1;
    end
  always @(posedge clk_i)
    if ({load}) begin
      m_pix_data_o <= {data};
      m_pix_eol_o  <= s_pix_eol_i;
    end
endmodule
"""


def decide(tmp: Path, gate: str, frame: bool = True) -> dict:
    tmp.mkdir(parents=True, exist_ok=True)
    g, m = tmp / "gold.v", tmp / "mut.v"
    g.write_text(tiny("gold"))
    m.write_text(gate)
    return miter.decide(g, m, TOP, PORTS, tmp / "decide",
                        frame={"MaxWidth": 4, "MaxHeight": 4} if frame else None, budget=60)


def test_streams_and_harness() -> None:
    s = {x.name: x for x in miter.streams(PORTS)}
    assert set(s) == {"s_pix", "m_pix"}
    assert s["m_pix"].output and s["m_pix"].payload == ("m_pix_data_o", "m_pix_eol_o")
    assert not s["s_pix"].output and s["s_pix"].payload == ("s_pix_data_i", "s_pix_eol_i")
    text = miter.harness(TOP, PORTS, {"MaxWidth": 4, "MaxHeight": 4})
    # valids, readies and the error flag always; the payload under the valid
    assert ("a_control: assert ({gold_s_pix_ready_o, gold_m_pix_valid_o, gold_frame_err_o} "
            "== {gate_s_pix_ready_o, gate_m_pix_valid_o, gate_frame_err_o})") in text
    assert "if (gold_m_pix_valid_o) begin\n        a_m_pix_payload: assert" in text
    assert "frame_width_i <= 3'd4" in text and ".Assume(1'b1)" in text


def test_payload_while_invalid_is_masked(tmp_path) -> None:
    # The mutant loads its output register whenever it is free, valid or not: its payload
    # differs from the original's only while m_pix_valid_o is 0.
    gate = tiny("mut", load="s_pix_ready_o", data="s_pix_data_i ^ {4{!s_pix_valid_i}}")
    res = decide(tmp_path / "masked", gate)
    assert res["verdict"] == "equivalent", res
    # The unmasked miter (irnuc mutate --auto's) finds them different.
    from irnuc.cosim import formal

    (tmp_path / "plain").mkdir()
    g, m = tmp_path / "plain" / "gold.v", tmp_path / "plain" / "mut.v"
    g.write_text(tiny("gold"))
    m.write_text(gate)
    plain = formal.equivalence(g, m, TOP, PORTS, tmp_path / "plain" / "eq", timeout=60)
    assert plain["verdict"] == "different", plain


def test_payload_while_valid_differs(tmp_path) -> None:
    res = decide(tmp_path, tiny("mut", data="s_pix_data_i ^ {3'd0, s_pix_eol_i}"))
    assert res["verdict"] == "different", res
    assert res["failed"] == ["a_m_pix_payload"] and res["step"] is not None
    assert res["vcd"] and Path(res["vcd"]).is_file()


def test_frame_size_contract(tmp_path) -> None:
    # Only a pixel taken at width 0 (illegal) comes out otherwise: equivalent under the
    # contract, different without the frame-size assumption.
    illegal = tiny("mut", data="s_pix_data_i ^ {4{frame_width_i == 3'd0}}")
    assert decide(tmp_path / "a", illegal)["verdict"] == "equivalent"
    assert decide(tmp_path / "b", illegal, frame=False)["verdict"] == "different"
    # At width 1 (legal) it is a difference.
    legal = tiny("mut", data="s_pix_data_i ^ {4{frame_width_i == 3'd1}}")
    res = decide(tmp_path / "c", legal)
    assert res["verdict"] == "different" and res["failed"] == ["a_m_pix_payload"], res


def test_input_stream_rule_assumed(tmp_path) -> None:
    # The mutant's output differs only after the source dropped valid before ready (vq:
    # stalled last cycle; not valid now): the AXI4-Stream rule excludes it.
    gate = tiny("mut").replace(
        "if (take && frame_width_i == 3'd0) frame_err_o <= 1'b1;",
        "if ((take && frame_width_i == 3'd0) || (vq && !s_pix_valid_i)) frame_err_o <= 1'b1;")
    assert gate != tiny("mut")
    assert decide(tmp_path, gate)["verdict"] == "equivalent"


def test_cli_decide_bad_id(tmp_path) -> None:
    def run(*args: str) -> subprocess.CompletedProcess:
        irnuc = Path(sys.executable).with_name("irnuc")
        return subprocess.run([str(irnuc), "mutate", *args, "--out", str(tmp_path / "out")],
                              capture_output=True, text=True)

    for args, want in ((("--decide", "ctrl_idle_read_cl"), "--decide ctrl_idle_read_cl: no "
                                                           "such mutant"),
                       (("--decide", "iw_bit_position"), "--decide iw_bit_position: its top "
                                                         "interp_weight has no input contract"),
                       (("--decide", "ctrl_idle_read_col", "--budget", "1"), "--budget 1 is "
                                                                             "outside")):
        p = run(*args)
        assert p.returncode == 2, p.stderr
        assert want in p.stderr and "Traceback" not in p.stderr
        assert len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("mid", ["ctrl_idle_read_col", "pwl_segment_at_knee"])
def test_catalogue_equivalents_have_a_contract(mid) -> None:
    m = miter.mutant(mid)
    assert m.equivalent and m.top in miter.FRAME_TOPS


def test_campaign_reads_the_decisions(monkeypatch) -> None:
    # The catalogue's equivalents as the report shows them: proved, different (then a
    # survivor), or argued.
    from irnuc.verif import mutate

    base = {"file": "dpc_ctrl.sv", "what": "w", "config": "minimal", "killed_by": None,
            "message": ""}
    results = [base | {"id": mid, "status": "equivalent", "equivalent": "the argument"}
               for mid in ("ctrl_idle_read_col", "pwl_segment_at_knee")]
    results.append(base | {"id": "ctrl_read_col_late", "status": "killed", "killed_by": "t"})
    decisions = {"ctrl_idle_read_col": {"verdict": "equivalent", "engine": "pdr",
                                        "seconds": 12.0, "frame_max": None}}
    monkeypatch.setattr(miter, "cached", lambda m: decisions.get(m.id))
    out = {r["id"]: r for r in mutate.with_decisions(results)}
    assert out["ctrl_idle_read_col"]["equivalent"] == (
        "proved equivalent (miter, masked by valid, legal inputs; pdr, 12 s); argument: "
        "the argument")
    assert out["pwl_segment_at_knee"]["equivalent"] == "argued: the argument"
    assert out["ctrl_read_col_late"] == results[2]
    decisions["pwl_segment_at_knee"] = {"verdict": "different", "engine": "pdr",
                                        "seconds": 3.0, "message": "a_m_pix_payload differs",
                                        "vcd": "/x.vcd", "frame_max": [4, 4]}
    out = {r["id"]: r for r in mutate.with_decisions(results)}
    assert out["pwl_segment_at_knee"]["status"] == "survived"
    assert "at MaxWidth 4 x MaxHeight 4" in out["pwl_segment_at_knee"]["message"]
    s = mutate.summarize(mutate.with_decisions(results))
    assert (s["killed"], s["survived"], s["equivalent"]) == (1, 1, 1)
    assert results[1]["status"] == "equivalent"  # the cached results are not changed
