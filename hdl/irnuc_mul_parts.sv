// Unsigned multiplier cut into DSP-sized partial products, one register stage.
//
// a_i and b_i are cut into chunks of irnuc_pkg::MulChunkBits bits; every chunk product
// is one DSP multiply whose inputs come from registers (the caller's) and whose output
// is registered here (moves when en_i is high). parts_o[k] is chunk product k shifted
// to its weight, so the sum of all Parts of them is a_i * b_i (irnuc_add_tree adds them).
// The valid flag and SideBits of side band travel along; only the valid flag resets.
module irnuc_mul_parts
  import irnuc_pkg::*;
#(
  parameter int unsigned ABits    = 17,
  parameter int unsigned BBits    = 17,
  parameter int unsigned SideBits = 1,
  // Derived, do not override.
  localparam int unsigned ProdBits = ABits + BBits,
  localparam int unsigned Parts    = mul_parts(ABits, BBits)
) (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic                          en_i,
  input  logic                          valid_i,
  input  logic [ABits-1:0]              a_i,
  input  logic [BBits-1:0]              b_i,
  input  logic [SideBits-1:0]           side_i,
  output logic                          valid_o,
  output logic [Parts-1:0][ProdBits-1:0] parts_o,
  output logic [SideBits-1:0]           side_o
);

  localparam int unsigned AChunks = mul_chunks(ABits);
  localparam int unsigned BChunks = mul_chunks(BBits);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (ABits >= 1 && ABits <= 64 && BBits >= 1 && BBits <= 64)
      else $fatal(1, "irnuc_mul_parts: ABits = %0d, BBits = %0d outside 1..64", ABits, BBits);
    assert (SideBits >= 1)
      else $fatal(1, "irnuc_mul_parts: SideBits = %0d must be at least 1", SideBits);
  end
`endif

  for (genvar i = 0; i < AChunks; i++) begin : gen_a
    localparam int unsigned ALsb  = i * MulChunkBits;
    localparam int unsigned AWide = (ABits - ALsb < MulChunkBits) ? ABits - ALsb : MulChunkBits;
    for (genvar j = 0; j < BChunks; j++) begin : gen_b
      localparam int unsigned BLsb  = j * MulChunkBits;
      localparam int unsigned BWide = (BBits - BLsb < MulChunkBits) ? BBits - BLsb
                                                                    : MulChunkBits;
      localparam int unsigned PWide = AWide + BWide;

      logic [PWide-1:0] part_q;

      always_ff @(posedge clk_i) begin : p_part
        if (en_i) part_q <= PWide'(a_i[ALsb +: AWide]) * PWide'(b_i[BLsb +: BWide]);
      end

      assign parts_o[i * BChunks + j] = ProdBits'(part_q) << (ALsb + BLsb);
    end
  end

  logic                valid_q;
  logic [SideBits-1:0] side_q;

  always_ff @(posedge clk_i) begin : p_side
    if (en_i) side_q <= side_i;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_valid
    if (!rst_ni) begin
      valid_q <= 1'b0;
    end else if (en_i) begin
      valid_q <= valid_i;
    end
  end

  assign valid_o = valid_q;
  assign side_o  = side_q;

endmodule
