// The register semantics of docs/registers.md on an AXI4-Lite register file, for
// `irnuc formal` (docs/formal.md); FORMAL only. Written against the s_axil interface, the
// register file's event inputs and the map of one configuration (the generated package
// irnuc_fv_map, from the map's one source through nuc_fixed.regmap.RegisterModel): any
// register file behind the port is held to it.
//
// Every response is checked:
//   a_bresp        BRESP as docs/registers.md says: SLVERR outside the map, for a register
//                  without a writable field (read-only, on every build: a reserved one too)
//                  and an illegal FRAME_SIZE; OKAY else (a reserved writable register too)
//   a_rresp        RRESP: SLVERR outside the map and for a register without a readable
//                  field (COMMAND, write only), OKAY else
//   a_rdata_refused  a read answered SLVERR returns 0
// (the responses by address and access are the map model's, in irnuc_fv_map) and the read
// data of one register, pick_i (free, constant: the proof covers every register), against
// its expected value: reset values, writes with their byte strobes, W1C clears (an event in
// the clear's cycle wins), counters counting their events and cleared by
// COMMAND.clear_counters (its pulse in the cycle the write's response rises: an event in
// that cycle is lost, as in the cycle after reset: docs/regmap.md), STATUS.pending set by a
// write to a shadowed register until the next frame start (start_i; a write in that cycle
// stays pending), bits outside the fields and above a method register's width 0:
//   a_reset_value  a read before any write or event that could change the register
//   a_const        read-only constants and reserved registers (0)
//   a_rw           RW fields after writes
//   a_w1c          W1C status bits after events and clears
//   a_count        counters
//   a_pending      STATUS.pending (the commit of shadowed registers at a frame start)
// Timing contract: a write takes effect at the clock edge before its BVALID rises; a read
// returns the register's value at some cycle between its AR handshake and its RVALID, so
// bits that change in that window (or while a write to the register is open) are not
// checked for that read. Bits driven by hardware levels (STATUS.core_err, in_frame,
// FFC_STATUS, TABLE_SEL) are not modelled.
module irnuc_fv_regs
  import irnuc_fv_map::*;
#(
  parameter int unsigned AddrBits = 12,
  parameter int unsigned Depth    = 2  // requests open at once per channel, at most
) (
  input logic                     clk_i,
  input logic                     rst_ni,
  input logic [AddrBits-1:0]      awaddr_i,
  input logic                     awvalid_i,
  input logic                     awready_i,
  input logic [31:0]              wdata_i,
  input logic [3:0]               wstrb_i,
  input logic                     wvalid_i,
  input logic                     wready_i,
  input logic [1:0]               bresp_i,
  input logic                     bvalid_i,
  input logic                     bready_i,
  input logic [AddrBits-1:0]      araddr_i,
  input logic                     arvalid_i,
  input logic                     arready_i,
  input logic [31:0]              rdata_i,
  input logic [1:0]               rresp_i,
  input logic                     rvalid_i,
  input logic                     rready_i,
  input logic [NumEvents-1:0]     ev_i,     // the register file's events (irnuc_fv_map)
  input logic                     start_i,  // a frame start: the shadowed values taken
  input logic [AddrBits-3:0]      pick_i    // free and constant: the register followed
);

`ifdef FORMAL
  localparam logic [1:0] Okay = 2'b00, SlvErr = 2'b10;
  localparam int unsigned W = AddrBits - 2;

  function automatic logic [31:0] bytes(input logic [3:0] strb);
    return {{8{strb[3]}}, {8{strb[2]}}, {8{strb[1]}}, {8{strb[0]}}};
  endfunction

  logic aw_fire, w_fire, b_fire, ar_fire, r_fire, b_new, r_new, b_stall_q, r_stall_q;
  assign aw_fire = awvalid_i && awready_i;
  assign w_fire  = wvalid_i && wready_i;
  assign b_fire  = bvalid_i && bready_i;
  assign ar_fire = arvalid_i && arready_i;
  assign r_fire  = rvalid_i && rready_i;
  // A response's first cycle (a new one may follow a handshake at once).
  assign b_new   = bvalid_i && !b_stall_q;
  assign r_new   = rvalid_i && !r_stall_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_stall
    if (!rst_ni) begin
      b_stall_q <= 1'b0;
      r_stall_q <= 1'b0;
    end else begin
      b_stall_q <= bvalid_i && !bready_i;
      r_stall_q <= rvalid_i && !rready_i;
    end
  end

  // ---- the requests open, oldest first -----------------------------------------------------
  logic [Depth-1:0][W-1:0]  aw_q, ar_q;
  logic [Depth-1:0][35:0]   w_q;
  logic [Depth-1:0][31:0]   rexp_q, rmask_q;  // a read's expected value and bits checked
  logic [$clog2(Depth+1)-1:0] naw_q, nw_q, nar_q;
  logic [W-1:0]             bw, aw_word, ar_word, pick;
  logic [31:0]              bdata;
  logic [3:0]               bstrb;

  assign aw_word = awaddr_i[AddrBits-1:2];
  assign ar_word = araddr_i[AddrBits-1:2];
  assign pick    = pick_i;
  assign bw      = aw_q[0];
  assign {bdata, bstrb} = w_q[0];

  // ---- the expected values: FRAME_SIZE (for the responses) and the register followed -------
  /* verilator lint_off UNUSEDSIGNAL */  // a register's entry: the fields a check needs
  reg_t        bi, pi, ri;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [1:0]  bresp_exp;
  logic [31:0] fs_q, exp_q, sure, prev_q, exp_cur, exp_d, written, wmask;
  logic [NumEvents-1:0] ev_q;
  logic        start_q, applies, hits, open_pick, in_touch_q, clr, first_q;

  assign bi = info(bw);
  assign pi = info(pick);
  // Levels are never checked; every other bit is (0 outside the fields).
  assign sure = ~pi.level;
  always_comb begin : p_bresp
    written = (fs_q & ~(bi.rw & bytes(bstrb))) | (bdata & bi.rw & bytes(bstrb));
    if (!bi.mapped) begin
      bresp_exp = SlvErr;
    end else if (bi.wr_err) begin
      bresp_exp = SlvErr;
    end else if (bi.present && bw == FrameSizeWord && !size_legal(written)) begin
      bresp_exp = SlvErr;
    end else begin
      bresp_exp = Okay;
    end
  end
  assign applies = b_new && bresp_exp == Okay && naw_q != '0 && nw_q != '0;

  // The value the followed register shows now: the expectation, corrected when a write's
  // response rises (it took effect at the edge before, together with that cycle's events).
  always_comb begin : p_expected
    logic [31:0] v;
    v     = prev_q;
    wmask = bytes(bstrb) & pi.value;
    hits  = applies && bw == pick;
    if (hits) begin
      v = (v & ~(pi.rw & wmask)) | (bdata & pi.rw & wmask);
      v = v & ~(bdata & pi.w1c & wmask);
    end
    v = evolve(pick, v, ev_q);
    clr = applies && clears(pick, bw, bdata & bytes(bstrb));
    if (clr) begin
      v = '0;
    end
    if (pi.pending != '0) begin
      v = (start_q ? v & ~pi.pending : v)
          | ((applies && info(bw).shadowed && |(info(bw).rw & bytes(bstrb))) ? pi.pending : '0);
    end
    exp_cur = applies ? v : exp_q;
    // The counters' clear (COMMAND's pulse, the cycle after reset) wins over an event.
    exp_d   = ((clr || first_q) && pi.kind == KCount) ? exp_cur : evolve(pick, exp_cur, ev_i);
    if (pi.pending != '0 && start_i) begin
      exp_d = exp_d & ~pi.pending;
    end
  end

  // A write to the followed register is open (taken, not answered): its effect is not known
  // before its response.
  always_comb begin : p_open_pick
    open_pick = (aw_fire && aw_word == pick);
    for (int unsigned k = 0; k < Depth; k++) begin
      if (k < 32'(naw_q) && aw_q[k] == pick) begin
        open_pick = 1'b1;
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_state
    if (!rst_ni) begin
      naw_q      <= '0;
      nw_q       <= '0;
      nar_q      <= '0;
      fs_q       <= info(FrameSizeWord).reset;
      exp_q      <= pi.reset;
      prev_q     <= pi.reset;
      ev_q       <= '0;
      start_q    <= 1'b0;
      first_q    <= 1'b1;
      in_touch_q <= 1'b0;
    end else begin
      if (b_fire) begin
        aw_q  <= {aw_q[Depth-1], aw_q[Depth-1:1]};
        w_q   <= {w_q[Depth-1], w_q[Depth-1:1]};
      end
      if (aw_fire) begin
        aw_q[32'(naw_q) - 32'(b_fire)] <= aw_word;
      end
      if (w_fire) begin
        w_q[32'(nw_q) - 32'(b_fire)] <= {wdata_i, wstrb_i};
      end
      naw_q <= naw_q + aw_fire - b_fire;
      nw_q  <= nw_q + w_fire - b_fire;
      if (applies && bw == FrameSizeWord) begin
        fs_q <= written;
      end
      exp_q   <= exp_d;
      prev_q  <= exp_cur;
      ev_q    <= ev_i;
      start_q <= start_i;
      first_q <= 1'b0;
      in_touch_q <= in_touch_q || (exp_d != pi.reset) || open_pick || hits;
    end
  end

  // ---- reads: the expectation at the AR handshake, less the bits that change until RVALID ---
  logic [31:0] chg;
  assign chg = (exp_cur ^ exp_q) | (exp_cur ^ exp_d) | (open_pick ? '1 : '0);

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_reads
    if (!rst_ni) begin
      nar_q <= '0;
    end else begin
      for (int unsigned k = 0; k < Depth; k++) begin
        rmask_q[k] <= rmask_q[k] & ~chg;
      end
      if (r_fire) begin
        ar_q    <= {ar_q[Depth-1], ar_q[Depth-1:1]};
        rexp_q  <= {rexp_q[Depth-1], rexp_q[Depth-1:1]};
        rmask_q <= {rmask_q[Depth-1] & ~chg, rmask_q[Depth-1:1] & ~{(Depth-1){chg}}};
      end
      if (ar_fire) begin
        ar_q[32'(nar_q) - 32'(r_fire)]    <= ar_word;
        rexp_q[32'(nar_q) - 32'(r_fire)]  <= exp_cur;
        rmask_q[32'(nar_q) - 32'(r_fire)] <= sure & ~chg;
      end
      nar_q <= nar_q + ar_fire - r_fire;
    end
  end

  // The reset values: no write to the followed register and no event changed it yet.
  logic        fresh_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_fresh
    if (!rst_ni) begin
      fresh_q <= 1'b1;
    end else if (ar_fire) begin
      fresh_q <= !in_touch_q && !open_pick;
    end
  end

  // ---- the checks --------------------------------------------------------------------------
  logic [31:0] diff;
  logic        unused_lanes;  // a byte address within the word: whole words are accessed
  assign unused_lanes = ^{awaddr_i[1:0], araddr_i[1:0]};
  assign ri   = info(ar_q[0]);
  assign diff = (rdata_i ^ rexp_q[0]) & rmask_q[0];

  always_comb begin : p_check
    if (rst_ni) begin
      if (b_new && naw_q != '0 && nw_q != '0) begin
        a_bresp: assert (bresp_i == bresp_exp);
      end
      if (r_new && nar_q != '0) begin
        a_rresp: assert (rresp_i == ((ri.mapped && !ri.rd_err) ? Okay : SlvErr));
        if (!ri.mapped || ri.rd_err) begin
          a_rdata_refused: assert (rdata_i == '0);
        end
        if (ar_q[0] == pick && ri.mapped && !ri.rd_err) begin
          if (fresh_q && nar_q == 1) begin
            a_reset_value: assert (diff == '0);
          end
          if (pi.kind == KConst) begin
            a_const: assert ((diff & ~pi.pending) == '0);
          end
          if (pi.kind == KRw) begin
            a_rw: assert ((diff & pi.rw) == '0);
          end
          if (pi.kind == KW1c) begin
            a_w1c: assert ((diff & pi.w1c) == '0);
          end
          if (pi.kind == KCount) begin
            a_count: assert (diff == '0);
          end
          a_pending: assert ((diff & pi.pending) == '0);
        end
      end
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, awaddr_i, awvalid_i, awready_i, wdata_i, wstrb_i,
                          wvalid_i, wready_i, bresp_i, bvalid_i, bready_i, araddr_i,
                          arvalid_i, arready_i, rdata_i, rresp_i, rvalid_i, rready_i, ev_i,
                          start_i, pick_i};
`endif

endmodule
