// Shared types, layouts and constants of the irnuc RTL (docs/datapath.md, docs/rtl.md).
//
// The block between the irnuc-spec markers is generated from irnuc.nuc_fixed.rtl_spec, the
// one spec of what the RTL and Python share (constants, parameter ranges, mode encodings,
// word layouts): edit the spec and run `python -m irnuc.cosim.spec_files --write`;
// tests/test_rtl_spec.py fails while the block is stale. The functions below it are
// written by hand and mirrored by the spec's Python functions of the same names.
// Everything here is read back from the simulated RTL through cosim/hdl/irnuc_pkg_probe.sv
// (generated too) and compared with the spec by cocotb_tests/tb_pkg.py.
package irnuc_pkg;

  // irnuc-spec: begin (generated from irnuc.nuc_fixed.rtl_spec; do not edit)
  // Each module uses some of these: no warning for the others.
  /* verilator lint_off UNUSEDPARAM */
  // ---- constants
  // operand chunk of the multipliers (one DSP block per partial product)
  localparam int unsigned MulChunkBits = 17;
  // largest frame width and height, and line-buffer depth
  localparam int unsigned FrameDimMax = 65535;
  // DPC reciprocal shift K = OutBits + this
  localparam int unsigned DpcRecipGuardBits = 6;
  // widest NUC sum (int64 golden model, one spare bit)
  localparam int unsigned SumBitsMax = 62;
  // ---- legal parameter ranges (asserted by every module taking them)
  localparam int unsigned AdcBitsMin = 1;
  localparam int unsigned AdcBitsMax = 24;  // bits
  localparam int unsigned GainIntBitsMin = 0;
  localparam int unsigned GainIntBitsMax = 16;  // bits
  localparam int unsigned GainFracBitsMin = 0;
  localparam int unsigned GainFracBitsMax = 32;  // bits
  localparam int unsigned OffsetIntBitsMin = 1;
  localparam int unsigned OffsetIntBitsMax = 32;  // bits
  localparam int unsigned OffsetFracBitsMin = 0;
  localparam int unsigned OffsetFracBitsMax = 32;  // bits
  localparam int unsigned OutBitsMin = 1;
  localparam int unsigned OutBitsMax = 24;  // bits
  localparam int unsigned MaxWidthMin = 1;
  localparam int unsigned MaxWidthMax = 65535;  // pixels
  localparam int unsigned MaxHeightMin = 1;
  localparam int unsigned MaxHeightMax = 65535;  // pixels
  // ---- rounding of the NUC sum (module parameter Rounding)
  typedef enum logic [1:0] {
    RoundTruncate = 2'd0,  // floor: s >>> F
    RoundHalfUp = 2'd1,  // ties toward +infinity
    RoundHalfEven = 2'd2  // ties to the even integer
  } rounding_e;
  localparam int unsigned RoundingCount = 3;
  // ---- overflow of the NUC output (module parameter Overflow)
  typedef enum logic [0:0] {
    OverflowSaturate = 1'd0,  // clamp to 0 .. 2^B - 1
    OverflowWrap = 1'd1  // keep the low B bits
  } overflow_e;
  localparam int unsigned OverflowCount = 2;
  // ---- coef_word, version 1: coefficient word of the two-point NUC, memory image version 1
  // (fields from bit 0 up: gain [GainBits], offset [OffsetBits], bad [1])
  function automatic int unsigned coef_word_bits(
    input int unsigned gain_bits,
    input int unsigned offset_bits);
    return gain_bits + offset_bits + 32'd1;
  endfunction
  function automatic int unsigned coef_word_gain_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned coef_word_offset_lsb(input int unsigned gain_bits);
    return gain_bits;
  endfunction
  function automatic int unsigned coef_word_bad_lsb(
    input int unsigned gain_bits,
    input int unsigned offset_bits);
    return gain_bits + offset_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class coef_word #(
    parameter int unsigned GainBits = 1,
    parameter int unsigned OffsetBits = 1
  );
    typedef struct packed {
      logic bad;  // defective-pixel flag
      logic [OffsetBits-1:0] offset;  // offset code, two's complement
      logic [GainBits-1:0] gain;  // gain code, unsigned
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  /* verilator lint_on UNUSEDPARAM */
  // irnuc-spec: end

  // ---- multipliers ---------------------------------------------------------------------
  // Operands are cut into chunks of MulChunkBits bits: an unsigned chunk then fits the
  // signed 18x18 multiplier of an ECP5 (MULT18X18D) and the 25x18 one of a 7-series
  // (DSP48E1), so every partial product is one DSP block with registered inputs and a
  // registered output (irnuc_mul_parts).

  function automatic int unsigned mul_chunks(input int unsigned bits);
    return (bits + MulChunkBits - 32'd1) / MulChunkBits;
  endfunction

  function automatic int unsigned mul_parts(input int unsigned a_bits,
                                            input int unsigned b_bits);
    return mul_chunks(a_bits) * mul_chunks(b_bits);
  endfunction

  // ---- DPC -----------------------------------------------------------------------------
  // Frame and flush control of dpc_ctrl (see there).
  typedef enum logic [1:0] {
    DpcIdle  = 2'd0,  // no output owed; the next pixel starts a frame, its size is sampled
    DpcFrame = 2'd1,  // pixels of a frame are being taken
    DpcTail  = 2'd2,  // last pixel taken; W+1 outputs owed
    DpcFlush = 2'd3   // phantom items push the owed outputs out
  } dpc_state_e;

  // Division by n = 1..8 as (M * R[n]) >> K with K = B + DpcRecipGuardBits (6) and
  // R[n] = ceil(2^K / n): exact for every M < 2^(B+3) because
  // M * (R[n] n - 2^K) < 2^(B+3) * 8 = 2^K (cocotb_tests/test_dpc_core.py proves it for
  // every M and n; cocotb_tests/tb_pkg.py reads this table back from simulation).
  // R[0] = 0: n = 0 is never divided.
  function automatic int unsigned dpc_recip_shift(input int unsigned out_bits);
    return out_bits + DpcRecipGuardBits;
  endfunction

  function automatic longint unsigned dpc_recip(input int unsigned out_bits,
                                                input int unsigned n);
    longint unsigned num;
    if (n == 0) begin
      return 64'd0;
    end
    num = (64'd1 << dpc_recip_shift(out_bits)) + longint'(n) - 64'd1;
    return num / longint'(n);
  endfunction

endpackage
