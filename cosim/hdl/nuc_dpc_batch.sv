// Simulation-only transactor around nuc_dpc_top for batched cocotb co-simulation
// (cocotb_tests/tb_batch.py): Python wakes once every Batch cycles instead of every cycle.
// Not part of the design; the DUT's ports and protocol assertions are unchanged.
//
// Command (cmd_i, written by Python once per window, LSB first):
//   [0]          tag: a command is taken at the first edge where it differs from the last
//                one taken; that edge starts a window of exactly Batch cycles
//   count fields pix_count, coef_count (CountBits each): items pushed into the FIFOs
//   [Batch] x 3  pause masks of the window, bit i for cycle i: pixel source, coefficient
//                source (no new valid in that cycle) and sink (ready low in that cycle)
//   pixel items  Batch x {sof, eol, data}, then coefficient words Batch x WordBits
// The sources honour valid/ready: a raised valid is held, with stable data, until ready.
// Outside a window (no command yet, or Python late) sources start nothing, the sink is not
// ready and late is flagged (sticky).
//
// Response (rsp_o, updated at the edge that takes a command, so stable when Python reads
// it mid-window): the window that just ended, LSB first: tag of the command just taken,
// late, overflow (a push found no room; sticky), out_count, pix_taken, coef_taken
// (CountBits each), then Batch x {sof, eol, data} of the outputs taken by the sink.
module nuc_dpc_batch
  import irnuc_pkg::*;
#(
  parameter int unsigned AdcBits        = 14,
  parameter int unsigned GainIntBits    = 2,
  parameter int unsigned GainFracBits   = 14,
  parameter int unsigned OffsetIntBits  = 12,
  parameter int unsigned OffsetFracBits = 4,
  parameter int unsigned OutBits        = 14,
  parameter int unsigned Rounding       = 1,
  parameter int unsigned Overflow       = 0,
  parameter int unsigned MaxWidth       = 1024,
  parameter int unsigned MaxHeight      = 1024,
  parameter int unsigned Batch          = 32,  // cycles per window, a power of two
  // Derived, do not override.
  localparam int unsigned WordBits      = coef_word_bits(GainIntBits + GainFracBits,
                                                         OffsetIntBits + OffsetFracBits),
  localparam int unsigned WidthBits     = $clog2(MaxWidth + 1),
  localparam int unsigned HeightBits    = $clog2(MaxHeight + 1),
  localparam int unsigned CountBits     = $clog2(Batch + 1),
  localparam int unsigned PixItemBits   = AdcBits + 2,
  localparam int unsigned OutItemBits   = OutBits + 2,
  localparam int unsigned CmdHeadBits   = 1 + 2 * CountBits + 3 * Batch,
  localparam int unsigned CmdBits       = CmdHeadBits + Batch * (PixItemBits + WordBits),
  localparam int unsigned RspHeadBits   = 3 + 3 * CountBits,
  localparam int unsigned RspBits       = RspHeadBits + Batch * OutItemBits
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic [WidthBits-1:0]  frame_width_i,
  input  logic [HeightBits-1:0] frame_height_i,
  input  logic [CmdBits-1:0]    cmd_i,
  output logic [RspBits-1:0]    rsp_o,
  output logic [15:0]           batch_o,  // Batch, read by the testbench
  output logic                  frame_err_o
);

  localparam int unsigned IdxBits   = $clog2(Batch);
  localparam int unsigned Depth     = 4 * Batch;  // room for the response lag of a window
  localparam int unsigned PtrBits   = $clog2(Depth);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (Batch >= 2 && Batch <= 1024 && (Batch & (Batch - 1)) == 0)
      else $fatal(1, "nuc_dpc_batch: Batch = %0d is not a power of two in 2..1024", Batch);
  end
`endif

  assign batch_o = 16'(Batch);

  // ---- command fields ------------------------------------------------------------------
  logic                         cmd_tag;
  logic [CountBits-1:0]         cmd_pix_count, cmd_coef_count;
  logic [Batch-1:0]             cmd_pix_pause, cmd_coef_pause, cmd_sink_pause;
  logic [Batch*PixItemBits-1:0] cmd_pix_items;
  logic [Batch*WordBits-1:0]    cmd_coef_items;

  assign {cmd_coef_items, cmd_pix_items, cmd_sink_pause, cmd_coef_pause, cmd_pix_pause,
          cmd_coef_count, cmd_pix_count, cmd_tag} = cmd_i;

  // ---- window: taken command, cycle index, pause masks ---------------------------------
  logic               tag_q, live_q, late_q, overflow_q, take;
  logic [IdxBits-1:0] idx_q;
  logic [Batch-1:0]   pix_pause_q, coef_pause_q, sink_pause_q;

  assign take = cmd_tag != tag_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_window
    if (!rst_ni) begin
      tag_q        <= 1'b0;
      live_q       <= 1'b0;
      late_q       <= 1'b0;
      idx_q        <= '0;
      pix_pause_q  <= '0;
      coef_pause_q <= '0;
      sink_pause_q <= '0;
    end else if (take) begin
      tag_q        <= cmd_tag;
      live_q       <= 1'b1;
      idx_q        <= '0;
      pix_pause_q  <= cmd_pix_pause;
      coef_pause_q <= cmd_coef_pause;
      sink_pause_q <= cmd_sink_pause;
    end else if (live_q) begin
      idx_q <= idx_q + IdxBits'(1);
      if (idx_q == IdxBits'(Batch - 1)) begin
        live_q <= 1'b0;  // the window ran out without a new command
        late_q <= 1'b1;
      end
    end
  end

  // ---- sources: FIFO -> valid/ready ----------------------------------------------------
  logic [PixItemBits-1:0] pix_mem_q  [Depth];
  logic [WordBits-1:0]    coef_mem_q [Depth];
  logic [PtrBits:0]       pix_wr_q, pix_rd_q, coef_wr_q, coef_rd_q;
  logic                   pix_hold_q, coef_hold_q;
  logic                   pix_valid, pix_ready, coef_valid, coef_ready;
  logic                   pix_fire, coef_fire, pix_room, coef_room;
  logic [PtrBits:0]       pix_used, coef_used;  // FIFO occupancy (pointers wrap)
  logic [PixItemBits-1:0] pix_item;
  logic [WordBits-1:0]    coef_item;

  // A new valid only inside a window and not paused; a raised valid stays until taken.
  assign pix_valid  = (pix_wr_q != pix_rd_q)
                      && (pix_hold_q || (live_q && !pix_pause_q[idx_q]));
  assign coef_valid = (coef_wr_q != coef_rd_q)
                      && (coef_hold_q || (live_q && !coef_pause_q[idx_q]));
  assign pix_item   = pix_mem_q[pix_rd_q[PtrBits-1:0]];
  assign coef_item  = coef_mem_q[coef_rd_q[PtrBits-1:0]];
  assign pix_fire   = pix_valid && pix_ready;
  assign coef_fire  = coef_valid && coef_ready;
  assign pix_used   = pix_wr_q - pix_rd_q;
  assign coef_used  = coef_wr_q - coef_rd_q;
  assign pix_room   = 32'(pix_used) + 32'(cmd_pix_count) <= Depth;
  assign coef_room  = 32'(coef_used) + 32'(cmd_coef_count) <= Depth;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_fifo_ptr
    if (!rst_ni) begin
      pix_wr_q    <= '0;
      pix_rd_q    <= '0;
      coef_wr_q   <= '0;
      coef_rd_q   <= '0;
      pix_hold_q  <= 1'b0;
      coef_hold_q <= 1'b0;
      overflow_q  <= 1'b0;
    end else begin
      pix_hold_q  <= pix_valid && !pix_ready;
      coef_hold_q <= coef_valid && !coef_ready;
      if (pix_fire) begin
        pix_rd_q <= pix_rd_q + (PtrBits + 1)'(1);
      end
      if (coef_fire) begin
        coef_rd_q <= coef_rd_q + (PtrBits + 1)'(1);
      end
      if (take) begin
        if (pix_room) begin
          pix_wr_q <= pix_wr_q + (PtrBits + 1)'(cmd_pix_count);
        end
        if (coef_room) begin
          coef_wr_q <= coef_wr_q + (PtrBits + 1)'(cmd_coef_count);
        end
        if (!pix_room || !coef_room) begin
          overflow_q <= 1'b1;
        end
      end
    end
  end

  // Storage without reset: written only below the write pointer.
  always_ff @(posedge clk_i) begin : p_fifo_mem
    if (take) begin
      for (int unsigned i = 0; i < Batch; i++) begin
        if (pix_room && i < 32'(cmd_pix_count)) begin
          pix_mem_q[PtrBits'(32'(pix_wr_q) + i)] <= cmd_pix_items[i*PixItemBits +: PixItemBits];
        end
        if (coef_room && i < 32'(cmd_coef_count)) begin
          coef_mem_q[PtrBits'(32'(coef_wr_q) + i)] <= cmd_coef_items[i*WordBits +: WordBits];
        end
      end
    end
  end

  // ---- DUT -------------------------------------------------------------------------------
  logic               out_valid, out_ready, out_sof, out_eol, out_fire;
  logic [OutBits-1:0] out_data;

  nuc_dpc_top #(
    .AdcBits       (AdcBits),
    .GainIntBits   (GainIntBits),
    .GainFracBits  (GainFracBits),
    .OffsetIntBits (OffsetIntBits),
    .OffsetFracBits(OffsetFracBits),
    .OutBits       (OutBits),
    .Rounding      (Rounding),
    .Overflow      (Overflow),
    .MaxWidth      (MaxWidth),
    .MaxHeight     (MaxHeight)
  ) u_dut (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .frame_width_i (frame_width_i),
    .frame_height_i(frame_height_i),
    .s_pix_valid_i (pix_valid),
    .s_pix_ready_o (pix_ready),
    .s_pix_data_i  (pix_item[AdcBits-1:0]),
    .s_pix_sof_i   (pix_item[AdcBits+1]),
    .s_pix_eol_i   (pix_item[AdcBits]),
    .s_coef_valid_i(coef_valid),
    .s_coef_ready_o(coef_ready),
    .s_coef_data_i (coef_item),
    .m_pix_valid_o (out_valid),
    .m_pix_ready_i (out_ready),
    .m_pix_data_o  (out_data),
    .m_pix_sof_o   (out_sof),
    .m_pix_eol_o   (out_eol),
    .frame_err_o   (frame_err_o)
  );

  assign out_ready = live_q && !sink_pause_q[idx_q];
  assign out_fire  = out_valid && out_ready;

  // ---- recorder: the transfers of the running window -----------------------------------
  // A window lasts Batch cycles and the sink is ready only inside one, so at most Batch
  // transfers per window.
  logic [Batch*OutItemBits-1:0] rec_items_q, rec_items_d;
  logic [CountBits-1:0]         rec_out_q, rec_out_d, rec_pix_q, rec_pix_d;
  logic [CountBits-1:0]         rec_coef_q, rec_coef_d;
  logic [RspBits-1:0]           rsp_q;

  always_comb begin : p_record
    rec_items_d = rec_items_q;
    if (out_fire) begin
      rec_items_d[32'(rec_out_q)*OutItemBits +: OutItemBits] = {out_sof, out_eol, out_data};
    end
    rec_out_d  = rec_out_q + CountBits'(out_fire);
    rec_pix_d  = rec_pix_q + CountBits'(pix_fire);
    rec_coef_d = rec_coef_q + CountBits'(coef_fire);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_recorder
    if (!rst_ni) begin
      rec_items_q <= '0;
      rec_out_q   <= '0;
      rec_pix_q   <= '0;
      rec_coef_q  <= '0;
      rsp_q       <= '0;
    end else if (take) begin
      rsp_q      <= {rec_items_d, rec_coef_d, rec_pix_d, rec_out_d, overflow_q, late_q, cmd_tag};
      rec_out_q  <= '0;
      rec_pix_q  <= '0;
      rec_coef_q <= '0;
    end else begin
      rec_items_q <= rec_items_d;
      rec_out_q   <= rec_out_d;
      rec_pix_q   <= rec_pix_d;
      rec_coef_q  <= rec_coef_d;
    end
  end

  assign rsp_o = rsp_q;

endmodule
