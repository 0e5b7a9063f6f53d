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
  // ---- base correction method of method_dpc_top (module parameter Method; the order of nuc_fixed.config.BASE_METHODS)
  typedef enum logic [2:0] {
    MethodOnePoint = 3'd0,  // per-pixel offset, global gain register
    MethodTwoPoint = 3'd1,  // per-pixel gain and offset
    MethodPiecewise = 3'd2,  // two gains meeting at a per-pixel knee
    MethodQuadratic = 3'd3,  // gain, offset and a quadratic term
    MethodTcOffset = 3'd4,  // coefficients polynomial in the FPA reading
    MethodTableInterp = 3'd5  // two tables interpolated by a weight
  } method_e;
  localparam int unsigned MethodCount = 6;
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
  // ---- coef_one_point, version 2: coefficient word of one_point (the gain is a register)
  // (fields from bit 0 up: offset [OffsetBits], bad [1])
  function automatic int unsigned coef_one_point_bits(input int unsigned offset_bits);
    return offset_bits + 32'd1;
  endfunction
  function automatic int unsigned coef_one_point_offset_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned coef_one_point_bad_lsb(input int unsigned offset_bits);
    return offset_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class coef_one_point #(
    parameter int unsigned OffsetBits = 1
  );
    typedef struct packed {
      logic bad;  // defective-pixel flag
      logic [OffsetBits-1:0] offset;  // offset code, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- coef_piecewise, version 2: coefficient word of piecewise
  // (fields from bit 0 up: gain_lo [GainBits], gain_hi [GainBits], knee [KneeBits], bad [1])
  function automatic int unsigned coef_piecewise_bits(
    input int unsigned gain_bits,
    input int unsigned knee_bits);
    return gain_bits + gain_bits + knee_bits + 32'd1;
  endfunction
  function automatic int unsigned coef_piecewise_gain_lo_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned coef_piecewise_gain_hi_lsb(input int unsigned gain_bits);
    return gain_bits;
  endfunction
  function automatic int unsigned coef_piecewise_knee_lsb(input int unsigned gain_bits);
    return gain_bits + gain_bits;
  endfunction
  function automatic int unsigned coef_piecewise_bad_lsb(
    input int unsigned gain_bits,
    input int unsigned knee_bits);
    return gain_bits + gain_bits + knee_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class coef_piecewise #(
    parameter int unsigned GainBits = 1,
    parameter int unsigned KneeBits = 1
  );
    typedef struct packed {
      logic bad;  // defective-pixel flag
      logic [KneeBits-1:0] knee;  // knee, ADC codes, unsigned
      logic [GainBits-1:0] gain_hi;  // gain above the knee, unsigned
      logic [GainBits-1:0] gain_lo;  // gain at and below the knee, unsigned
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- quad_word, version 2: quadratic's second memory
  // (fields from bit 0 up: quad [QuadBits])
  function automatic int unsigned quad_word_bits(input int unsigned quad_bits);
    return quad_bits;
  endfunction
  function automatic int unsigned quad_word_quad_lsb();
    return 32'd0;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class quad_word #(
    parameter int unsigned QuadBits = 1
  );
    typedef struct packed {
      logic [QuadBits-1:0] quad;  // quadratic term at x = 2^A, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- tc_word1, version 2: tc_offset's offset polynomial of order 1
  // (fields from bit 0 up: tc1 [Tc1Bits])
  function automatic int unsigned tc_word1_bits(input int unsigned tc1_bits);
    return tc1_bits;
  endfunction
  function automatic int unsigned tc_word1_tc1_lsb();
    return 32'd0;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class tc_word1 #(
    parameter int unsigned Tc1Bits = 1
  );
    typedef struct packed {
      logic [Tc1Bits-1:0] tc1;  // offset change per v, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- tc_word2, version 2: tc_offset's offset polynomial of order 2
  // (fields from bit 0 up: tc1 [Tc1Bits], tc2 [Tc2Bits])
  function automatic int unsigned tc_word2_bits(
    input int unsigned tc1_bits,
    input int unsigned tc2_bits);
    return tc1_bits + tc2_bits;
  endfunction
  function automatic int unsigned tc_word2_tc1_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned tc_word2_tc2_lsb(input int unsigned tc1_bits);
    return tc1_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class tc_word2 #(
    parameter int unsigned Tc1Bits = 1,
    parameter int unsigned Tc2Bits = 1
  );
    typedef struct packed {
      logic [Tc2Bits-1:0] tc2;  // offset change per v^2, two's complement
      logic [Tc1Bits-1:0] tc1;  // offset change per v, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- tg_word1, version 2: tc_offset's gain polynomial of order 1 (tc_gain)
  // (fields from bit 0 up: tg1 [Tg1Bits])
  function automatic int unsigned tg_word1_bits(input int unsigned tg1_bits);
    return tg1_bits;
  endfunction
  function automatic int unsigned tg_word1_tg1_lsb();
    return 32'd0;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class tg_word1 #(
    parameter int unsigned Tg1Bits = 1
  );
    typedef struct packed {
      logic [Tg1Bits-1:0] tg1;  // gain change per v, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- tg_word2, version 2: tc_offset's gain polynomial of order 2 (tc_gain)
  // (fields from bit 0 up: tg1 [Tg1Bits], tg2 [Tg2Bits])
  function automatic int unsigned tg_word2_bits(
    input int unsigned tg1_bits,
    input int unsigned tg2_bits);
    return tg1_bits + tg2_bits;
  endfunction
  function automatic int unsigned tg_word2_tg1_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned tg_word2_tg2_lsb(input int unsigned tg1_bits);
    return tg1_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class tg_word2 #(
    parameter int unsigned Tg1Bits = 1,
    parameter int unsigned Tg2Bits = 1
  );
    typedef struct packed {
      logic [Tg2Bits-1:0] tg2;  // gain change per v^2, two's complement
      logic [Tg1Bits-1:0] tg1;  // gain change per v, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- frame_tc_offset, version 2: tc_offset's frame word (method_dpc_top's s_pix_frame_i, read with the frame's first pixel)
  // (fields from bit 0 up: reading [ReadingBits], t_ref [ReadingBits])
  function automatic int unsigned frame_tc_offset_bits(input int unsigned reading_bits);
    return reading_bits + reading_bits;
  endfunction
  function automatic int unsigned frame_tc_offset_reading_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned frame_tc_offset_t_ref_lsb(input int unsigned reading_bits);
    return reading_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class frame_tc_offset #(
    parameter int unsigned ReadingBits = 1
  );
    typedef struct packed {
      logic [ReadingBits-1:0] t_ref;  // the reading the polynomials are centred at, unsigned
      logic [ReadingBits-1:0] reading;  // the frame's FPA reading, unsigned
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
