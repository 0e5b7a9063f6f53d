// Pipelined adder tree: sum_o = the sum of Leaves operands, modulo 2^Width.
//
// The caller extends every leaf to Width bits (zero or sign extension: in two's
// complement the same adder serves signed and unsigned leaves) and makes Width wide
// enough for the sum. One level of pairwise additions per register stage, an odd node
// passes through its level, so Levels = clog2(Leaves) stages (none for a single leaf).
// The valid flag and SideBits of side band travel along. Every register moves when en_i
// is high (the enclosing pipeline's enable); only the valid flags reset.
module irnuc_add_tree #(
  parameter int unsigned Leaves   = 2,
  parameter int unsigned Width    = 8,
  parameter int unsigned SideBits = 1,
  // Derived, do not override.
  localparam int unsigned Levels  = $clog2(Leaves)
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  input  logic                         en_i,
  input  logic                         valid_i,
  input  logic [Leaves-1:0][Width-1:0] leaves_i,
  input  logic [SideBits-1:0]          side_i,
  output logic                         valid_o,
  output logic [Width-1:0]             sum_o,
  output logic [SideBits-1:0]          side_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (Leaves >= 1 && Leaves <= 64)
      else $fatal(1, "irnuc_add_tree: Leaves = %0d outside 1..64", Leaves);
    assert (Width >= 1 && Width <= 64)
      else $fatal(1, "irnuc_add_tree: Width = %0d outside 1..64", Width);
    assert (SideBits >= 1)
      else $fatal(1, "irnuc_add_tree: SideBits = %0d must be at least 1", SideBits);
  end
`endif

  // Nodes of level l (level 0: the leaves).
  function automatic int unsigned nodes(input int unsigned level);
    return (Leaves + (32'd1 << level) - 32'd1) >> level;
  endfunction

  if (Levels == 0) begin : gen_single
    assign valid_o = valid_i;
    assign sum_o   = leaves_i[0];
    assign side_o  = side_i;
    logic unused_clk;
    assign unused_clk = ^{clk_i, rst_ni, en_i};
  end else begin : gen_tree
    for (genvar l = 1; l <= Levels; l++) begin : gen_level
      localparam int unsigned NumIn  = nodes(l - 1);
      localparam int unsigned NumOut = nodes(l);

      // Unpacked: one simulator variable per node (a packed array wider than 64 bits is
      // one wide word that every node access shifts and masks).
      logic [Width-1:0]             node_in [NumIn];
      logic [Width-1:0]             node_q  [NumOut];
      logic [SideBits-1:0]          side_in, side_q;
      logic                         valid_in, valid_q;

      if (l == 1) begin : gen_from_leaves
        for (genvar k = 0; k < NumIn; k++) begin : gen_leaf
          assign node_in[k] = leaves_i[k];
        end
        assign side_in  = side_i;
        assign valid_in = valid_i;
      end else begin : gen_from_level
        assign node_in  = gen_level[l-1].node_q;
        assign side_in  = gen_level[l-1].side_q;
        assign valid_in = gen_level[l-1].valid_q;
      end

      for (genvar k = 0; k < NumOut; k++) begin : gen_node
        if (2 * k + 1 < NumIn) begin : gen_add
          always_ff @(posedge clk_i) begin : p_add
            if (en_i) node_q[k] <= node_in[2*k] + node_in[2*k+1];
          end
        end else begin : gen_pass
          always_ff @(posedge clk_i) begin : p_pass
            if (en_i) node_q[k] <= node_in[2*k];
          end
        end
      end

      always_ff @(posedge clk_i) begin : p_side
        if (en_i) side_q <= side_in;
      end

      always_ff @(posedge clk_i or negedge rst_ni) begin : p_valid
        if (!rst_ni) begin
          valid_q <= 1'b0;
        end else if (en_i) begin
          valid_q <= valid_in;
        end
      end
    end

    assign valid_o = gen_level[Levels].valid_q;
    assign sum_o   = gen_level[Levels].node_q[0];
    assign side_o  = gen_level[Levels].side_q;
  end

endmodule
