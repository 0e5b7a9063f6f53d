// The input register of an AXI4-Stream port of irnuc_axis_top (and of the streams
// method_ffc_top joins: s_coef, s_foff, s_acc and its pixel stage): a two-entry buffer with the
// cycles of irnuc_spill_register (ready_o = "fewer than two items held", a flop; an item
// taken is at the output the next cycle; one item per clock at valid = ready = 1), built so
// that the consumer's ready_i reaches only a read pointer and the fill flags, never the
// enables of the data registers: each entry is written only from the input side, and the
// output is the older entry, picked by the read pointer (a multiplexer on the data path).
// An entry's enable is two flops: the free entry (the write pointer's, while not full)
// loads the input every cycle, valid or not, and the write pointer moves on a push; so
// valid_i, which reaches the enables of every data bit of a wide word, is not on them
// (data_o while valid_o is low is then the input's last word instead of a stale item). The consumer is the framer, or method_ffc_top's
// join, whose decision to take an item is the deepest logic; with a spill register that
// decision fanned out to the enables of every data bit (the critical path). The input side
// is checked by the user (irnuc_axis_assert, method_ffc_top's stream checkers).
//
// HeadBits > 0: the top HeadBits bits of the data (the markers the consumer decides on, e.g.
// the video's tuser/tlast) come from a register of their own that holds the older entry's
// bits, loaded in the cycle that entry becomes the older one: the consumer's decision
// starts at flops, not behind the read pointer's multiplexer (its ready_i reaches the
// enables of these few bits only).
module irnuc_axis_buffer #(
  parameter int unsigned DataBits = 1,
  parameter int unsigned HeadBits = 0  // top bits from a head register, < DataBits
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  // Input side (the AXI4-Stream port).
  input  logic                valid_i,
  output logic                ready_o,
  input  logic [DataBits-1:0] data_i,
  // Output side.
  output logic                valid_o,
  input  logic                ready_i,
  output logic [DataBits-1:0] data_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (DataBits >= 1)
      else $fatal(1, "irnuc_axis_buffer: DataBits = %0d must be at least 1", DataBits);
    assert (HeadBits < DataBits)
      else $fatal(1, "irnuc_axis_buffer: HeadBits = %0d must be below DataBits = %0d",
                  HeadBits, DataBits);
  end
`endif

  logic [1:0][DataBits-1:0] mem_q;
  logic                     wr_q, rd_q, rd_n_q, full_q, any_q;
  logic                     push, pop;

  assign push = valid_i && !full_q;
  assign pop  = any_q && ready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_state
    if (!rst_ni) begin
      wr_q   <= 1'b0;
      rd_q   <= 1'b0;
      rd_n_q <= 1'b1;
      full_q <= 1'b0;
      any_q  <= 1'b0;
    end else begin
      wr_q <= wr_q ^ push;
      rd_q <= rd_q ^ pop;
      rd_n_q <= !(rd_q ^ pop);
      if (push && !pop) begin
        full_q <= any_q;
        any_q  <= 1'b1;
      end else if (pop && !push) begin
        full_q <= 1'b0;
        any_q  <= full_q;
      end
    end
  end

  // Only the fill flags reset; the entries are qualified by them. While not full, the
  // entry the write pointer names holds no item (the older one, if any, is the other), so
  // loading it without a push changes no item; a push then leaves it as loaded.
  always_ff @(posedge clk_i) begin : p_mem
    if (!full_q) begin
      mem_q[wr_q] <= data_i;
    end
  end

  assign ready_o = !full_q;
  assign valid_o = any_q;
  // The read pointer selects every data bit below the head bits: its complement copy (a
  // distinct flop, which synthesis does not merge with it) selects the upper half, so each
  // drives half the fanout (the wide coefficient words: docs/rtl.md).
  localparam int unsigned MuxBits = DataBits - HeadBits;
  localparam int unsigned Lo      = (MuxBits + 1) / 2;
  assign data_o[Lo-1:0] = mem_q[rd_q][Lo-1:0];
  if (MuxBits > Lo) begin : gen_hi
    assign data_o[MuxBits-1:Lo] = rd_n_q ? mem_q[0][MuxBits-1:Lo] : mem_q[1][MuxBits-1:Lo];
  end else begin : gen_no_hi
    logic unused_rd_n;
    assign unused_rd_n = rd_n_q;
  end

  // The head bits: the older entry's, registered. The register loads when the older entry
  // leaves or none is held: then the entry that becomes the older one is the other entry
  // (two held) or the input (pushed now; with no push, the bits are not valid).
  if (HeadBits > 0) begin : gen_head
    logic [HeadBits-1:0] head_q, head_next;
    assign head_next = full_q ? mem_q[!rd_q][DataBits-1:MuxBits] : data_i[DataBits-1:MuxBits];
    always_ff @(posedge clk_i) begin : p_head
      if (!any_q || ready_i) begin
        head_q <= head_next;
      end
    end
    assign data_o[DataBits-1:MuxBits] = head_q;
`ifdef IRNUC_ASSERT
    // (any_q resets to 0: no check in reset.)
    always_ff @(posedge clk_i) begin : p_check_head
      if (any_q) begin
        a_head: assert (head_q == mem_q[rd_q][DataBits-1:MuxBits])
          else $error("irnuc_axis_buffer: the head bits are not the older entry's");
      end
    end
`endif
  end

`ifdef IRNUC_ASSERT
  // The input side is an AXI4-Stream port (irnuc_axis_assert in the top); the output side:
  irnuc_stream_assert #(.DataBits(DataBits)) u_assert_out (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(valid_o),
    .ready_i(ready_i),
    .data_i (data_o)
  );
  // The read pointer's copy is its complement.
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_rd_copy: assert (rd_n_q == !rd_q)
        else $error("irnuc_axis_buffer: the read pointer's copy is not its complement");
    end
  end
`endif

endmodule
