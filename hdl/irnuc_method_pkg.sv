// Correction methods of the RTL (docs/datapath.md "Correction methods", docs/rtl.md
// "Methods"): the signed DSP chunking of the method multipliers, width helpers, the core
// kinds, and (generated from the method registry, nuc_fixed.methods) per method the widths
// of the two stream words of method_dpc_top, the neutral words of irnuc_axis_top, its core
// kind and the stages its tops compose it with.
//
// The method encoding (method_e) and every memory word layout (coef_word, coef_one_point,
// coef_piecewise, quad_word, tc_word1/2, tg_word1/2, frame_tc_offset) are generated into
// irnuc_pkg from the same registry; the stream words concatenate them in the order of
// MethodSpec.stream (irnuc.nuc_fixed.streams is their Python side, and
// cocotb_tests/tb_method.py reads the widths back from every simulated method_dpc_top).
package irnuc_method_pkg;

  import irnuc_pkg::*;

  // ---- multipliers with signed operands ---------------------------------------------------
  // Every partial product is one signed 18 x 18 DSP multiply (irnuc_dsp_mul): an operand is
  // cut into chunks of MulChunkBits (17) unsigned bits from bit 0 up; the top chunk of a
  // signed operand keeps its sign and may hold one bit more (17 bits and the sign), so a
  // signed operand of up to 18 bits is one chunk. For unsigned operands this is
  // irnuc_pkg::mul_chunks.
  function automatic int unsigned smul_chunks(input int unsigned bits, input bit is_signed);
    int unsigned low;
    low = is_signed ? bits - 32'd1 : bits;
    if (low == 0) begin
      return 32'd1;
    end
    return (low + MulChunkBits - 32'd1) / MulChunkBits;
  endfunction

  function automatic int unsigned smul_parts(input int unsigned a_bits, input bit a_signed,
                                             input int unsigned b_bits, input bit b_signed);
    return smul_chunks(a_bits, a_signed) * smul_chunks(b_bits, b_signed);
  endfunction

  // ---- widths of docs/datapath.md ("Widths of sums") --------------------------------------
  function automatic int unsigned max2(input int unsigned a, input int unsigned b);
    return (a > b) ? a : b;
  endfunction

  function automatic int unsigned max3(input int unsigned a, input int unsigned b,
                                       input int unsigned c);
    return max2(max2(a, b), c);
  endfunction

  // ---- neutral stream word and bad flags (irnuc_axis_top) -----------------------------------
  // NUC off and filler pixels (docs/integration.md "Methods"; Python
  // irnuc.nuc_fixed.streams.neutral_word, bad_mask): every gain field 1.0 (2^Gf, or the
  // largest code when the format has no integer bit), every other field 0; the bad flags'
  // bits. In the low bits of StreamWordMax (the widest stream word, tcgain14's, has 97).
  localparam int unsigned StreamWordMax = 128;

  function automatic logic [StreamWordMax-1:0] unity_gain(input int unsigned gain_int_bits,
                                                          input int unsigned gain_frac_bits);
    return (gain_int_bits > 0) ? (StreamWordMax'(1) << gain_frac_bits)
                               : ((StreamWordMax'(1) << (gain_int_bits + gain_frac_bits)) - 1);
  endfunction

  // ---- the sum of a base method's core (its kind: MethodSpec.core) ----------------------
  typedef enum logic [1:0] {
    CoreLin  = 2'd0,  // lin: g*x + o (nuc_core, core_sum)
    CoreQuad = 2'd1,  // quad: + q*(x/2^A)^2 (quad_core)
    CorePwl  = 2'd2   // pwl: L + g_sel*(x - k) (pwl_core)
  } core_kind_e;

  // irnuc-params: begin irnuc_method_pkg (generated from nuc_fixed.methods; do not edit)
  /* verilator lint_off UNUSEDSIGNAL */  // each method uses some arguments

  // The coefficient stream word of each method (s_coef of method_dpc_top): its
  // memories' words concatenated, the first at bit 0 (MethodSpec.stream).
  function automatic int unsigned coef_stream_bits(
    input method_e     method,
    input int unsigned offset_bits,
    input int unsigned gain_bits,
    input int unsigned knee_bits,
    input int unsigned quad_bits,
    input int unsigned tc_word_bits,
    input int unsigned tg_word_bits,
    input int unsigned th_word_bits);
    unique case (method)
      MethodOnePoint:    return coef_one_point_bits(offset_bits);
      MethodTwoPoint:    return coef_word_bits(gain_bits, offset_bits);
      MethodPiecewise:   return coef_piecewise_bits(gain_bits, knee_bits);
      MethodQuadratic:   return coef_word_bits(gain_bits, offset_bits) + quad_word_bits(quad_bits);
      MethodTcOffset:    return coef_word_bits(gain_bits, offset_bits) + tc_word_bits
                                + tg_word_bits;
      MethodTableInterp: return coef_word_bits(gain_bits, offset_bits) + coef_word_bits(gain_bits,
                                               offset_bits);
      default:           return coef_word_bits(gain_bits, offset_bits) + tc_word_bits + th_word_bits
                                + tg_word_bits;
    endcase
  endfunction

  // The frame word of each method (s_pix_frame_i, read with the frame's first
  // pixel; MethodSpec.frame_word): one unused bit where it has none.
  function automatic int unsigned frame_word_bits(
    input method_e     method,
    input int unsigned gain_bits,
    input int unsigned level_bits,
    input int unsigned reading_bits,
    input int unsigned weight_bits,
    input int unsigned housing_bits);
    unique case (method)
      MethodOnePoint:    return gain_bits;
      MethodTwoPoint:    return 32'd1;
      MethodPiecewise:   return level_bits;
      MethodQuadratic:   return 32'd1;
      MethodTcOffset:    return frame_tc_offset_bits(reading_bits);
      MethodTableInterp: return weight_bits;
      default:           return frame_tc_housing_bits(reading_bits, housing_bits);
    endcase
  endfunction

  // The coefficient word of NUC off and of a filler pixel (irnuc_axis_top):
  // every gain field 1.0 (unity_gain), every other field 0.
  function automatic logic [StreamWordMax-1:0] neutral_stream_word(
    input method_e     method,
    input int unsigned gain_int_bits,
    input int unsigned gain_frac_bits,
    input int unsigned offset_bits,
    input int unsigned gain_bits,
    input int unsigned knee_bits,
    input int unsigned quad_bits,
    input int unsigned tc_word_bits,
    input int unsigned tg_word_bits,
    input int unsigned th_word_bits);
    logic [StreamWordMax-1:0] one;
    one = unity_gain(gain_int_bits, gain_frac_bits);
    unique case (method)
      MethodOnePoint:    return '0;
      MethodTwoPoint:    return (one << (coef_word_gain_lsb()));
      MethodPiecewise:   return (one << (coef_piecewise_gain_lo_lsb()))
                              | (one << (coef_piecewise_gain_hi_lsb(gain_bits)));
      MethodQuadratic:   return (one << (coef_word_gain_lsb()));
      MethodTcOffset:    return (one << (coef_word_gain_lsb()));
      MethodTableInterp: return (one << (coef_word_gain_lsb()))
                              | (one << (coef_word_bits(gain_bits, offset_bits) + coef_word_gain_lsb()));
      default:           return (one << (coef_word_gain_lsb()));
    endcase
  endfunction

  // The bits of the coefficient word that are bad flags.
  function automatic logic [StreamWordMax-1:0] stream_bad_mask(
    input method_e     method,
    input int unsigned offset_bits,
    input int unsigned gain_bits,
    input int unsigned knee_bits,
    input int unsigned quad_bits,
    input int unsigned tc_word_bits,
    input int unsigned tg_word_bits,
    input int unsigned th_word_bits);
    logic [StreamWordMax-1:0] bit0;
    bit0 = StreamWordMax'(1);
    unique case (method)
      MethodOnePoint:    return (bit0 << (coef_one_point_bad_lsb(offset_bits)));
      MethodTwoPoint:    return (bit0 << (coef_word_bad_lsb(gain_bits, offset_bits)));
      MethodPiecewise:   return (bit0 << (coef_piecewise_bad_lsb(gain_bits, knee_bits)));
      MethodQuadratic:   return (bit0 << (coef_word_bad_lsb(gain_bits, offset_bits)));
      MethodTcOffset:    return (bit0 << (coef_word_bad_lsb(gain_bits, offset_bits)));
      MethodTableInterp: return (bit0 << (coef_word_bad_lsb(gain_bits, offset_bits)))
                              | (bit0 << (coef_word_bits(gain_bits, offset_bits) + coef_word_bad_lsb(gain_bits, offset_bits)));
      default:           return (bit0 << (coef_word_bad_lsb(gain_bits, offset_bits)));
    endcase
  endfunction

  // The frame word of NUC off: every gain field (one_point's gain) 1.0.
  function automatic logic [StreamWordMax-1:0] neutral_frame_word(
    input method_e     method,
    input int unsigned gain_int_bits,
    input int unsigned gain_frac_bits,
    input int unsigned gain_bits,
    input int unsigned level_bits,
    input int unsigned reading_bits,
    input int unsigned weight_bits,
    input int unsigned housing_bits);
    logic [StreamWordMax-1:0] one;
    one = unity_gain(gain_int_bits, gain_frac_bits);
    unique case (method)
      MethodOnePoint:    return (one << (32'd0));
      MethodTwoPoint:    return '0;
      MethodPiecewise:   return '0;
      MethodQuadratic:   return '0;
      MethodTcOffset:    return '0;
      MethodTableInterp: return '0;
      default:           return '0;
    endcase
  endfunction

  // The core kind of each method (MethodSpec.core): the sum core_sum and
  // method_core form.
  function automatic core_kind_e core_kind(input method_e method);
    unique case (method)
      MethodOnePoint:    return CoreLin;
      MethodTwoPoint:    return CoreLin;
      MethodPiecewise:   return CorePwl;
      MethodQuadratic:   return CoreQuad;
      MethodTcOffset:    return CoreLin;
      MethodTableInterp: return CoreLin;
      default:           return CoreLin;
    endcase
  endfunction

  // The plain method (MethodSpec.plain): without a stage, irnuc_axis_top builds it
  // around nuc_dpc_top, the core of memory image version 1.
  function automatic bit method_plain(input method_e method);
    return method == MethodTwoPoint;
  endfunction

  // The methods whose front is a pipeline ending in flops (MethodSpec
  // .rtl_front_registered: tc_poly, table_interp); the others pass through.
  function automatic bit front_registered(input method_e method);
    return method == MethodTcOffset || method == MethodTableInterp || method == MethodTcHousing;
  endfunction

  // The base methods method_drift_top composes blind_drift with (StageSpec.rtl_bases).
  function automatic bit blind_drift_composes(input method_e method);
    return method == MethodOnePoint || method == MethodTwoPoint;
  endfunction

  // The base methods method_ffc_top composes ffc with (StageSpec.rtl_bases).
  function automatic bit ffc_composes(input method_e method);
    return method == MethodOnePoint || method == MethodTwoPoint || method == MethodQuadratic
           || method == MethodTcOffset;
  endfunction

  /* verilator lint_on UNUSEDSIGNAL */
  // irnuc-params: end

endpackage
