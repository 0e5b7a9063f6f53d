// The end of a core: r = ROUND_F(s) (the pipeline's rounding), registered, then y = OUT(r)
// (saturate or wrap to B bits) into the output register (docs/datapath.md "Cores, per
// pixel", the last step of every core; nuc_fixed.cores.round_out).
//
// The output register (irnuc_axis_buffer: the cycles of irnuc_spill_register) is the
// enclosing pipeline's enable: en_o is its ready_o, a flop, and the rounding register moves
// with it. Its entries are written from the pipeline side only, so m_ready_i (in the stage
// tops a fork over several outputs) reaches its read pointer and flags, not the enables of
// the word's bits. UserBits of side band travel with each item. Latency 2 (the rounding
// register and the output register).
module core_out #(
  parameter int unsigned SumBits  = 40,
  parameter int unsigned FracBits = 14,
  parameter int unsigned OutBits  = 14,
  parameter int unsigned Rounding = 1,  // irnuc_pkg::rounding_e
  parameter int unsigned Overflow = 0,  // irnuc_pkg::overflow_e
  parameter int unsigned UserBits = 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  output logic                en_o,
  input  logic                valid_i,
  input  logic [SumBits-1:0]  sum_i,
  input  logic [UserBits-1:0] user_i,
  output logic                m_valid_o,
  input  logic                m_ready_i,
  output logic [OutBits-1:0]  m_data_o,
  output logic [UserBits-1:0] m_user_o
);

  localparam int unsigned RndBits = SumBits + 1 - FracBits;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (SumBits >= 2 && SumBits <= 64 && FracBits < SumBits)
      else $fatal(1, "core_out: SumBits = %0d, FracBits = %0d out of range", SumBits,
                  FracBits);
    assert (OutBits >= 1 && OutBits <= 32 && UserBits >= 1)
      else $fatal(1, "core_out: OutBits = %0d, UserBits = %0d out of range", OutBits,
                  UserBits);
  end
`endif

  logic [RndBits-1:0]  rnd_d, rnd_q;
  logic                rnd_valid_q;
  logic [UserBits-1:0] rnd_user_q;

  irnuc_round #(
    .InBits  (SumBits),
    .FracBits(FracBits),
    .Rounding(Rounding)
  ) u_round (
    .s_i(sum_i),
    .r_o(rnd_d)
  );

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_round_valid
    if (!rst_ni) begin
      rnd_valid_q <= 1'b0;
    end else if (en_o) begin
      rnd_valid_q <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin : p_round
    if (en_o) begin
      rnd_q      <= rnd_d;
      rnd_user_q <= user_i;
    end
  end

  logic [OutBits-1:0] out_d;

  irnuc_clip #(
    .InBits   (RndBits),
    .OutBits  (OutBits),
    .OutSigned(1'b0),
    .Overflow (Overflow)
  ) u_clip (
    .v_i(rnd_q),
    .y_o(out_d)
  );

  irnuc_axis_buffer #(.DataBits(UserBits + OutBits)) u_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(rnd_valid_q),
    .ready_o(en_o),
    .data_i ({rnd_user_q, out_d}),
    .valid_o(m_valid_o),
    .ready_i(m_ready_i),
    .data_o ({m_user_o, m_data_o})
  );

endmodule
