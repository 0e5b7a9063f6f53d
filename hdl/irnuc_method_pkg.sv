// Correction methods of the RTL (docs/datapath.md "Correction methods", docs/rtl.md
// "Methods"): the signed DSP chunking of the method multipliers, width helpers, and the
// widths of method_dpc_top's two stream words per method.
//
// The method encoding (method_e) and every memory word layout (coef_word, coef_one_point,
// coef_piecewise, quad_word, tc_word1/2, tg_word1/2, frame_tc_offset) are generated into
// irnuc_pkg from irnuc.nuc_fixed.rtl_spec, whose layouts tests/test_rtl_spec.py checks
// against PipelineConfig.memories of every method configuration; the stream words below
// concatenate them in that order (irnuc.cosim.stream is their Python side, and
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

  // ---- coefficient stream word of method_dpc_top, per method ------------------------------
  // One word per pixel: the method's calibration memories concatenated, the first memory of
  // PipelineConfig.memories at bit 0; table_interp carries table j at bit 0 and table j + 1
  // above it (the two tables the frame's weight interpolates):
  //   one_point     coef_one_point
  //   two_point     coef_word
  //   piecewise     coef_piecewise
  //   quadratic     coef_word | quad_word
  //   tc_offset     coef_word | tc_word1/2 (tc_order) | tg_word1/2 (with tc_gain)
  //   table_interp  coef_word (table j) | coef_word (table j + 1)
  function automatic int unsigned coef_stream_bits(
    input method_e     method,
    input int unsigned gain_bits,
    input int unsigned offset_bits,
    input int unsigned knee_bits,
    input int unsigned quad_bits,
    input int unsigned tc_word_bits,
    input int unsigned tg_word_bits);
    unique case (method)
      MethodOnePoint:  return coef_one_point_bits(offset_bits);
      MethodTwoPoint:  return coef_word_bits(gain_bits, offset_bits);
      MethodPiecewise: return coef_piecewise_bits(gain_bits, knee_bits);
      MethodQuadratic: return coef_word_bits(gain_bits, offset_bits) + quad_word_bits(quad_bits);
      MethodTcOffset:  return coef_word_bits(gain_bits, offset_bits) + tc_word_bits
                              + tg_word_bits;
      default:         return 32'd2 * coef_word_bits(gain_bits, offset_bits);
    endcase
  endfunction

  // ---- frame word of method_dpc_top (s_pix_frame_i), per method -------------------------
  // Sampled with the first pixel of every frame (sof) and used for all of its pixels:
  //   one_point     the gain register (U Gi.Gf)
  //   piecewise     the level register (U Li.Lf)
  //   tc_offset     frame_tc_offset: reading, t_ref
  //   table_interp  the weight (U Wi.Wf, at most 2^Wf)
  //   two_point, quadratic: none (one unused bit)
  function automatic int unsigned frame_word_bits(
    input method_e     method,
    input int unsigned gain_bits,
    input int unsigned level_bits,
    input int unsigned reading_bits,
    input int unsigned weight_bits);
    unique case (method)
      MethodOnePoint:    return gain_bits;
      MethodPiecewise:   return level_bits;
      MethodTcOffset:    return frame_tc_offset_bits(reading_bits);
      MethodTableInterp: return weight_bits;
      default:           return 32'd1;
    endcase
  endfunction

  // ---- neutral stream word and bad flags, per method (irnuc_axis_top) -------------------
  // NUC off and filler pixels (docs/integration.md "Methods"; Python
  // irnuc.nuc_fixed.axis.neutral_word, bad_mask): every gain field 1.0 (2^Gf, or the largest
  // code when the format has no integer bit), every other field 0; the bad flags' bits. In
  // the low bits of StreamWordMax (the widest stream word, tcgain14's, has 97).
  localparam int unsigned StreamWordMax = 128;

  function automatic logic [StreamWordMax-1:0] unity_gain(input int unsigned gain_int_bits,
                                                          input int unsigned gain_frac_bits);
    return (gain_int_bits > 0) ? (StreamWordMax'(1) << gain_frac_bits)
                               : ((StreamWordMax'(1) << (gain_int_bits + gain_frac_bits)) - 1);
  endfunction

  function automatic logic [StreamWordMax-1:0] neutral_stream_word(
    input method_e     method,
    input int unsigned gain_int_bits,
    input int unsigned gain_frac_bits,
    input int unsigned offset_bits);
    logic [StreamWordMax-1:0] one;
    int unsigned              gb;
    gb  = gain_int_bits + gain_frac_bits;
    one = unity_gain(gain_int_bits, gain_frac_bits);
    unique case (method)
      MethodOnePoint:    return '0;  // offset 0 (the gain is the frame word's)
      MethodPiecewise:   return (one << coef_piecewise_gain_lo_lsb())
                                | (one << coef_piecewise_gain_hi_lsb(gb));
      MethodTableInterp: return (one << coef_word_gain_lsb())  // tables j and j + 1
                                | (one << (coef_word_bits(gb, offset_bits) + coef_word_gain_lsb()));
      default:           return one << coef_word_gain_lsb();  // the two-point word first
    endcase
  endfunction

  function automatic logic [StreamWordMax-1:0] stream_bad_mask(
    input method_e     method,
    input int unsigned gain_bits,
    input int unsigned offset_bits,
    input int unsigned knee_bits);
    logic [StreamWordMax-1:0] bad;
    bad = StreamWordMax'(1) << coef_word_bad_lsb(gain_bits, offset_bits);
    unique case (method)
      MethodOnePoint:    return StreamWordMax'(1) << coef_one_point_bad_lsb(offset_bits);
      MethodPiecewise:   return StreamWordMax'(1) << coef_piecewise_bad_lsb(gain_bits, knee_bits);
      MethodTableInterp: return bad | (bad << coef_word_bits(gain_bits, offset_bits));
      default:           return bad;
    endcase
  endfunction

endpackage
