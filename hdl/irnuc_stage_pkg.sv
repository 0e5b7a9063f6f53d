// The stages of the correction methods in RTL (docs/datapath.md "blind_drift", "ffc";
// docs/rtl.md "Stages"): the core kinds of core_sum, their widths and latencies, and the
// FFC's per-frame mode.
//
// The widths are the closed forms of nuc_fixed.widths.core_widths (docs/datapath.md "Cores,
// per pixel") for a core input x of any width, signedness and fraction bits (raw codes,
// x' of drift_sub, the FFC accumulator); cocotb_tests/tb_stage.py reads the streams' widths
// back from the simulated tops and compares them with irnuc.cosim.stages.
package irnuc_stage_pkg;

  import irnuc_pkg::*;
  import irnuc_method_pkg::*;

  // Width of an operand as a signed word (an unsigned one gains a zero sign bit).
  function automatic int unsigned as_signed(input int unsigned bits, input bit is_signed);
    return is_signed ? bits : bits + 32'd1;
  endfunction

  // The core kinds (core_kind_e, core_kind of a method) are irnuc_method_pkg's.

  // D = max(Kf, Xf) of pwl_core: the fraction bits of d = x - k.
  function automatic int unsigned pwl_d_frac(input int unsigned knee_frac,
                                             input int unsigned x_frac);
    return max2(knee_frac, x_frac);
  endfunction

  // F: the fraction bits of the core's sum (nuc_fixed.widths.core_frac), at least min_frac
  // (the FFC term's Cf when the correction is added to the sum).
  function automatic int unsigned core_frac(input core_kind_e kind,
                                            input int unsigned x_frac,
                                            input int unsigned gain_frac,
                                            input int unsigned offset_frac,
                                            input int unsigned knee_frac,
                                            input int unsigned level_frac,
                                            input int unsigned min_frac);
    if (kind == CorePwl) begin
      return max3(gain_frac + pwl_d_frac(knee_frac, x_frac), level_frac, min_frac);
    end
    return max3(gain_frac + x_frac, offset_frac, min_frac);
  endfunction

  // Sq = max(0, 2A - square_bits): the bits the square of a raw code drops (quad_core).
  function automatic int unsigned square_shift(input int unsigned adc_bits,
                                               input int unsigned square_bits);
    return (2 * adc_bits > square_bits) ? 2 * adc_bits - square_bits : 32'd0;
  endfunction

  // QPf = Qf + 2A - Sq: the fraction bits of q * xq.
  function automatic int unsigned quad_qp_frac(input int unsigned adc_bits,
                                               input int unsigned quad_frac,
                                               input int unsigned square_bits);
    return quad_frac + 2 * adc_bits - square_shift(adc_bits, square_bits);
  endfunction

  // Width of xq = (x * x) >> (2 Xf + Sq): min(2A, square_bits) for an input of A + Xf bits.
  function automatic int unsigned quad_xq_bits(input int unsigned x_bits,
                                               input int unsigned x_frac,
                                               input int unsigned adc_bits,
                                               input int unsigned square_bits);
    return 2 * x_bits - 2 * x_frac - square_shift(adc_bits, square_bits);
  endfunction

  // Width of d = (x << (D - Xf)) - (k << (D - Kf)), signed (both terms as signed words).
  function automatic int unsigned pwl_diff_bits(input int unsigned x_bits,
                                                input bit          x_signed,
                                                input int unsigned x_frac,
                                                input int unsigned knee_bits,
                                                input int unsigned knee_frac);
    int unsigned d;
    d = pwl_d_frac(knee_frac, x_frac);
    return max2(as_signed(x_bits + d - x_frac, x_signed),
                as_signed(knee_bits + d - knee_frac, 1'b0)) + 32'd1;
  endfunction

  // Width of the signed sum s (docs/datapath.md: the terms as signed words, max + 1 for two
  // terms, max + 2 for three).
  function automatic int unsigned core_sum_bits(input core_kind_e kind,
                                                input int unsigned x_bits,
                                                input bit          x_signed,
                                                input int unsigned x_frac,
                                                input int unsigned adc_bits,
                                                input int unsigned gain_bits,
                                                input int unsigned gain_frac,
                                                input int unsigned offset_bits,
                                                input int unsigned offset_frac,
                                                input int unsigned quad_bits,
                                                input int unsigned quad_frac,
                                                input int unsigned square_bits,
                                                input int unsigned knee_bits,
                                                input int unsigned knee_frac,
                                                input int unsigned level_bits,
                                                input int unsigned level_frac,
                                                input int unsigned min_frac);
    int unsigned f, d, t1, t2, qp, qpf, qs;
    f = core_frac(kind, x_frac, gain_frac, offset_frac, knee_frac, level_frac, min_frac);
    if (kind == CorePwl) begin
      d  = pwl_d_frac(knee_frac, x_frac);
      t1 = pwl_diff_bits(x_bits, x_signed, x_frac, knee_bits, knee_frac) + gain_bits
           + f - gain_frac - d;
      t2 = level_bits + 32'd1 + f - level_frac;
      return max2(t1, t2) + 32'd1;
    end
    t1 = as_signed(x_bits + gain_bits, x_signed) + f - gain_frac - x_frac;
    t2 = offset_bits + f - offset_frac;
    if (kind == CoreLin) begin
      return max2(t1, t2) + 32'd1;
    end
    qp  = quad_bits + quad_xq_bits(x_bits, x_frac, adc_bits, square_bits);
    qpf = quad_qp_frac(adc_bits, quad_frac, square_bits);
    qs  = (qpf <= f) ? qp + f - qpf : qp - (qpf - f);
    return max3(t1, t2, qs) + 32'd2;
  endfunction

  // Register stages of core_sum without padding (it documents each).
  function automatic int unsigned core_sum_latency(input core_kind_e kind,
                                                   input int unsigned x_bits,
                                                   input bit          x_signed,
                                                   input int unsigned x_frac,
                                                   input int unsigned adc_bits,
                                                   input int unsigned gain_bits,
                                                   input int unsigned quad_bits,
                                                   input int unsigned square_bits,
                                                   input int unsigned knee_bits,
                                                   input int unsigned knee_frac);
    int unsigned parts, sq_parts, xq;
    if (kind == CorePwl) begin
      parts = smul_parts(pwl_diff_bits(x_bits, x_signed, x_frac, knee_bits, knee_frac), 1'b1,
                         gain_bits, 1'b0);
      return 32'd3 + $clog2(parts + 1);
    end
    parts = smul_parts(x_bits, x_signed, gain_bits, 1'b0);
    if (kind == CoreLin) begin
      return 32'd2 + $clog2(parts + 1);
    end
    xq       = quad_xq_bits(x_bits, x_frac, adc_bits, square_bits);
    sq_parts = smul_parts(x_bits, 1'b0, x_bits, 1'b0);
    return 32'd4 + $clog2(sq_parts) + $clog2(parts + smul_parts(quad_bits, 1'b1, xq, 1'b0) + 1);
  endfunction

  // ---- the FFC's mode of a frame (ffc_ctrl decides it at the frame's first pixel) --------
  typedef struct packed {
    logic acc_rd;     // the frame takes one ffc_acc word per pixel (s_acc)
    logic acc_first;  // first frame of a shutter run: acc = x, written (m_acc)
    logic acc_add;    // a later frame of the run: acc = acc + x, written (m_acc)
    logic mean;       // the N-th frame: the target's mean pass over the new accumulator
    logic refresh;    // the refresh pass: new offsets from the read accumulator (m_foff)
    logic hold;       // the frame's output repeats the last open frame (ffc_output hold)
  } ffc_mode_t;


endpackage
