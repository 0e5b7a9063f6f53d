// table_interp's front (docs/datapath.md "table_interp", nuc_fixed.methods.table_interp): the
// pixel's coefficient word {table j + 1, table j} (each a coef_word: gain, offset, bad) and
// the frame's weight w of table j + 1 (U Wi.Wf, at most 2^Wf: the frame word) to the frame's
// gain and offset of the pixel: table_interp, a pipeline of its latency with its own input
// and output registers. The bad flag is set when either table flags the pixel (the DPC
// replaces a pixel bad in table j or j + 1, the two the frame interpolates between).
// m_user_o = {s_user_i, bad}.
module method_table_interp
  import irnuc_pkg::*;
#(
  // irnuc-params: begin method_table_interp (generated from nuc_fixed.methods; do not edit)
  parameter int unsigned GainIntBits      = 2,
  parameter int unsigned GainFracBits     = 14,
  parameter int unsigned OffsetIntBits    = 12,
  parameter int unsigned OffsetFracBits   = 4,
  parameter int unsigned KneeIntBits      = 14,
  parameter int unsigned KneeFracBits     = 2,
  parameter int unsigned LevelIntBits     = 14,
  parameter int unsigned LevelFracBits    = 4,
  parameter int unsigned QuadIntBits      = 10,
  parameter int unsigned QuadFracBits     = 6,
  parameter int unsigned WeightIntBits    = 1,
  parameter int unsigned WeightFracBits   = 15,
  parameter int unsigned WeightRounding   = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned UserBits         = 1,  // side band passed with the pixel
  // Derived, do not override.
  localparam int unsigned GainBits         = GainIntBits + GainFracBits,
  localparam int unsigned OffsetBits       = OffsetIntBits + OffsetFracBits,
  localparam int unsigned KneeBits         = KneeIntBits + KneeFracBits,
  localparam int unsigned LevelBits        = LevelIntBits + LevelFracBits,
  localparam int unsigned QuadBits         = QuadIntBits + QuadFracBits,
  localparam int unsigned WeightBits       = WeightIntBits + WeightFracBits,
  localparam int unsigned CoefBits         = coef_word_bits(GainBits,
                                                            OffsetBits) + coef_word_bits(GainBits,
                                                            OffsetBits),
  localparam int unsigned FrameBits        = WeightBits
  // irnuc-params: end
) (
  // irnuc-params: ports (generated from nuc_fixed.methods; do not edit)
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // The pixel's coefficient word and its frame's word (read at sof by the top), side band.
  input  logic                  s_valid_i,
  output logic                  s_ready_o,
  input  logic [CoefBits-1:0]   s_coef_i,
  input  logic [FrameBits-1:0]  s_frame_i,
  input  logic [UserBits-1:0]   s_user_i,
  // The coefficients of the core of the method's kind (core_sum's ports: lin gain, offset;
  // quad also quad; pwl gain (g_lo), gain_hi, knee, level; the others 0) and {user, bad}.
  output logic                  m_valid_o,
  input  logic                  m_ready_i,
  output logic [GainBits-1:0]   m_gain_o,
  output logic [GainBits-1:0]   m_gain_hi_o,
  output logic [OffsetBits-1:0] m_offset_o,
  output logic [QuadBits-1:0]   m_quad_o,
  output logic [KneeBits-1:0]   m_knee_o,
  output logic [LevelBits-1:0]  m_level_o,
  output logic [UserBits:0]     m_user_o
  // irnuc-params: end
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (WeightIntBits >= 1)
      else $fatal(1, "method_table_interp: the weight format needs an integer bit (w = 1)");
  end
`endif

  typedef struct packed {
    coef_word#(GainBits, OffsetBits)::word_t upper;  // table j + 1
    coef_word#(GainBits, OffsetBits)::word_t lower;  // table j
  } stream_t;
  stream_t w;
  assign w = s_coef_i;

  table_interp #(
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .WeightFracBits(WeightFracBits),
    .WeightRounding(WeightRounding),
    .UserBits      (UserBits + 1)
  ) u_coef (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .s_valid_i  (s_valid_i),
    .s_ready_o  (s_ready_o),
    .s_gain0_i  (w.lower.gain),
    .s_offset0_i(w.lower.offset),
    .s_gain1_i  (w.upper.gain),
    .s_offset1_i(w.upper.offset),
    .s_weight_i (s_frame_i[WeightFracBits:0]),
    .s_user_i   ({s_user_i, w.lower.bad | w.upper.bad}),
    .m_valid_o  (m_valid_o),
    .m_ready_i  (m_ready_i),
    .m_gain_o   (m_gain_o),
    .m_offset_o (m_offset_o),
    .m_user_o   (m_user_o)
  );

  assign m_gain_hi_o = '0;
  assign m_quad_o    = '0;
  assign m_knee_o    = '0;
  assign m_level_o   = '0;

  // The weight's bits above Wf are 0 (asserted below).
  if (FrameBits > WeightFracBits + 1) begin : gen_weight_high
    logic unused_weight;
    assign unused_weight = ^s_frame_i[FrameBits-1:WeightFracBits+1];
  end

`ifdef IRNUC_ASSERT
  // table_interp's contract (docs/datapath.md), on every pixel taken:
  //   a_weight_range  the frame's weight is at most 2^Wf.
  // The range test sits in the guard as well, so the assertion executes only when it
  // fails: the same obligation (taken -> in range), but at full rate the simulator skips
  // it (Verilator queries its assertion enable once per executed assertion).
  logic armed_q;  // from the second edge after reset
  logic weight_in_range;
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  assign weight_in_range = 64'(s_frame_i) <= (64'd1 << WeightFracBits);
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q && s_valid_i && s_ready_o && !weight_in_range) begin
      a_weight_range: assert (weight_in_range)
        else $error("method_table_interp: weight %0d above 2^%0d", s_frame_i, WeightFracBits);
    end
  end
`endif

endmodule
