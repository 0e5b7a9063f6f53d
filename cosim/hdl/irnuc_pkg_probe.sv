// Simulation-only probe of hdl/irnuc_pkg.sv, generated from
// irnuc.nuc_fixed.rtl_spec (python -m irnuc.cosim.spec_files --write); do not edit.
// Every constant, range, enum literal and word layout of the package is on a port,
// so that cocotb_tests/tb_pkg.py compares them with the Python side by simulation.
// Not part of the design.
module irnuc_pkg_probe
  import irnuc_pkg::*;
#(
  parameter int unsigned GainIntBits = 2,
  parameter int unsigned GainFracBits = 14,
  parameter int unsigned OffsetIntBits = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits = 14,
  // Derived, do not override.
  localparam int unsigned GainBits = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits = OffsetIntBits + OffsetFracBits,
  localparam int unsigned RecBits = dpc_recip_shift(OutBits) + 1
) (
  output logic [31:0] const_mul_chunk_bits_o,
  output logic [31:0] const_frame_dim_max_o,
  output logic [31:0] const_dpc_recip_guard_bits_o,
  output logic [31:0] const_sum_bits_max_o,
  output logic [31:0] min_adc_bits_o,
  output logic [31:0] max_adc_bits_o,
  output logic [31:0] min_gain_int_bits_o,
  output logic [31:0] max_gain_int_bits_o,
  output logic [31:0] min_gain_frac_bits_o,
  output logic [31:0] max_gain_frac_bits_o,
  output logic [31:0] min_offset_int_bits_o,
  output logic [31:0] max_offset_int_bits_o,
  output logic [31:0] min_offset_frac_bits_o,
  output logic [31:0] max_offset_frac_bits_o,
  output logic [31:0] min_out_bits_o,
  output logic [31:0] max_out_bits_o,
  output logic [31:0] min_max_width_o,
  output logic [31:0] max_max_width_o,
  output logic [31:0] min_max_height_o,
  output logic [31:0] max_max_height_o,
  output logic [1:0] enum_roundtruncate_o,
  output logic [1:0] enum_roundhalfup_o,
  output logic [1:0] enum_roundhalfeven_o,
  output logic [7:0] count_rounding_e_o,
  output logic [31:0] const_rounding_count_o,
  output logic [0:0] enum_overflowsaturate_o,
  output logic [0:0] enum_overflowwrap_o,
  output logic [7:0] count_overflow_e_o,
  output logic [31:0] const_overflow_count_o,
  input  logic [coef_word_bits(GainBits, OffsetBits)-1:0] coef_word_word_i,
  output logic [coef_word_bits(GainBits, OffsetBits)-1:0] coef_word_word_o,
  output logic [7:0] coef_word_bits_o,
  input  logic [GainBits-1:0] coef_word_gain_i,
  output logic [GainBits-1:0] coef_word_gain_o,
  output logic [7:0] coef_word_gain_lsb_o,
  input  logic [OffsetBits-1:0] coef_word_offset_i,
  output logic [OffsetBits-1:0] coef_word_offset_o,
  output logic [7:0] coef_word_offset_lsb_o,
  input  logic coef_word_bad_i,
  output logic coef_word_bad_o,
  output logic [7:0] coef_word_bad_lsb_o,
  output logic [64:1][7:0] mul_chunks_o,
  output logic [24:1][7:0] dpc_recip_shift_o,
  input  logic [3:0] recip_n_i,
  output logic [RecBits-1:0] recip_o
);

  assign const_mul_chunk_bits_o = 32'(MulChunkBits);
  assign const_frame_dim_max_o = 32'(FrameDimMax);
  assign const_dpc_recip_guard_bits_o = 32'(DpcRecipGuardBits);
  assign const_sum_bits_max_o = 32'(SumBitsMax);
  assign min_adc_bits_o = 32'(AdcBitsMin);
  assign max_adc_bits_o = 32'(AdcBitsMax);
  assign min_gain_int_bits_o = 32'(GainIntBitsMin);
  assign max_gain_int_bits_o = 32'(GainIntBitsMax);
  assign min_gain_frac_bits_o = 32'(GainFracBitsMin);
  assign max_gain_frac_bits_o = 32'(GainFracBitsMax);
  assign min_offset_int_bits_o = 32'(OffsetIntBitsMin);
  assign max_offset_int_bits_o = 32'(OffsetIntBitsMax);
  assign min_offset_frac_bits_o = 32'(OffsetFracBitsMin);
  assign max_offset_frac_bits_o = 32'(OffsetFracBitsMax);
  assign min_out_bits_o = 32'(OutBitsMin);
  assign max_out_bits_o = 32'(OutBitsMax);
  assign min_max_width_o = 32'(MaxWidthMin);
  assign max_max_width_o = 32'(MaxWidthMax);
  assign min_max_height_o = 32'(MaxHeightMin);
  assign max_max_height_o = 32'(MaxHeightMax);
  assign enum_roundtruncate_o = RoundTruncate;
  assign enum_roundhalfup_o = RoundHalfUp;
  assign enum_roundhalfeven_o = RoundHalfEven;
  assign const_rounding_count_o = 32'(RoundingCount);
  rounding_e rounding_any;
  assign rounding_any = RoundTruncate;
  assign count_rounding_e_o = 8'(rounding_any.num());
  logic unused_rounding;
  assign unused_rounding = ^rounding_any;  // num() is of the type
  assign enum_overflowsaturate_o = OverflowSaturate;
  assign enum_overflowwrap_o = OverflowWrap;
  assign const_overflow_count_o = 32'(OverflowCount);
  overflow_e overflow_any;
  assign overflow_any = OverflowSaturate;
  assign count_overflow_e_o = 8'(overflow_any.num());
  logic unused_overflow;
  assign unused_overflow = ^overflow_any;  // num() is of the type
  typedef coef_word#(GainBits, OffsetBits)::word_t coef_word_t;
  coef_word_t coef_word_packed, coef_word_unpacked;
  assign coef_word_word_o = coef_word_packed;
  assign coef_word_unpacked = coef_word_t'(coef_word_word_i);
  assign coef_word_bits_o = 8'($bits(coef_word_t));
  assign coef_word_gain_o = coef_word_unpacked.gain;
  assign coef_word_gain_lsb_o = 8'(coef_word_gain_lsb());
  assign coef_word_offset_o = coef_word_unpacked.offset;
  assign coef_word_offset_lsb_o = 8'(coef_word_offset_lsb(GainBits));
  assign coef_word_bad_o = coef_word_unpacked.bad;
  assign coef_word_bad_lsb_o = 8'(coef_word_bad_lsb(GainBits, OffsetBits));
  always_comb begin : p_pack_coef_word
    coef_word_packed = '0;
    coef_word_packed.gain = coef_word_gain_i;
    coef_word_packed.offset = coef_word_offset_i;
    coef_word_packed.bad = coef_word_bad_i;
  end
  for (genvar b = 1; b <= 64; b++) begin : gen_mul_chunks
    assign mul_chunks_o[b] = 8'(mul_chunks(b));
  end
  for (genvar b = 1; b <= 24; b++) begin : gen_recip_shift
    assign dpc_recip_shift_o[b] = 8'(dpc_recip_shift(b));
  end
  // The DPC table as dpc_core builds it: constant calls of dpc_recip.
  logic [8:0][RecBits-1:0] recip_table;
  for (genvar n = 0; n <= 8; n++) begin : gen_recip
    assign recip_table[n] = RecBits'(dpc_recip(OutBits, n));
  end
  assign recip_o = (recip_n_i <= 4'd8) ? recip_table[recip_n_i] : '0;

endmodule
