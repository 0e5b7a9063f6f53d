// The NUC core of a base method's kind (irnuc_method_pkg::core_kind of the method,
// MethodSpec.core; docs/rtl.md "Methods"): nuc_core (lin), quad_core (quad) or pwl_core
// (pwl) behind the ports of core_sum, on the coefficients of the method's front
// (frame_coefficients): gain (pwl: g_lo), gain_hi, offset, quad, knee and level, a kind
// reading those it has. One pixel per clock; the core's own input and output registers and
// latency. UserBits of side band pass unchanged.
module method_core
  import irnuc_method_pkg::*;
#(
  parameter core_kind_e  Kind           = CoreLin,
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits        = 14,
  parameter int unsigned Rounding       = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned Overflow       = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned KneeIntBits    = 14,
  parameter int unsigned KneeFracBits   = 2,
  parameter int unsigned LevelIntBits   = 14,
  parameter int unsigned LevelFracBits  = 4,
  parameter int unsigned QuadIntBits    = 10,
  parameter int unsigned QuadFracBits   = 6,
  parameter int unsigned SquareBits     = 18,
  parameter int unsigned UserBits       = 1,
  // s_* is checked by the core's input register (0: by the caller, whose driver is a
  // checked spill register).
  parameter bit          CheckIn        = 1'b1,
  // Derived, do not override.
  localparam int unsigned GainBits      = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits    = OffsetIntBits + OffsetFracBits,
  localparam int unsigned KneeBits      = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits     = LevelIntBits + LevelFracBits,
  localparam int unsigned QuadBits      = QuadIntBits + QuadFracBits
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [AdcBits-1:0]    s_pix_data_i,
  input  logic [GainBits-1:0]   s_gain_i,     // g (pwl: g_lo)
  input  logic [GainBits-1:0]   s_gain_hi_i,  // pwl: g_hi
  input  logic [OffsetBits-1:0] s_offset_i,   // lin, quad
  input  logic [QuadBits-1:0]   s_quad_i,     // quad
  input  logic [KneeBits-1:0]   s_knee_i,     // pwl
  input  logic [LevelBits-1:0]  s_level_i,    // pwl
  input  logic [UserBits-1:0]   s_user_i,
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [OutBits-1:0]    m_pix_data_o,
  output logic [UserBits-1:0]   m_user_o
);

  if (Kind == CorePwl) begin : gen_pwl
    pwl_core #(
      .AdcBits      (AdcBits),
      .GainIntBits  (GainIntBits),
      .GainFracBits (GainFracBits),
      .KneeIntBits  (KneeIntBits),
      .KneeFracBits (KneeFracBits),
      .LevelIntBits (LevelIntBits),
      .LevelFracBits(LevelFracBits),
      .OutBits      (OutBits),
      .Rounding     (Rounding),
      .Overflow     (Overflow),
      .UserBits     (UserBits),
      .CheckIn      (CheckIn)
    ) u_nuc (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_pix_data_i(s_pix_data_i),
      .s_gain_lo_i (s_gain_i),
      .s_gain_hi_i (s_gain_hi_i),
      .s_knee_i    (s_knee_i),
      .s_level_i   (s_level_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_pix_data_o(m_pix_data_o),
      .m_user_o    (m_user_o)
    );
    logic unused_pwl;
    assign unused_pwl = ^{s_offset_i, s_quad_i};
  end else if (Kind == CoreQuad) begin : gen_quad
    quad_core #(
      .AdcBits       (AdcBits),
      .GainIntBits   (GainIntBits),
      .GainFracBits  (GainFracBits),
      .OffsetIntBits (OffsetIntBits),
      .OffsetFracBits(OffsetFracBits),
      .QuadIntBits   (QuadIntBits),
      .QuadFracBits  (QuadFracBits),
      .SquareBits    (SquareBits),
      .OutBits       (OutBits),
      .Rounding      (Rounding),
      .Overflow      (Overflow),
      .UserBits      (UserBits),
      .CheckIn       (CheckIn)
    ) u_nuc (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_pix_data_i(s_pix_data_i),
      .s_gain_i    (s_gain_i),
      .s_offset_i  (s_offset_i),
      .s_quad_i    (s_quad_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_pix_data_o(m_pix_data_o),
      .m_user_o    (m_user_o)
    );
    logic unused_quad;
    assign unused_quad = ^{s_gain_hi_i, s_knee_i, s_level_i};
  end else begin : gen_lin
    nuc_core #(
      .AdcBits       (AdcBits),
      .GainIntBits   (GainIntBits),
      .GainFracBits  (GainFracBits),
      .OffsetIntBits (OffsetIntBits),
      .OffsetFracBits(OffsetFracBits),
      .OutBits       (OutBits),
      .Rounding      (Rounding),
      .Overflow      (Overflow),
      .UserBits      (UserBits),
      .CheckIn       (CheckIn)
    ) u_nuc (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .s_valid_i   (s_valid_i),
      .s_ready_o   (s_ready_o),
      .s_pix_data_i(s_pix_data_i),
      .s_gain_i    (s_gain_i),
      .s_offset_i  (s_offset_i),
      .s_user_i    (s_user_i),
      .m_valid_o   (m_valid_o),
      .m_ready_i   (m_ready_i),
      .m_pix_data_o(m_pix_data_o),
      .m_user_o    (m_user_o)
    );
    logic unused_lin;
    assign unused_lin = ^{s_gain_hi_i, s_quad_i, s_knee_i, s_level_i};
  end

endmodule
