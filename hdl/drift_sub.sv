// drift_sub of blind_drift, per pixel (docs/datapath.md "drift_sub"; nuc_fixed.cores
// .drift_sub): x' = (x << Df) - delta, delta the frame's drift code (S Di.Df, ADC codes).
// x' is signed with Df fraction bits and is not clamped (a negative x' multiplies as a
// signed value in the core).
//
// A building block of an enclosing pipeline: one register stage moving with en_i, the
// valid flag and SideBits of side band along, only the valid flag reset.
module drift_sub #(
  parameter int unsigned AdcBits       = 14,
  parameter int unsigned DriftIntBits  = 14,
  parameter int unsigned DriftFracBits = 2,
  parameter int unsigned SideBits      = 1,
  // Derived, do not override.
  localparam int unsigned DriftBits    = DriftIntBits + DriftFracBits,
  // max(A + Df + 1, DW) + 1, signed (nuc_fixed.widths.input_x)
  localparam int unsigned XBits        = ((AdcBits + DriftFracBits + 1 > DriftBits)
                                          ? AdcBits + DriftFracBits + 1 : DriftBits) + 1
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 en_i,
  input  logic                 valid_i,
  input  logic [AdcBits-1:0]   x_i,
  input  logic [DriftBits-1:0] delta_i,
  input  logic [SideBits-1:0]  side_i,
  output logic                 valid_o,
  output logic [XBits-1:0]     x_o,
  output logic [SideBits-1:0]  side_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (AdcBits >= 1 && AdcBits <= 32 && DriftIntBits >= 1 && XBits <= 48)
      else $fatal(1, "drift_sub: AdcBits = %0d, drift S%0d.%0d out of range", AdcBits,
                  DriftIntBits, DriftFracBits);
    assert (SideBits >= 1)
      else $fatal(1, "drift_sub: SideBits = %0d must be at least 1", SideBits);
  end
`endif

  logic                valid_q;
  logic [XBits-1:0]    x_q;
  logic [SideBits-1:0] side_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_valid
    if (!rst_ni) begin
      valid_q <= 1'b0;
    end else if (en_i) begin
      valid_q <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin : p_sub
    if (en_i) begin
      // x is unsigned (zero extension), delta two's complement (sign extension).
      x_q    <= (XBits'(x_i) << DriftFracBits) - XBits'($signed(delta_i));
      side_q <= side_i;
    end
  end

  assign valid_o = valid_q;
  assign x_o     = x_q;
  assign side_o  = side_q;

endmodule
