// Correction methods of the RTL (docs/datapath.md "Correction methods", docs/rtl.md
// "Methods"): the method encoding, the signed DSP chunking of the method multipliers, and
// the per-method words of method_dpc_top's two streams.
//
// The method codes are the index in nuc_fixed.config.BASE_METHODS (as Method of
// nuc_fixed.layout.rtl_package; irnuc.cosim.sources.method_parameters passes it); the word
// layouts are nuc_fixed.config.PipelineConfig.memories in stream order (irnuc.cosim.stream
// is their Python side). cocotb_tests/tb_method.py reads the stream widths back from every
// simulated method_dpc_top and compares them with irnuc.cosim.stream, and the co-simulation
// checks every field bit for bit.
package irnuc_method_pkg;

  import irnuc_pkg::MulChunkBits;

  // ---- base methods (module parameter Method carries these codes) -----------------------
  typedef enum logic [2:0] {
    MethodOnePoint    = 3'd0,  // per-pixel offset, global gain register
    MethodTwoPoint    = 3'd1,  // per-pixel gain and offset
    MethodPiecewise   = 3'd2,  // two gains meeting at a per-pixel knee, global level
    MethodQuadratic   = 3'd3,  // gain, offset and a quadratic term per pixel
    MethodTcOffset    = 3'd4,  // offset (and gain) polynomials in the FPA reading
    MethodTableInterp = 3'd5   // two tables interpolated by a per-frame weight
  } method_e;

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
  // A value of `bits` bits as a signed word (an unsigned one needs one bit more).
  function automatic int unsigned as_signed(input int unsigned bits, input bit is_signed);
    return is_signed ? bits : bits + 32'd1;
  endfunction

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
  // above it (the two tables the frame's weight interpolates). Fields of each memory from
  // bit 0 up, as in the memory image:
  //   one_point     coeffs: offset, bad
  //   two_point     coeffs: gain, offset, bad
  //   piecewise     coeffs: gain_lo, gain_hi, knee, bad
  //   quadratic     coeffs: gain, offset, bad | quad: quad
  //   tc_offset     coeffs: gain, offset (c0), bad | tc: tc1[, tc2] | tg: tg1[, tg2] (tc_gain)
  //   table_interp  table j: gain, offset, bad | table j + 1: gain, offset, bad
  function automatic int unsigned two_point_word_bits(input int unsigned gain_bits,
                                                      input int unsigned offset_bits);
    return gain_bits + offset_bits + 32'd1;
  endfunction

  function automatic int unsigned coef_stream_bits(
    input method_e     method,
    input int unsigned gain_bits,
    input int unsigned offset_bits,
    input int unsigned knee_bits,
    input int unsigned quad_bits,
    input int unsigned tc_word_bits,
    input int unsigned tg_word_bits);
    unique case (method)
      MethodOnePoint:  return offset_bits + 32'd1;
      MethodTwoPoint:  return two_point_word_bits(gain_bits, offset_bits);
      MethodPiecewise: return 32'd2 * gain_bits + knee_bits + 32'd1;
      MethodQuadratic: return two_point_word_bits(gain_bits, offset_bits) + quad_bits;
      MethodTcOffset:  return two_point_word_bits(gain_bits, offset_bits) + tc_word_bits
                              + tg_word_bits;
      default:         return 32'd2 * two_point_word_bits(gain_bits, offset_bits);
    endcase
  endfunction

  // ---- frame word of method_dpc_top (s_pix_frame_i), per method -------------------------
  // Sampled with the first pixel of every frame (sof) and used for all of its pixels:
  //   one_point     gain (the global gain register, U Gi.Gf)
  //   piecewise     level (the knee level register, U Li.Lf)
  //   tc_offset     reading (bit 0 up, R bits), t_ref (R bits)
  //   table_interp  weight (U Wi.Wf, at most 2^Wf)
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
      MethodTcOffset:    return 32'd2 * reading_bits;
      MethodTableInterp: return weight_bits;
      default:           return 32'd1;
    endcase
  endfunction

endpackage
