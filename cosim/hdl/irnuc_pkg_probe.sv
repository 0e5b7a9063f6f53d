// Simulation-only probe of hdl/irnuc_pkg.sv, generated from
// irnuc.nuc_fixed.rtl_spec (python -m irnuc.cosim.spec_files --write); do not edit.
// Every constant, range, enum literal and word layout of the package is on a port,
// so that cocotb_tests/tb_pkg.py compares them with the Python side by simulation.
// Not part of the design.
module irnuc_pkg_probe
  import irnuc_pkg::*;
#(
  parameter int unsigned KneeBits = 16,
  parameter int unsigned QuadBits = 16,
  parameter int unsigned Tc1Bits = 16,
  parameter int unsigned Tc2Bits = 16,
  parameter int unsigned Tg1Bits = 16,
  parameter int unsigned Tg2Bits = 16,
  parameter int unsigned ReadingBits = 14,
  parameter int unsigned Th1Bits = 18,
  parameter int unsigned ThxBits = 18,
  parameter int unsigned Th2Bits = 16,
  parameter int unsigned HousingBits = 14,
  parameter int unsigned GainIntBits = 2,
  parameter int unsigned GainFracBits = 14,
  parameter int unsigned OffsetIntBits = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits = 14,
  parameter int unsigned BaseBits = 16,
  parameter int unsigned SumBits = 28,
  parameter int unsigned DriftGainBits = 25,
  // Derived, do not override.
  localparam int unsigned GainBits = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits = OffsetIntBits + OffsetFracBits,
  localparam int unsigned RecBits = dpc_recip_shift(OutBits) + 1
) (
  output logic [31:0] const_mul_chunk_bits_o,
  output logic [31:0] const_frame_dim_max_o,
  output logic [31:0] const_dpc_recip_guard_bits_o,
  output logic [31:0] const_sum_bits_max_o,
  output logic [31:0] const_reg_map_id_o,
  output logic [31:0] const_reg_map_major_o,
  output logic [31:0] const_reg_map_minor_o,
  output logic [31:0] const_reg_addr_bits_o,
  output logic [31:0] const_reg_slot_count_o,
  output logic [31:0] const_reg_id_offset_o,
  output logic [31:0] const_reg_id_value_lsb_o,
  output logic [31:0] const_reg_id_value_bits_o,
  output logic [31:0] const_reg_version_offset_o,
  output logic [31:0] const_reg_version_minor_lsb_o,
  output logic [31:0] const_reg_version_minor_bits_o,
  output logic [31:0] const_reg_version_major_lsb_o,
  output logic [31:0] const_reg_version_major_bits_o,
  output logic [31:0] const_reg_version_coef_layout_lsb_o,
  output logic [31:0] const_reg_version_coef_layout_bits_o,
  output logic [31:0] const_reg_config_offset_o,
  output logic [31:0] const_reg_config_adc_bits_lsb_o,
  output logic [31:0] const_reg_config_adc_bits_bits_o,
  output logic [31:0] const_reg_config_out_bits_lsb_o,
  output logic [31:0] const_reg_config_out_bits_bits_o,
  output logic [31:0] const_reg_config_word_bits_lsb_o,
  output logic [31:0] const_reg_config_word_bits_bits_o,
  output logic [31:0] const_reg_config_method_lsb_o,
  output logic [31:0] const_reg_config_method_bits_o,
  output logic [31:0] const_reg_config_blind_drift_lsb_o,
  output logic [31:0] const_reg_config_ffc_lsb_o,
  output logic [31:0] const_reg_config_rounding_lsb_o,
  output logic [31:0] const_reg_config_rounding_bits_o,
  output logic [31:0] const_reg_config_overflow_lsb_o,
  output logic [31:0] const_reg_format_offset_o,
  output logic [31:0] const_reg_format_gain_int_bits_lsb_o,
  output logic [31:0] const_reg_format_gain_int_bits_bits_o,
  output logic [31:0] const_reg_format_gain_frac_bits_lsb_o,
  output logic [31:0] const_reg_format_gain_frac_bits_bits_o,
  output logic [31:0] const_reg_format_offset_int_bits_lsb_o,
  output logic [31:0] const_reg_format_offset_int_bits_bits_o,
  output logic [31:0] const_reg_format_offset_frac_bits_lsb_o,
  output logic [31:0] const_reg_format_offset_frac_bits_bits_o,
  output logic [31:0] const_reg_frame_max_offset_o,
  output logic [31:0] const_reg_frame_max_width_lsb_o,
  output logic [31:0] const_reg_frame_max_width_bits_o,
  output logic [31:0] const_reg_frame_max_height_lsb_o,
  output logic [31:0] const_reg_frame_max_height_bits_o,
  output logic [31:0] const_reg_ctrl_offset_o,
  output logic [31:0] const_reg_ctrl_nuc_en_lsb_o,
  output logic [31:0] const_reg_ctrl_nuc_en_reset_o,
  output logic [31:0] const_reg_ctrl_dpc_en_lsb_o,
  output logic [31:0] const_reg_ctrl_dpc_en_reset_o,
  output logic [31:0] const_reg_ctrl_coef_sync_lsb_o,
  output logic [31:0] const_reg_ctrl_coef_sync_reset_o,
  output logic [31:0] const_reg_frame_size_offset_o,
  output logic [31:0] const_reg_frame_size_width_lsb_o,
  output logic [31:0] const_reg_frame_size_width_bits_o,
  output logic [31:0] const_reg_frame_size_height_lsb_o,
  output logic [31:0] const_reg_frame_size_height_bits_o,
  output logic [31:0] const_reg_command_offset_o,
  output logic [31:0] const_reg_command_clear_counters_lsb_o,
  output logic [31:0] const_reg_status_offset_o,
  output logic [31:0] const_reg_status_sof_early_lsb_o,
  output logic [31:0] const_reg_status_sof_early_reset_o,
  output logic [31:0] const_reg_status_sof_late_lsb_o,
  output logic [31:0] const_reg_status_sof_late_reset_o,
  output logic [31:0] const_reg_status_eol_early_lsb_o,
  output logic [31:0] const_reg_status_eol_early_reset_o,
  output logic [31:0] const_reg_status_eol_late_lsb_o,
  output logic [31:0] const_reg_status_eol_late_reset_o,
  output logic [31:0] const_reg_status_coef_early_lsb_o,
  output logic [31:0] const_reg_status_coef_early_reset_o,
  output logic [31:0] const_reg_status_coef_late_lsb_o,
  output logic [31:0] const_reg_status_coef_late_reset_o,
  output logic [31:0] const_reg_status_core_err_lsb_o,
  output logic [31:0] const_reg_status_in_frame_lsb_o,
  output logic [31:0] const_reg_status_pending_lsb_o,
  output logic [31:0] const_reg_irq_enable_offset_o,
  output logic [31:0] const_reg_irq_enable_error_lsb_o,
  output logic [31:0] const_reg_irq_enable_error_reset_o,
  output logic [31:0] const_reg_irq_enable_frame_done_lsb_o,
  output logic [31:0] const_reg_irq_enable_frame_done_reset_o,
  output logic [31:0] const_reg_irq_enable_ffc_done_lsb_o,
  output logic [31:0] const_reg_irq_enable_ffc_done_reset_o,
  output logic [31:0] const_reg_irq_enable_ffc_request_lsb_o,
  output logic [31:0] const_reg_irq_enable_ffc_request_reset_o,
  output logic [31:0] const_reg_irq_status_offset_o,
  output logic [31:0] const_reg_irq_status_error_lsb_o,
  output logic [31:0] const_reg_irq_status_error_reset_o,
  output logic [31:0] const_reg_irq_status_frame_done_lsb_o,
  output logic [31:0] const_reg_irq_status_frame_done_reset_o,
  output logic [31:0] const_reg_irq_status_ffc_done_lsb_o,
  output logic [31:0] const_reg_irq_status_ffc_done_reset_o,
  output logic [31:0] const_reg_irq_status_ffc_request_lsb_o,
  output logic [31:0] const_reg_irq_status_ffc_request_reset_o,
  output logic [31:0] const_reg_frames_in_offset_o,
  output logic [31:0] const_reg_frames_in_count_lsb_o,
  output logic [31:0] const_reg_frames_in_count_bits_o,
  output logic [31:0] const_reg_frames_out_offset_o,
  output logic [31:0] const_reg_frames_out_count_lsb_o,
  output logic [31:0] const_reg_frames_out_count_bits_o,
  output logic [31:0] const_reg_pixels_in_offset_o,
  output logic [31:0] const_reg_pixels_in_count_lsb_o,
  output logic [31:0] const_reg_pixels_in_count_bits_o,
  output logic [31:0] const_reg_pixels_out_offset_o,
  output logic [31:0] const_reg_pixels_out_count_lsb_o,
  output logic [31:0] const_reg_pixels_out_count_bits_o,
  output logic [31:0] const_reg_dropped_offset_o,
  output logic [31:0] const_reg_dropped_count_lsb_o,
  output logic [31:0] const_reg_dropped_count_bits_o,
  output logic [31:0] const_reg_padded_offset_o,
  output logic [31:0] const_reg_padded_count_lsb_o,
  output logic [31:0] const_reg_padded_count_bits_o,
  output logic [31:0] const_reg_sof_errors_offset_o,
  output logic [31:0] const_reg_sof_errors_early_lsb_o,
  output logic [31:0] const_reg_sof_errors_early_bits_o,
  output logic [31:0] const_reg_sof_errors_late_lsb_o,
  output logic [31:0] const_reg_sof_errors_late_bits_o,
  output logic [31:0] const_reg_eol_errors_offset_o,
  output logic [31:0] const_reg_eol_errors_early_lsb_o,
  output logic [31:0] const_reg_eol_errors_early_bits_o,
  output logic [31:0] const_reg_eol_errors_late_lsb_o,
  output logic [31:0] const_reg_eol_errors_late_bits_o,
  output logic [31:0] const_reg_coef_errors_offset_o,
  output logic [31:0] const_reg_coef_errors_early_lsb_o,
  output logic [31:0] const_reg_coef_errors_early_bits_o,
  output logic [31:0] const_reg_coef_errors_late_lsb_o,
  output logic [31:0] const_reg_coef_errors_late_bits_o,
  output logic [31:0] const_reg_ffc_ctrl_offset_o,
  output logic [31:0] const_reg_ffc_ctrl_start_lsb_o,
  output logic [31:0] const_reg_ffc_ctrl_frames_lsb_o,
  output logic [31:0] const_reg_ffc_ctrl_frames_bits_o,
  output logic [31:0] const_reg_ffc_status_offset_o,
  output logic [31:0] const_reg_ffc_status_busy_lsb_o,
  output logic [31:0] const_reg_ffc_status_done_lsb_o,
  output logic [31:0] const_reg_ffc_period_offset_o,
  output logic [31:0] const_reg_ffc_period_frames_lsb_o,
  output logic [31:0] const_reg_ffc_period_frames_bits_o,
  output logic [31:0] const_reg_ffc_period_frames_reset_o,
  output logic [31:0] const_reg_ffc_threshold_offset_o,
  output logic [31:0] const_reg_ffc_threshold_codes_lsb_o,
  output logic [31:0] const_reg_ffc_threshold_codes_bits_o,
  output logic [31:0] const_reg_ffc_threshold_codes_reset_o,
  output logic [31:0] const_reg_ffc_trigger_offset_o,
  output logic [31:0] const_reg_ffc_trigger_since_lsb_o,
  output logic [31:0] const_reg_ffc_trigger_since_bits_o,
  output logic [31:0] const_reg_ffc_trigger_period_lsb_o,
  output logic [31:0] const_reg_ffc_trigger_threshold_lsb_o,
  output logic [31:0] const_reg_ffc_ref_offset_o,
  output logic [31:0] const_reg_ffc_ref_reading_lsb_o,
  output logic [31:0] const_reg_ffc_ref_reading_bits_o,
  output logic [31:0] const_reg_gain_lo_offset_o,
  output logic [31:0] const_reg_gain_hi_offset_o,
  output logic [31:0] const_reg_level_lo_offset_o,
  output logic [31:0] const_reg_level_hi_offset_o,
  output logic [31:0] const_reg_reading_lo_offset_o,
  output logic [31:0] const_reg_reading_hi_offset_o,
  output logic [31:0] const_reg_t_ref_lo_offset_o,
  output logic [31:0] const_reg_t_ref_hi_offset_o,
  output logic [31:0] const_reg_blind_sum_lo_offset_o,
  output logic [31:0] const_reg_blind_sum_hi_offset_o,
  output logic [31:0] const_reg_blind_ref_lo_offset_o,
  output logic [31:0] const_reg_blind_ref_hi_offset_o,
  output logic [31:0] const_reg_drift_gain_lo_offset_o,
  output logic [31:0] const_reg_drift_gain_hi_offset_o,
  output logic [31:0] const_reg_ffc_target_lo_offset_o,
  output logic [31:0] const_reg_ffc_target_hi_offset_o,
  output logic [31:0] const_reg_housing_reading_lo_offset_o,
  output logic [31:0] const_reg_housing_reading_hi_offset_o,
  output logic [31:0] const_reg_h_ref_lo_offset_o,
  output logic [31:0] const_reg_h_ref_hi_offset_o,
  output logic [31:0] const_reg_table_reading_offset_o,
  output logic [31:0] const_reg_table_reading_stride_o,
  output logic [31:0] const_reg_table_reading_count_o,
  output logic [31:0] const_reg_table_sel_offset_o,
  output logic [31:0] const_reg_table_sel_weight_lsb_o,
  output logic [31:0] const_reg_table_sel_weight_bits_o,
  output logic [31:0] const_reg_table_sel_j_lsb_o,
  output logic [31:0] const_reg_table_sel_j_bits_o,
  output logic [31:0] const_reg_table_sel_valid_lsb_o,
  output logic [31:0] const_reg_table_sel_error_lsb_o,
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
  output logic [2:0] enum_methodonepoint_o,
  output logic [2:0] enum_methodtwopoint_o,
  output logic [2:0] enum_methodpiecewise_o,
  output logic [2:0] enum_methodquadratic_o,
  output logic [2:0] enum_methodtcoffset_o,
  output logic [2:0] enum_methodtableinterp_o,
  output logic [2:0] enum_methodtchousing_o,
  output logic [7:0] count_method_e_o,
  output logic [31:0] const_method_count_o,
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
  input  logic [coef_one_point_bits(OffsetBits)-1:0] coef_one_point_word_i,
  output logic [coef_one_point_bits(OffsetBits)-1:0] coef_one_point_word_o,
  output logic [7:0] coef_one_point_bits_o,
  input  logic [OffsetBits-1:0] coef_one_point_offset_i,
  output logic [OffsetBits-1:0] coef_one_point_offset_o,
  output logic [7:0] coef_one_point_offset_lsb_o,
  input  logic coef_one_point_bad_i,
  output logic coef_one_point_bad_o,
  output logic [7:0] coef_one_point_bad_lsb_o,
  input  logic [coef_piecewise_bits(GainBits, KneeBits)-1:0] coef_piecewise_word_i,
  output logic [coef_piecewise_bits(GainBits, KneeBits)-1:0] coef_piecewise_word_o,
  output logic [7:0] coef_piecewise_bits_o,
  input  logic [GainBits-1:0] coef_piecewise_gain_lo_i,
  output logic [GainBits-1:0] coef_piecewise_gain_lo_o,
  output logic [7:0] coef_piecewise_gain_lo_lsb_o,
  input  logic [GainBits-1:0] coef_piecewise_gain_hi_i,
  output logic [GainBits-1:0] coef_piecewise_gain_hi_o,
  output logic [7:0] coef_piecewise_gain_hi_lsb_o,
  input  logic [KneeBits-1:0] coef_piecewise_knee_i,
  output logic [KneeBits-1:0] coef_piecewise_knee_o,
  output logic [7:0] coef_piecewise_knee_lsb_o,
  input  logic coef_piecewise_bad_i,
  output logic coef_piecewise_bad_o,
  output logic [7:0] coef_piecewise_bad_lsb_o,
  input  logic [quad_word_bits(QuadBits)-1:0] quad_word_word_i,
  output logic [quad_word_bits(QuadBits)-1:0] quad_word_word_o,
  output logic [7:0] quad_word_bits_o,
  input  logic [QuadBits-1:0] quad_word_quad_i,
  output logic [QuadBits-1:0] quad_word_quad_o,
  output logic [7:0] quad_word_quad_lsb_o,
  input  logic [tc_word1_bits(Tc1Bits)-1:0] tc_word1_word_i,
  output logic [tc_word1_bits(Tc1Bits)-1:0] tc_word1_word_o,
  output logic [7:0] tc_word1_bits_o,
  input  logic [Tc1Bits-1:0] tc_word1_tc1_i,
  output logic [Tc1Bits-1:0] tc_word1_tc1_o,
  output logic [7:0] tc_word1_tc1_lsb_o,
  input  logic [tc_word2_bits(Tc1Bits, Tc2Bits)-1:0] tc_word2_word_i,
  output logic [tc_word2_bits(Tc1Bits, Tc2Bits)-1:0] tc_word2_word_o,
  output logic [7:0] tc_word2_bits_o,
  input  logic [Tc1Bits-1:0] tc_word2_tc1_i,
  output logic [Tc1Bits-1:0] tc_word2_tc1_o,
  output logic [7:0] tc_word2_tc1_lsb_o,
  input  logic [Tc2Bits-1:0] tc_word2_tc2_i,
  output logic [Tc2Bits-1:0] tc_word2_tc2_o,
  output logic [7:0] tc_word2_tc2_lsb_o,
  input  logic [tg_word1_bits(Tg1Bits)-1:0] tg_word1_word_i,
  output logic [tg_word1_bits(Tg1Bits)-1:0] tg_word1_word_o,
  output logic [7:0] tg_word1_bits_o,
  input  logic [Tg1Bits-1:0] tg_word1_tg1_i,
  output logic [Tg1Bits-1:0] tg_word1_tg1_o,
  output logic [7:0] tg_word1_tg1_lsb_o,
  input  logic [tg_word2_bits(Tg1Bits, Tg2Bits)-1:0] tg_word2_word_i,
  output logic [tg_word2_bits(Tg1Bits, Tg2Bits)-1:0] tg_word2_word_o,
  output logic [7:0] tg_word2_bits_o,
  input  logic [Tg1Bits-1:0] tg_word2_tg1_i,
  output logic [Tg1Bits-1:0] tg_word2_tg1_o,
  output logic [7:0] tg_word2_tg1_lsb_o,
  input  logic [Tg2Bits-1:0] tg_word2_tg2_i,
  output logic [Tg2Bits-1:0] tg_word2_tg2_o,
  output logic [7:0] tg_word2_tg2_lsb_o,
  input  logic [frame_tc_offset_bits(ReadingBits)-1:0] frame_tc_offset_word_i,
  output logic [frame_tc_offset_bits(ReadingBits)-1:0] frame_tc_offset_word_o,
  output logic [7:0] frame_tc_offset_bits_o,
  input  logic [ReadingBits-1:0] frame_tc_offset_reading_i,
  output logic [ReadingBits-1:0] frame_tc_offset_reading_o,
  output logic [7:0] frame_tc_offset_reading_lsb_o,
  input  logic [ReadingBits-1:0] frame_tc_offset_t_ref_i,
  output logic [ReadingBits-1:0] frame_tc_offset_t_ref_o,
  output logic [7:0] frame_tc_offset_t_ref_lsb_o,
  input  logic [housing_word_bits(Th1Bits, ThxBits, Th2Bits)-1:0] housing_word_word_i,
  output logic [housing_word_bits(Th1Bits, ThxBits, Th2Bits)-1:0] housing_word_word_o,
  output logic [7:0] housing_word_bits_o,
  input  logic [Th1Bits-1:0] housing_word_th1_i,
  output logic [Th1Bits-1:0] housing_word_th1_o,
  output logic [7:0] housing_word_th1_lsb_o,
  input  logic [ThxBits-1:0] housing_word_thx_i,
  output logic [ThxBits-1:0] housing_word_thx_o,
  output logic [7:0] housing_word_thx_lsb_o,
  input  logic [Th2Bits-1:0] housing_word_th2_i,
  output logic [Th2Bits-1:0] housing_word_th2_o,
  output logic [7:0] housing_word_th2_lsb_o,
  input  logic [frame_tc_housing_bits(ReadingBits, HousingBits)-1:0] frame_tc_housing_word_i,
  output logic [frame_tc_housing_bits(ReadingBits, HousingBits)-1:0] frame_tc_housing_word_o,
  output logic [7:0] frame_tc_housing_bits_o,
  input  logic [ReadingBits-1:0] frame_tc_housing_reading_i,
  output logic [ReadingBits-1:0] frame_tc_housing_reading_o,
  output logic [7:0] frame_tc_housing_reading_lsb_o,
  input  logic [ReadingBits-1:0] frame_tc_housing_t_ref_i,
  output logic [ReadingBits-1:0] frame_tc_housing_t_ref_o,
  output logic [7:0] frame_tc_housing_t_ref_lsb_o,
  input  logic [HousingBits-1:0] frame_tc_housing_housing_reading_i,
  output logic [HousingBits-1:0] frame_tc_housing_housing_reading_o,
  output logic [7:0] frame_tc_housing_housing_reading_lsb_o,
  input  logic [HousingBits-1:0] frame_tc_housing_h_ref_i,
  output logic [HousingBits-1:0] frame_tc_housing_h_ref_o,
  output logic [7:0] frame_tc_housing_h_ref_lsb_o,
  input  logic [frame_blind_drift_bits(BaseBits, SumBits, DriftGainBits)-1:0] frame_blind_drift_word_i,
  output logic [frame_blind_drift_bits(BaseBits, SumBits, DriftGainBits)-1:0] frame_blind_drift_word_o,
  output logic [7:0] frame_blind_drift_bits_o,
  input  logic [BaseBits-1:0] frame_blind_drift_base_i,
  output logic [BaseBits-1:0] frame_blind_drift_base_o,
  output logic [7:0] frame_blind_drift_base_lsb_o,
  input  logic [SumBits-1:0] frame_blind_drift_blind_sum_i,
  output logic [SumBits-1:0] frame_blind_drift_blind_sum_o,
  output logic [7:0] frame_blind_drift_blind_sum_lsb_o,
  input  logic [SumBits-1:0] frame_blind_drift_blind_ref_i,
  output logic [SumBits-1:0] frame_blind_drift_blind_ref_o,
  output logic [7:0] frame_blind_drift_blind_ref_lsb_o,
  input  logic [DriftGainBits-1:0] frame_blind_drift_drift_gain_i,
  output logic [DriftGainBits-1:0] frame_blind_drift_drift_gain_o,
  output logic [7:0] frame_blind_drift_drift_gain_lsb_o,
  output logic [64:1][7:0] mul_chunks_o,
  output logic [24:1][7:0] dpc_recip_shift_o,
  input  logic [3:0] recip_n_i,
  output logic [RecBits-1:0] recip_o
);

  assign const_mul_chunk_bits_o = 32'(MulChunkBits);
  assign const_frame_dim_max_o = 32'(FrameDimMax);
  assign const_dpc_recip_guard_bits_o = 32'(DpcRecipGuardBits);
  assign const_sum_bits_max_o = 32'(SumBitsMax);
  assign const_reg_map_id_o = 32'(RegMapId);
  assign const_reg_map_major_o = 32'(RegMapMajor);
  assign const_reg_map_minor_o = 32'(RegMapMinor);
  assign const_reg_addr_bits_o = 32'(RegAddrBits);
  assign const_reg_slot_count_o = 32'(RegSlotCount);
  assign const_reg_id_offset_o = 32'(RegIdOffset);
  assign const_reg_id_value_lsb_o = 32'(RegIdValueLsb);
  assign const_reg_id_value_bits_o = 32'(RegIdValueBits);
  assign const_reg_version_offset_o = 32'(RegVersionOffset);
  assign const_reg_version_minor_lsb_o = 32'(RegVersionMinorLsb);
  assign const_reg_version_minor_bits_o = 32'(RegVersionMinorBits);
  assign const_reg_version_major_lsb_o = 32'(RegVersionMajorLsb);
  assign const_reg_version_major_bits_o = 32'(RegVersionMajorBits);
  assign const_reg_version_coef_layout_lsb_o = 32'(RegVersionCoefLayoutLsb);
  assign const_reg_version_coef_layout_bits_o = 32'(RegVersionCoefLayoutBits);
  assign const_reg_config_offset_o = 32'(RegConfigOffset);
  assign const_reg_config_adc_bits_lsb_o = 32'(RegConfigAdcBitsLsb);
  assign const_reg_config_adc_bits_bits_o = 32'(RegConfigAdcBitsBits);
  assign const_reg_config_out_bits_lsb_o = 32'(RegConfigOutBitsLsb);
  assign const_reg_config_out_bits_bits_o = 32'(RegConfigOutBitsBits);
  assign const_reg_config_word_bits_lsb_o = 32'(RegConfigWordBitsLsb);
  assign const_reg_config_word_bits_bits_o = 32'(RegConfigWordBitsBits);
  assign const_reg_config_method_lsb_o = 32'(RegConfigMethodLsb);
  assign const_reg_config_method_bits_o = 32'(RegConfigMethodBits);
  assign const_reg_config_blind_drift_lsb_o = 32'(RegConfigBlindDriftLsb);
  assign const_reg_config_ffc_lsb_o = 32'(RegConfigFfcLsb);
  assign const_reg_config_rounding_lsb_o = 32'(RegConfigRoundingLsb);
  assign const_reg_config_rounding_bits_o = 32'(RegConfigRoundingBits);
  assign const_reg_config_overflow_lsb_o = 32'(RegConfigOverflowLsb);
  assign const_reg_format_offset_o = 32'(RegFormatOffset);
  assign const_reg_format_gain_int_bits_lsb_o = 32'(RegFormatGainIntBitsLsb);
  assign const_reg_format_gain_int_bits_bits_o = 32'(RegFormatGainIntBitsBits);
  assign const_reg_format_gain_frac_bits_lsb_o = 32'(RegFormatGainFracBitsLsb);
  assign const_reg_format_gain_frac_bits_bits_o = 32'(RegFormatGainFracBitsBits);
  assign const_reg_format_offset_int_bits_lsb_o = 32'(RegFormatOffsetIntBitsLsb);
  assign const_reg_format_offset_int_bits_bits_o = 32'(RegFormatOffsetIntBitsBits);
  assign const_reg_format_offset_frac_bits_lsb_o = 32'(RegFormatOffsetFracBitsLsb);
  assign const_reg_format_offset_frac_bits_bits_o = 32'(RegFormatOffsetFracBitsBits);
  assign const_reg_frame_max_offset_o = 32'(RegFrameMaxOffset);
  assign const_reg_frame_max_width_lsb_o = 32'(RegFrameMaxWidthLsb);
  assign const_reg_frame_max_width_bits_o = 32'(RegFrameMaxWidthBits);
  assign const_reg_frame_max_height_lsb_o = 32'(RegFrameMaxHeightLsb);
  assign const_reg_frame_max_height_bits_o = 32'(RegFrameMaxHeightBits);
  assign const_reg_ctrl_offset_o = 32'(RegCtrlOffset);
  assign const_reg_ctrl_nuc_en_lsb_o = 32'(RegCtrlNucEnLsb);
  assign const_reg_ctrl_nuc_en_reset_o = 32'(RegCtrlNucEnReset);
  assign const_reg_ctrl_dpc_en_lsb_o = 32'(RegCtrlDpcEnLsb);
  assign const_reg_ctrl_dpc_en_reset_o = 32'(RegCtrlDpcEnReset);
  assign const_reg_ctrl_coef_sync_lsb_o = 32'(RegCtrlCoefSyncLsb);
  assign const_reg_ctrl_coef_sync_reset_o = 32'(RegCtrlCoefSyncReset);
  assign const_reg_frame_size_offset_o = 32'(RegFrameSizeOffset);
  assign const_reg_frame_size_width_lsb_o = 32'(RegFrameSizeWidthLsb);
  assign const_reg_frame_size_width_bits_o = 32'(RegFrameSizeWidthBits);
  assign const_reg_frame_size_height_lsb_o = 32'(RegFrameSizeHeightLsb);
  assign const_reg_frame_size_height_bits_o = 32'(RegFrameSizeHeightBits);
  assign const_reg_command_offset_o = 32'(RegCommandOffset);
  assign const_reg_command_clear_counters_lsb_o = 32'(RegCommandClearCountersLsb);
  assign const_reg_status_offset_o = 32'(RegStatusOffset);
  assign const_reg_status_sof_early_lsb_o = 32'(RegStatusSofEarlyLsb);
  assign const_reg_status_sof_early_reset_o = 32'(RegStatusSofEarlyReset);
  assign const_reg_status_sof_late_lsb_o = 32'(RegStatusSofLateLsb);
  assign const_reg_status_sof_late_reset_o = 32'(RegStatusSofLateReset);
  assign const_reg_status_eol_early_lsb_o = 32'(RegStatusEolEarlyLsb);
  assign const_reg_status_eol_early_reset_o = 32'(RegStatusEolEarlyReset);
  assign const_reg_status_eol_late_lsb_o = 32'(RegStatusEolLateLsb);
  assign const_reg_status_eol_late_reset_o = 32'(RegStatusEolLateReset);
  assign const_reg_status_coef_early_lsb_o = 32'(RegStatusCoefEarlyLsb);
  assign const_reg_status_coef_early_reset_o = 32'(RegStatusCoefEarlyReset);
  assign const_reg_status_coef_late_lsb_o = 32'(RegStatusCoefLateLsb);
  assign const_reg_status_coef_late_reset_o = 32'(RegStatusCoefLateReset);
  assign const_reg_status_core_err_lsb_o = 32'(RegStatusCoreErrLsb);
  assign const_reg_status_in_frame_lsb_o = 32'(RegStatusInFrameLsb);
  assign const_reg_status_pending_lsb_o = 32'(RegStatusPendingLsb);
  assign const_reg_irq_enable_offset_o = 32'(RegIrqEnableOffset);
  assign const_reg_irq_enable_error_lsb_o = 32'(RegIrqEnableErrorLsb);
  assign const_reg_irq_enable_error_reset_o = 32'(RegIrqEnableErrorReset);
  assign const_reg_irq_enable_frame_done_lsb_o = 32'(RegIrqEnableFrameDoneLsb);
  assign const_reg_irq_enable_frame_done_reset_o = 32'(RegIrqEnableFrameDoneReset);
  assign const_reg_irq_enable_ffc_done_lsb_o = 32'(RegIrqEnableFfcDoneLsb);
  assign const_reg_irq_enable_ffc_done_reset_o = 32'(RegIrqEnableFfcDoneReset);
  assign const_reg_irq_enable_ffc_request_lsb_o = 32'(RegIrqEnableFfcRequestLsb);
  assign const_reg_irq_enable_ffc_request_reset_o = 32'(RegIrqEnableFfcRequestReset);
  assign const_reg_irq_status_offset_o = 32'(RegIrqStatusOffset);
  assign const_reg_irq_status_error_lsb_o = 32'(RegIrqStatusErrorLsb);
  assign const_reg_irq_status_error_reset_o = 32'(RegIrqStatusErrorReset);
  assign const_reg_irq_status_frame_done_lsb_o = 32'(RegIrqStatusFrameDoneLsb);
  assign const_reg_irq_status_frame_done_reset_o = 32'(RegIrqStatusFrameDoneReset);
  assign const_reg_irq_status_ffc_done_lsb_o = 32'(RegIrqStatusFfcDoneLsb);
  assign const_reg_irq_status_ffc_done_reset_o = 32'(RegIrqStatusFfcDoneReset);
  assign const_reg_irq_status_ffc_request_lsb_o = 32'(RegIrqStatusFfcRequestLsb);
  assign const_reg_irq_status_ffc_request_reset_o = 32'(RegIrqStatusFfcRequestReset);
  assign const_reg_frames_in_offset_o = 32'(RegFramesInOffset);
  assign const_reg_frames_in_count_lsb_o = 32'(RegFramesInCountLsb);
  assign const_reg_frames_in_count_bits_o = 32'(RegFramesInCountBits);
  assign const_reg_frames_out_offset_o = 32'(RegFramesOutOffset);
  assign const_reg_frames_out_count_lsb_o = 32'(RegFramesOutCountLsb);
  assign const_reg_frames_out_count_bits_o = 32'(RegFramesOutCountBits);
  assign const_reg_pixels_in_offset_o = 32'(RegPixelsInOffset);
  assign const_reg_pixels_in_count_lsb_o = 32'(RegPixelsInCountLsb);
  assign const_reg_pixels_in_count_bits_o = 32'(RegPixelsInCountBits);
  assign const_reg_pixels_out_offset_o = 32'(RegPixelsOutOffset);
  assign const_reg_pixels_out_count_lsb_o = 32'(RegPixelsOutCountLsb);
  assign const_reg_pixels_out_count_bits_o = 32'(RegPixelsOutCountBits);
  assign const_reg_dropped_offset_o = 32'(RegDroppedOffset);
  assign const_reg_dropped_count_lsb_o = 32'(RegDroppedCountLsb);
  assign const_reg_dropped_count_bits_o = 32'(RegDroppedCountBits);
  assign const_reg_padded_offset_o = 32'(RegPaddedOffset);
  assign const_reg_padded_count_lsb_o = 32'(RegPaddedCountLsb);
  assign const_reg_padded_count_bits_o = 32'(RegPaddedCountBits);
  assign const_reg_sof_errors_offset_o = 32'(RegSofErrorsOffset);
  assign const_reg_sof_errors_early_lsb_o = 32'(RegSofErrorsEarlyLsb);
  assign const_reg_sof_errors_early_bits_o = 32'(RegSofErrorsEarlyBits);
  assign const_reg_sof_errors_late_lsb_o = 32'(RegSofErrorsLateLsb);
  assign const_reg_sof_errors_late_bits_o = 32'(RegSofErrorsLateBits);
  assign const_reg_eol_errors_offset_o = 32'(RegEolErrorsOffset);
  assign const_reg_eol_errors_early_lsb_o = 32'(RegEolErrorsEarlyLsb);
  assign const_reg_eol_errors_early_bits_o = 32'(RegEolErrorsEarlyBits);
  assign const_reg_eol_errors_late_lsb_o = 32'(RegEolErrorsLateLsb);
  assign const_reg_eol_errors_late_bits_o = 32'(RegEolErrorsLateBits);
  assign const_reg_coef_errors_offset_o = 32'(RegCoefErrorsOffset);
  assign const_reg_coef_errors_early_lsb_o = 32'(RegCoefErrorsEarlyLsb);
  assign const_reg_coef_errors_early_bits_o = 32'(RegCoefErrorsEarlyBits);
  assign const_reg_coef_errors_late_lsb_o = 32'(RegCoefErrorsLateLsb);
  assign const_reg_coef_errors_late_bits_o = 32'(RegCoefErrorsLateBits);
  assign const_reg_ffc_ctrl_offset_o = 32'(RegFfcCtrlOffset);
  assign const_reg_ffc_ctrl_start_lsb_o = 32'(RegFfcCtrlStartLsb);
  assign const_reg_ffc_ctrl_frames_lsb_o = 32'(RegFfcCtrlFramesLsb);
  assign const_reg_ffc_ctrl_frames_bits_o = 32'(RegFfcCtrlFramesBits);
  assign const_reg_ffc_status_offset_o = 32'(RegFfcStatusOffset);
  assign const_reg_ffc_status_busy_lsb_o = 32'(RegFfcStatusBusyLsb);
  assign const_reg_ffc_status_done_lsb_o = 32'(RegFfcStatusDoneLsb);
  assign const_reg_ffc_period_offset_o = 32'(RegFfcPeriodOffset);
  assign const_reg_ffc_period_frames_lsb_o = 32'(RegFfcPeriodFramesLsb);
  assign const_reg_ffc_period_frames_bits_o = 32'(RegFfcPeriodFramesBits);
  assign const_reg_ffc_period_frames_reset_o = 32'(RegFfcPeriodFramesReset);
  assign const_reg_ffc_threshold_offset_o = 32'(RegFfcThresholdOffset);
  assign const_reg_ffc_threshold_codes_lsb_o = 32'(RegFfcThresholdCodesLsb);
  assign const_reg_ffc_threshold_codes_bits_o = 32'(RegFfcThresholdCodesBits);
  assign const_reg_ffc_threshold_codes_reset_o = 32'(RegFfcThresholdCodesReset);
  assign const_reg_ffc_trigger_offset_o = 32'(RegFfcTriggerOffset);
  assign const_reg_ffc_trigger_since_lsb_o = 32'(RegFfcTriggerSinceLsb);
  assign const_reg_ffc_trigger_since_bits_o = 32'(RegFfcTriggerSinceBits);
  assign const_reg_ffc_trigger_period_lsb_o = 32'(RegFfcTriggerPeriodLsb);
  assign const_reg_ffc_trigger_threshold_lsb_o = 32'(RegFfcTriggerThresholdLsb);
  assign const_reg_ffc_ref_offset_o = 32'(RegFfcRefOffset);
  assign const_reg_ffc_ref_reading_lsb_o = 32'(RegFfcRefReadingLsb);
  assign const_reg_ffc_ref_reading_bits_o = 32'(RegFfcRefReadingBits);
  assign const_reg_gain_lo_offset_o = 32'(RegGainLoOffset);
  assign const_reg_gain_hi_offset_o = 32'(RegGainHiOffset);
  assign const_reg_level_lo_offset_o = 32'(RegLevelLoOffset);
  assign const_reg_level_hi_offset_o = 32'(RegLevelHiOffset);
  assign const_reg_reading_lo_offset_o = 32'(RegReadingLoOffset);
  assign const_reg_reading_hi_offset_o = 32'(RegReadingHiOffset);
  assign const_reg_t_ref_lo_offset_o = 32'(RegTRefLoOffset);
  assign const_reg_t_ref_hi_offset_o = 32'(RegTRefHiOffset);
  assign const_reg_blind_sum_lo_offset_o = 32'(RegBlindSumLoOffset);
  assign const_reg_blind_sum_hi_offset_o = 32'(RegBlindSumHiOffset);
  assign const_reg_blind_ref_lo_offset_o = 32'(RegBlindRefLoOffset);
  assign const_reg_blind_ref_hi_offset_o = 32'(RegBlindRefHiOffset);
  assign const_reg_drift_gain_lo_offset_o = 32'(RegDriftGainLoOffset);
  assign const_reg_drift_gain_hi_offset_o = 32'(RegDriftGainHiOffset);
  assign const_reg_ffc_target_lo_offset_o = 32'(RegFfcTargetLoOffset);
  assign const_reg_ffc_target_hi_offset_o = 32'(RegFfcTargetHiOffset);
  assign const_reg_housing_reading_lo_offset_o = 32'(RegHousingReadingLoOffset);
  assign const_reg_housing_reading_hi_offset_o = 32'(RegHousingReadingHiOffset);
  assign const_reg_h_ref_lo_offset_o = 32'(RegHRefLoOffset);
  assign const_reg_h_ref_hi_offset_o = 32'(RegHRefHiOffset);
  assign const_reg_table_reading_offset_o = 32'(RegTableReadingOffset);
  assign const_reg_table_reading_stride_o = 32'(RegTableReadingStride);
  assign const_reg_table_reading_count_o = 32'(RegTableReadingCount);
  assign const_reg_table_sel_offset_o = 32'(RegTableSelOffset);
  assign const_reg_table_sel_weight_lsb_o = 32'(RegTableSelWeightLsb);
  assign const_reg_table_sel_weight_bits_o = 32'(RegTableSelWeightBits);
  assign const_reg_table_sel_j_lsb_o = 32'(RegTableSelJLsb);
  assign const_reg_table_sel_j_bits_o = 32'(RegTableSelJBits);
  assign const_reg_table_sel_valid_lsb_o = 32'(RegTableSelValidLsb);
  assign const_reg_table_sel_error_lsb_o = 32'(RegTableSelErrorLsb);
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
  assign enum_methodonepoint_o = MethodOnePoint;
  assign enum_methodtwopoint_o = MethodTwoPoint;
  assign enum_methodpiecewise_o = MethodPiecewise;
  assign enum_methodquadratic_o = MethodQuadratic;
  assign enum_methodtcoffset_o = MethodTcOffset;
  assign enum_methodtableinterp_o = MethodTableInterp;
  assign enum_methodtchousing_o = MethodTcHousing;
  assign const_method_count_o = 32'(MethodCount);
  method_e method_any;
  assign method_any = MethodOnePoint;
  assign count_method_e_o = 8'(method_any.num());
  logic unused_method;
  assign unused_method = ^method_any;  // num() is of the type
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
  typedef coef_one_point#(OffsetBits)::word_t coef_one_point_t;
  coef_one_point_t coef_one_point_packed, coef_one_point_unpacked;
  assign coef_one_point_word_o = coef_one_point_packed;
  assign coef_one_point_unpacked = coef_one_point_t'(coef_one_point_word_i);
  assign coef_one_point_bits_o = 8'($bits(coef_one_point_t));
  assign coef_one_point_offset_o = coef_one_point_unpacked.offset;
  assign coef_one_point_offset_lsb_o = 8'(coef_one_point_offset_lsb());
  assign coef_one_point_bad_o = coef_one_point_unpacked.bad;
  assign coef_one_point_bad_lsb_o = 8'(coef_one_point_bad_lsb(OffsetBits));
  always_comb begin : p_pack_coef_one_point
    coef_one_point_packed = '0;
    coef_one_point_packed.offset = coef_one_point_offset_i;
    coef_one_point_packed.bad = coef_one_point_bad_i;
  end
  typedef coef_piecewise#(GainBits, KneeBits)::word_t coef_piecewise_t;
  coef_piecewise_t coef_piecewise_packed, coef_piecewise_unpacked;
  assign coef_piecewise_word_o = coef_piecewise_packed;
  assign coef_piecewise_unpacked = coef_piecewise_t'(coef_piecewise_word_i);
  assign coef_piecewise_bits_o = 8'($bits(coef_piecewise_t));
  assign coef_piecewise_gain_lo_o = coef_piecewise_unpacked.gain_lo;
  assign coef_piecewise_gain_lo_lsb_o = 8'(coef_piecewise_gain_lo_lsb());
  assign coef_piecewise_gain_hi_o = coef_piecewise_unpacked.gain_hi;
  assign coef_piecewise_gain_hi_lsb_o = 8'(coef_piecewise_gain_hi_lsb(GainBits));
  assign coef_piecewise_knee_o = coef_piecewise_unpacked.knee;
  assign coef_piecewise_knee_lsb_o = 8'(coef_piecewise_knee_lsb(GainBits));
  assign coef_piecewise_bad_o = coef_piecewise_unpacked.bad;
  assign coef_piecewise_bad_lsb_o = 8'(coef_piecewise_bad_lsb(GainBits, KneeBits));
  always_comb begin : p_pack_coef_piecewise
    coef_piecewise_packed = '0;
    coef_piecewise_packed.gain_lo = coef_piecewise_gain_lo_i;
    coef_piecewise_packed.gain_hi = coef_piecewise_gain_hi_i;
    coef_piecewise_packed.knee = coef_piecewise_knee_i;
    coef_piecewise_packed.bad = coef_piecewise_bad_i;
  end
  typedef quad_word#(QuadBits)::word_t quad_word_t;
  quad_word_t quad_word_packed, quad_word_unpacked;
  assign quad_word_word_o = quad_word_packed;
  assign quad_word_unpacked = quad_word_t'(quad_word_word_i);
  assign quad_word_bits_o = 8'($bits(quad_word_t));
  assign quad_word_quad_o = quad_word_unpacked.quad;
  assign quad_word_quad_lsb_o = 8'(quad_word_quad_lsb());
  always_comb begin : p_pack_quad_word
    quad_word_packed = '0;
    quad_word_packed.quad = quad_word_quad_i;
  end
  typedef tc_word1#(Tc1Bits)::word_t tc_word1_t;
  tc_word1_t tc_word1_packed, tc_word1_unpacked;
  assign tc_word1_word_o = tc_word1_packed;
  assign tc_word1_unpacked = tc_word1_t'(tc_word1_word_i);
  assign tc_word1_bits_o = 8'($bits(tc_word1_t));
  assign tc_word1_tc1_o = tc_word1_unpacked.tc1;
  assign tc_word1_tc1_lsb_o = 8'(tc_word1_tc1_lsb());
  always_comb begin : p_pack_tc_word1
    tc_word1_packed = '0;
    tc_word1_packed.tc1 = tc_word1_tc1_i;
  end
  typedef tc_word2#(Tc1Bits, Tc2Bits)::word_t tc_word2_t;
  tc_word2_t tc_word2_packed, tc_word2_unpacked;
  assign tc_word2_word_o = tc_word2_packed;
  assign tc_word2_unpacked = tc_word2_t'(tc_word2_word_i);
  assign tc_word2_bits_o = 8'($bits(tc_word2_t));
  assign tc_word2_tc1_o = tc_word2_unpacked.tc1;
  assign tc_word2_tc1_lsb_o = 8'(tc_word2_tc1_lsb());
  assign tc_word2_tc2_o = tc_word2_unpacked.tc2;
  assign tc_word2_tc2_lsb_o = 8'(tc_word2_tc2_lsb(Tc1Bits));
  always_comb begin : p_pack_tc_word2
    tc_word2_packed = '0;
    tc_word2_packed.tc1 = tc_word2_tc1_i;
    tc_word2_packed.tc2 = tc_word2_tc2_i;
  end
  typedef tg_word1#(Tg1Bits)::word_t tg_word1_t;
  tg_word1_t tg_word1_packed, tg_word1_unpacked;
  assign tg_word1_word_o = tg_word1_packed;
  assign tg_word1_unpacked = tg_word1_t'(tg_word1_word_i);
  assign tg_word1_bits_o = 8'($bits(tg_word1_t));
  assign tg_word1_tg1_o = tg_word1_unpacked.tg1;
  assign tg_word1_tg1_lsb_o = 8'(tg_word1_tg1_lsb());
  always_comb begin : p_pack_tg_word1
    tg_word1_packed = '0;
    tg_word1_packed.tg1 = tg_word1_tg1_i;
  end
  typedef tg_word2#(Tg1Bits, Tg2Bits)::word_t tg_word2_t;
  tg_word2_t tg_word2_packed, tg_word2_unpacked;
  assign tg_word2_word_o = tg_word2_packed;
  assign tg_word2_unpacked = tg_word2_t'(tg_word2_word_i);
  assign tg_word2_bits_o = 8'($bits(tg_word2_t));
  assign tg_word2_tg1_o = tg_word2_unpacked.tg1;
  assign tg_word2_tg1_lsb_o = 8'(tg_word2_tg1_lsb());
  assign tg_word2_tg2_o = tg_word2_unpacked.tg2;
  assign tg_word2_tg2_lsb_o = 8'(tg_word2_tg2_lsb(Tg1Bits));
  always_comb begin : p_pack_tg_word2
    tg_word2_packed = '0;
    tg_word2_packed.tg1 = tg_word2_tg1_i;
    tg_word2_packed.tg2 = tg_word2_tg2_i;
  end
  typedef frame_tc_offset#(ReadingBits)::word_t frame_tc_offset_t;
  frame_tc_offset_t frame_tc_offset_packed, frame_tc_offset_unpacked;
  assign frame_tc_offset_word_o = frame_tc_offset_packed;
  assign frame_tc_offset_unpacked = frame_tc_offset_t'(frame_tc_offset_word_i);
  assign frame_tc_offset_bits_o = 8'($bits(frame_tc_offset_t));
  assign frame_tc_offset_reading_o = frame_tc_offset_unpacked.reading;
  assign frame_tc_offset_reading_lsb_o = 8'(frame_tc_offset_reading_lsb());
  assign frame_tc_offset_t_ref_o = frame_tc_offset_unpacked.t_ref;
  assign frame_tc_offset_t_ref_lsb_o = 8'(frame_tc_offset_t_ref_lsb(ReadingBits));
  always_comb begin : p_pack_frame_tc_offset
    frame_tc_offset_packed = '0;
    frame_tc_offset_packed.reading = frame_tc_offset_reading_i;
    frame_tc_offset_packed.t_ref = frame_tc_offset_t_ref_i;
  end
  typedef housing_word#(Th1Bits, ThxBits, Th2Bits)::word_t housing_word_t;
  housing_word_t housing_word_packed, housing_word_unpacked;
  assign housing_word_word_o = housing_word_packed;
  assign housing_word_unpacked = housing_word_t'(housing_word_word_i);
  assign housing_word_bits_o = 8'($bits(housing_word_t));
  assign housing_word_th1_o = housing_word_unpacked.th1;
  assign housing_word_th1_lsb_o = 8'(housing_word_th1_lsb());
  assign housing_word_thx_o = housing_word_unpacked.thx;
  assign housing_word_thx_lsb_o = 8'(housing_word_thx_lsb(Th1Bits));
  assign housing_word_th2_o = housing_word_unpacked.th2;
  assign housing_word_th2_lsb_o = 8'(housing_word_th2_lsb(Th1Bits, ThxBits));
  always_comb begin : p_pack_housing_word
    housing_word_packed = '0;
    housing_word_packed.th1 = housing_word_th1_i;
    housing_word_packed.thx = housing_word_thx_i;
    housing_word_packed.th2 = housing_word_th2_i;
  end
  typedef frame_tc_housing#(ReadingBits, HousingBits)::word_t frame_tc_housing_t;
  frame_tc_housing_t frame_tc_housing_packed, frame_tc_housing_unpacked;
  assign frame_tc_housing_word_o = frame_tc_housing_packed;
  assign frame_tc_housing_unpacked = frame_tc_housing_t'(frame_tc_housing_word_i);
  assign frame_tc_housing_bits_o = 8'($bits(frame_tc_housing_t));
  assign frame_tc_housing_reading_o = frame_tc_housing_unpacked.reading;
  assign frame_tc_housing_reading_lsb_o = 8'(frame_tc_housing_reading_lsb());
  assign frame_tc_housing_t_ref_o = frame_tc_housing_unpacked.t_ref;
  assign frame_tc_housing_t_ref_lsb_o = 8'(frame_tc_housing_t_ref_lsb(ReadingBits));
  assign frame_tc_housing_housing_reading_o = frame_tc_housing_unpacked.housing_reading;
  assign frame_tc_housing_housing_reading_lsb_o = 8'(frame_tc_housing_housing_reading_lsb(ReadingBits));
  assign frame_tc_housing_h_ref_o = frame_tc_housing_unpacked.h_ref;
  assign frame_tc_housing_h_ref_lsb_o = 8'(frame_tc_housing_h_ref_lsb(ReadingBits, HousingBits));
  always_comb begin : p_pack_frame_tc_housing
    frame_tc_housing_packed = '0;
    frame_tc_housing_packed.reading = frame_tc_housing_reading_i;
    frame_tc_housing_packed.t_ref = frame_tc_housing_t_ref_i;
    frame_tc_housing_packed.housing_reading = frame_tc_housing_housing_reading_i;
    frame_tc_housing_packed.h_ref = frame_tc_housing_h_ref_i;
  end
  typedef frame_blind_drift#(BaseBits, SumBits, DriftGainBits)::word_t frame_blind_drift_t;
  frame_blind_drift_t frame_blind_drift_packed, frame_blind_drift_unpacked;
  assign frame_blind_drift_word_o = frame_blind_drift_packed;
  assign frame_blind_drift_unpacked = frame_blind_drift_t'(frame_blind_drift_word_i);
  assign frame_blind_drift_bits_o = 8'($bits(frame_blind_drift_t));
  assign frame_blind_drift_base_o = frame_blind_drift_unpacked.base;
  assign frame_blind_drift_base_lsb_o = 8'(frame_blind_drift_base_lsb());
  assign frame_blind_drift_blind_sum_o = frame_blind_drift_unpacked.blind_sum;
  assign frame_blind_drift_blind_sum_lsb_o = 8'(frame_blind_drift_blind_sum_lsb(BaseBits));
  assign frame_blind_drift_blind_ref_o = frame_blind_drift_unpacked.blind_ref;
  assign frame_blind_drift_blind_ref_lsb_o = 8'(frame_blind_drift_blind_ref_lsb(BaseBits, SumBits));
  assign frame_blind_drift_drift_gain_o = frame_blind_drift_unpacked.drift_gain;
  assign frame_blind_drift_drift_gain_lsb_o = 8'(frame_blind_drift_drift_gain_lsb(BaseBits, SumBits));
  always_comb begin : p_pack_frame_blind_drift
    frame_blind_drift_packed = '0;
    frame_blind_drift_packed.base = frame_blind_drift_base_i;
    frame_blind_drift_packed.blind_sum = frame_blind_drift_blind_sum_i;
    frame_blind_drift_packed.blind_ref = frame_blind_drift_blind_ref_i;
    frame_blind_drift_packed.drift_gain = frame_blind_drift_drift_gain_i;
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
