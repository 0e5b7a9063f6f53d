// Rounding of a fixed-point value to an integer: r = ROUND_F(s) of docs/datapath.md
// (combinational; the caller registers the result).
//
// s_i is a two's complement number with FracBits fraction bits; r_o = (s >>> F) + inc,
// where adding the mode's rounding constant carries into the integer part exactly when:
//   truncate   never (floor);
//   half_up    the fraction is at least 1/2 (bit F-1);
//   half_even  the fraction is above 1/2, or exactly 1/2 and the integer part is odd.
// r_o has one bit more than the integer part of s (the carry of the largest value).
module irnuc_round #(
  parameter int unsigned InBits   = 8,
  parameter int unsigned FracBits = 0,
  parameter int unsigned Rounding = 1,  // irnuc_pkg::rounding_e
  // Derived, do not override.
  localparam int unsigned OutBits = InBits + 1 - FracBits
) (
  input  logic [InBits-1:0]  s_i,
  output logic [OutBits-1:0] r_o
);

  localparam irnuc_pkg::rounding_e RoundMode = irnuc_pkg::rounding_e'(Rounding);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (InBits >= 1 && InBits <= 64 && FracBits < InBits)
      else $fatal(1, "irnuc_round: InBits = %0d, FracBits = %0d (need 0 <= F < InBits <= 64)",
                  InBits, FracBits);
    assert (Rounding <= 2)
      else $fatal(1, "irnuc_round: Rounding = %0d outside 0..2", Rounding);
  end
`endif

  logic inc;

  if (FracBits == 0 || RoundMode == irnuc_pkg::RoundTruncate) begin : gen_inc_none
    assign inc = 1'b0;
    if (FracBits > 0) begin : gen_frac_unused
      logic unused_frac;
      assign unused_frac = ^s_i[FracBits-1:0];
    end
  end else if (RoundMode == irnuc_pkg::RoundHalfUp) begin : gen_inc_half_up
    assign inc = s_i[FracBits-1];
    if (FracBits > 1) begin : gen_frac_unused
      logic unused_frac;
      assign unused_frac = ^s_i[FracBits-2:0];
    end
  end else begin : gen_inc_half_even
    logic sticky;  // fraction bits below the half
    if (FracBits > 1) begin : gen_sticky
      assign sticky = |s_i[FracBits-2:0];
    end else begin : gen_no_sticky
      assign sticky = 1'b0;
    end
    assign inc = s_i[FracBits-1] & (sticky | s_i[FracBits]);
  end

  // Keeping bits [InBits-1:F] is the arithmetic (floor) shift by F.
  assign r_o = OutBits'($signed(s_i[InBits-1:FracBits])) + OutBits'(inc);

endmodule
