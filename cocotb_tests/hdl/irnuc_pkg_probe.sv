// Simulation-only probe of hdl/irnuc_pkg.sv: exposes the package's enum values, the
// coefficient word layout (through its packed struct) and the DPC reciprocal table on
// ports, so that cocotb_tests/test_pkg.py compares them with the Python side
// (nuc_fixed.config ROUNDING_MODES / OVERFLOW_MODES, nuc_fixed.memimage.pack_words,
// nuc_fixed.rtl.reciprocal_table) by simulation. Not part of the design.
module irnuc_pkg_probe
  import irnuc_pkg::*;
#(
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits        = 14,
  // Derived, do not override.
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits,
  localparam int unsigned WordBits      = coef_word_bits(GainBits, OffsetBits),
  localparam int unsigned RecBits       = dpc_recip_shift(OutBits) + 1
) (
  // Coefficient word: fields in, the packed word out ...
  input  logic [GainBits-1:0]   gain_i,
  input  logic [OffsetBits-1:0] offset_i,
  input  logic                  bad_i,
  output logic [WordBits-1:0]   word_o,
  // ... and a word in, its fields out.
  input  logic [WordBits-1:0]   word_i,
  output logic [GainBits-1:0]   gain_o,
  output logic [OffsetBits-1:0] offset_o,
  output logic                  bad_o,
  // Layout constants of the package.
  output logic [7:0]            word_bits_o,
  output logic [7:0]            offset_lsb_o,
  output logic [7:0]            bad_bit_o,
  // Enum values, one port per literal (named rounding_<mode>_o / overflow_<mode>_o after
  // the configuration's mode names), and the number of literals.
  output logic [1:0]            rounding_truncate_o,
  output logic [1:0]            rounding_half_up_o,
  output logic [1:0]            rounding_half_even_o,
  output logic [7:0]            rounding_count_o,
  output logic                  overflow_saturate_o,
  output logic                  overflow_wrap_o,
  output logic [7:0]            overflow_count_o,
  // DPC reciprocal table R[n] (n = 0..8) and its shift K.
  input  logic [3:0]            recip_n_i,
  output logic [RecBits-1:0]    recip_o,
  output logic [7:0]            recip_shift_o
);

  typedef coef_word#(GainBits, OffsetBits)::word_t coef_word_t;

  coef_word_t packed_w, unpacked_w;
  rounding_e  rounding_any;
  overflow_e  overflow_any;

  always_comb begin : p_pack
    packed_w        = '0;
    packed_w.gain   = gain_i;
    packed_w.offset = offset_i;
    packed_w.bad    = bad_i;
  end
  assign word_o     = packed_w;
  assign unpacked_w = coef_word_t'(word_i);
  assign gain_o     = unpacked_w.gain;
  assign offset_o   = unpacked_w.offset;
  assign bad_o      = unpacked_w.bad;

  assign word_bits_o  = 8'($bits(coef_word_t));
  assign offset_lsb_o = 8'(coef_offset_lsb(GainBits));
  assign bad_bit_o    = 8'(coef_bad_bit(GainBits, OffsetBits));

  assign rounding_truncate_o  = RoundTruncate;
  assign rounding_half_up_o   = RoundHalfUp;
  assign rounding_half_even_o = RoundHalfEven;
  assign overflow_saturate_o  = OverflowSaturate;
  assign overflow_wrap_o      = OverflowWrap;
  assign rounding_any         = RoundTruncate;
  assign overflow_any         = OverflowSaturate;
  assign rounding_count_o     = 8'(rounding_any.num());
  assign overflow_count_o     = 8'(overflow_any.num());
  // num() is a property of the type; the variables themselves carry nothing.
  logic unused_enum;
  assign unused_enum = ^{rounding_any, overflow_any};

  // The table as dpc_core builds it: constant calls of irnuc_pkg::dpc_recip.
  logic [8:0][RecBits-1:0] recip_table;
  for (genvar n = 0; n <= 8; n++) begin : gen_recip
    assign recip_table[n] = RecBits'(dpc_recip(OutBits, n));
  end
  assign recip_o       = (recip_n_i <= 4'd8) ? recip_table[recip_n_i] : '0;
  assign recip_shift_o = 8'(dpc_recip_shift(OutBits));

endmodule
