// Multiplier cut into DSP-sized partial products, two register stages (the DSP block's
// input and output registers, irnuc_dsp_mul).
//
// a_i and b_i are cut into chunks (irnuc_method_pkg::smul_chunks: 17 unsigned bits each,
// the top chunk of a signed operand with its sign); every chunk product is one signed
// 18 x 18 DSP multiply. parts_o[k] is chunk product k shifted to its weight, sign-extended
// (a signed product) or zero-extended (an unsigned one) to PartBits, so the sum of all
// Parts of them modulo 2^PartBits is a_i * b_i (irnuc_add_tree adds them). Every register
// moves when en_i is high; the valid flag and SideBits of side band travel along, and only
// the valid flags reset.
module irnuc_mul_parts
  import irnuc_method_pkg::smul_chunks;
#(
  parameter int unsigned ABits    = 17,
  parameter int unsigned BBits    = 17,
  parameter bit          ASigned  = 1'b0,
  parameter bit          BSigned  = 1'b0,
  // Width of each part: at least ABits + BBits (one more keeps an unsigned product
  // non-negative when the caller reads the parts as signed).
  parameter int unsigned PartBits = ABits + BBits,
  parameter int unsigned SideBits = 1,
  // Derived, do not override.
  localparam int unsigned AChunks = smul_chunks(ABits, ASigned),
  localparam int unsigned BChunks = smul_chunks(BBits, BSigned),
  localparam int unsigned Parts   = AChunks * BChunks
) (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic                          en_i,
  input  logic                          valid_i,
  input  logic [ABits-1:0]              a_i,
  input  logic [BBits-1:0]              b_i,
  input  logic [SideBits-1:0]           side_i,
  output logic                          valid_o,
  output logic [Parts-1:0][PartBits-1:0] parts_o,
  output logic [SideBits-1:0]           side_o
);

  localparam int unsigned ChunkBits = irnuc_pkg::MulChunkBits;

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (ABits >= 1 && ABits <= 64 && BBits >= 1 && BBits <= 64)
      else $fatal(1, "irnuc_mul_parts: ABits = %0d, BBits = %0d outside 1..64", ABits, BBits);
    assert (PartBits >= ABits + BBits && PartBits <= 64)
      else $fatal(1, "irnuc_mul_parts: PartBits = %0d outside %0d..64", PartBits,
                  ABits + BBits);
    assert (SideBits >= 1)
      else $fatal(1, "irnuc_mul_parts: SideBits = %0d must be at least 1", SideBits);
  end
`endif

  // Chunk k of an operand as an 18-bit signed DSP input: bits [lsb +: width], the top
  // chunk of a signed operand sign-extended, every other chunk zero-extended.
  for (genvar i = 0; i < AChunks; i++) begin : gen_a
    localparam int unsigned ALsb  = i * ChunkBits;
    localparam int unsigned AWide = (i == AChunks - 1) ? ABits - ALsb : ChunkBits;
    localparam bit          ASign = ASigned && (i == AChunks - 1);
    logic signed [17:0] a_chunk;
    if (ASign) begin : gen_sign
      assign a_chunk = 18'($signed(a_i[ALsb +: AWide]));
    end else begin : gen_zero
      assign a_chunk = 18'(a_i[ALsb +: AWide]);
    end

    for (genvar j = 0; j < BChunks; j++) begin : gen_b
      localparam int unsigned BLsb  = j * ChunkBits;
      localparam int unsigned BWide = (j == BChunks - 1) ? BBits - BLsb : ChunkBits;
      localparam bit          BSign = BSigned && (j == BChunks - 1);
      logic signed [17:0] b_chunk;
      logic signed [35:0] part;
      if (BSign) begin : gen_sign
        assign b_chunk = 18'($signed(b_i[BLsb +: BWide]));
      end else begin : gen_zero
        assign b_chunk = 18'(b_i[BLsb +: BWide]);
      end

      irnuc_dsp_mul u_dsp (
        .clk_i(clk_i),
        .en_i (en_i),
        .a_i  (a_chunk),
        .b_i  (b_chunk),
        .p_o  (part)
      );

      // A chunk product of two unsigned chunks is below 2^34: its sign bit is 0, so the
      // sign extension is a zero extension there.
      assign parts_o[i * BChunks + j] = PartBits'(part) << (ALsb + BLsb);
      if (PartBits < 36) begin : gen_part_high
        // The chunk product has at most AWide + BWide + 1 <= PartBits significant bits.
        logic unused_high;
        assign unused_high = ^part[35:PartBits];
      end
    end
  end

  // Valid flag and side band: the DSP's two register stages.
  logic [1:0]               valid_q;
  logic [1:0][SideBits-1:0] side_q;

  always_ff @(posedge clk_i) begin : p_side
    if (en_i) begin
      side_q[0] <= side_i;
      side_q[1] <= side_q[0];
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_valid
    if (!rst_ni) begin
      valid_q <= '0;
    end else if (en_i) begin
      valid_q <= {valid_q[0], valid_i};
    end
  end

  assign valid_o = valid_q[1];
  assign side_o  = side_q[1];

endmodule
