// Shared types, layouts and constants of the irnuc RTL (docs/datapath.md, docs/rtl.md).
//
// Everything here is checked against the Python side by simulation:
// cocotb_tests/hdl/irnuc_pkg_probe.sv exposes the enum values, the coefficient word
// layout and the DPC reciprocal table, and cocotb_tests/test_pkg.py compares them with
// nuc_fixed.config (ROUNDING_MODES, OVERFLOW_MODES), nuc_fixed.memimage.pack_words and
// nuc_fixed.rtl.reciprocal_table.
package irnuc_pkg;

  // ---- NUC modes (module parameters Rounding and Overflow carry these codes) -----------
  typedef enum logic [1:0] {
    RoundTruncate = 2'd0,  // floor: s >>> F
    RoundHalfUp   = 2'd1,  // ties toward +infinity
    RoundHalfEven = 2'd2   // ties to the even integer
  } rounding_e;

  typedef enum logic [0:0] {
    OverflowSaturate = 1'b0,  // clamp to 0 .. 2^B - 1
    OverflowWrap     = 1'b1   // keep the low B bits
  } overflow_e;

  // ---- coefficient word, memory image version 1 ---------------------------------------
  // WW = GW + OW + 1 bits: [GW-1:0] gain (unsigned), [GW+OW-1:GW] offset (two's
  // complement), [GW+OW] bad flag. A package cannot take parameters, a class can: the
  // word type of given field widths is coef_word #(GW, OW)::word_t.
  function automatic int unsigned coef_word_bits(input int unsigned gain_bits,
                                                 input int unsigned offset_bits);
    return gain_bits + offset_bits + 32'd1;
  endfunction

  function automatic int unsigned coef_offset_lsb(input int unsigned gain_bits);
    return gain_bits;
  endfunction

  function automatic int unsigned coef_bad_bit(input int unsigned gain_bits,
                                               input int unsigned offset_bits);
    return gain_bits + offset_bits;
  endfunction

  /* verilator lint_off DECLFILENAME */  // a class inside the package: named as it reads, not as the file
  virtual class coef_word #(
    parameter int unsigned GainBits   = 1,
    parameter int unsigned OffsetBits = 1
  );
    typedef struct packed {
      logic                  bad;     // [GW+OW]
      logic [OffsetBits-1:0] offset;  // [GW+OW-1:GW], two's complement
      logic [GainBits-1:0]   gain;    // [GW-1:0], unsigned
    } word_t;
  endclass

  // ---- multipliers ---------------------------------------------------------------------
  // Operands are cut into chunks of MulChunkBits bits: an unsigned chunk then fits the
  // signed 18x18 multiplier of an ECP5 (MULT18X18D) and the 25x18 one of a 7-series
  // (DSP48E1), so every partial product is one DSP block with registered inputs and a
  // registered output (irnuc_mul_parts).
  localparam int unsigned MulChunkBits = 17;

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

  // Division by n = 1..8 as (M * R[n]) >> K with K = B + 6 and R[n] = ceil(2^K / n):
  // exact for every M < 2^(B+3) because M * (R[n] n - 2^K) < 2^(B+3) * 8 = 2^K
  // (cocotb_tests/test_dpc_core.py proves it for every M and n; cocotb_tests/test_pkg.py
  // reads this table back from simulation). R[0] = 0: n = 0 is never divided.
  function automatic int unsigned dpc_recip_shift(input int unsigned out_bits);
    return out_bits + 32'd6;
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
