// The AXI4-Lite slave of the register block (irnuc's CPU interface for peakrdl-regblock,
// irnuc.cosim.regfiles): every output a flop, the block's request from flops, one
// transaction at a time.
//   * The write address, the write data and the read address each go into a holding
//     register; awready / wready / arready are flops of their own, the complements of the
//     holding flags the logic reads (each holding register follows its input while empty:
//     no input passes an enable). No input-to-output path.
//   * When no transaction is in progress a held read, or a held write (address and data),
//     is chosen (reads and writes alternate when both wait); the choice is a flop, which
//     loads the request in the next cycle: cpuif_req, cpuif_addr, cpuif_wr_data and
//     cpuif_wr_biten are flops (the block's address decode starts at a flop) whose enables
//     are flops (no decision before their fanout). A request the block stalls is held
//     until it takes it.
//   * The block's acknowledge is registered into the response (RVALID with RDATA, or
//     BVALID) and held until the master takes it; then the next request. SLVERR for the
//     block's decode errors (outside the map, a write to a read-only or a read of a
//     write-only register) and, on a write, for hwif_wr_err given with an external
//     register's acknowledge (FRAME_SIZE's value check).
logic                                axil_aw_held, axil_w_held, axil_ar_held;
logic                                axil_aw_held_d, axil_w_held_d, axil_ar_held_d;
logic                                axil_aw_ready, axil_w_ready, axil_ar_ready;
logic [{{cpuif.addr_width-1}}:0]     axil_awaddr, axil_araddr;
logic [{{cpuif.data_width-1}}:0]     axil_wdata;
logic [{{cpuif.data_width_bytes-1}}:0] axil_wstrb;
logic                                axil_busy;     // a request issued, its response not taken
logic                                axil_last_rd;  // the last request was a read
logic                                axil_issue_rd, axil_issue_wr, axil_taken;
logic                                axil_take_rd, axil_take_wr;  // load the chosen request
logic                                axil_req, axil_req_is_wr;
logic [{{cpuif.addr_width-1}}:0]     axil_req_addr;
logic [{{cpuif.data_width-1}}:0]     axil_req_data, axil_req_biten;
logic                                axil_bvalid, axil_rvalid, axil_berr, axil_rerr;
logic [{{cpuif.data_width-1}}:0]     axil_rdata;

// The next request: a read when no write waits or the last one was a write.
assign axil_issue_rd = !axil_busy && axil_ar_held
                       && (!(axil_aw_held && axil_w_held) || !axil_last_rd);
assign axil_issue_wr = !axil_busy && axil_aw_held && axil_w_held && !axil_issue_rd;
// The block takes the request unless it stalls it.
assign axil_taken    = axil_req && !(axil_req_is_wr ? cpuif_req_stall_wr : cpuif_req_stall_rd);
// A holding register fills on its valid while empty and empties when its request is
// loaded.
assign axil_aw_held_d = axil_aw_held ? !axil_take_wr : {{cpuif.signal("awvalid")}};
assign axil_w_held_d  = axil_w_held ? !axil_take_wr : {{cpuif.signal("wvalid")}};
assign axil_ar_held_d = axil_ar_held ? !axil_take_rd : {{cpuif.signal("arvalid")}};

always_ff {{get_always_ff_event(cpuif.reset)}} begin
    if({{get_resetsignal(cpuif.reset)}}) begin
        axil_aw_held   <= '0;
        axil_w_held    <= '0;
        axil_ar_held   <= '0;
        axil_aw_ready  <= '1;
        axil_w_ready   <= '1;
        axil_ar_ready  <= '1;
        axil_busy      <= '0;
        axil_last_rd   <= '0;
        axil_take_rd   <= '0;
        axil_take_wr   <= '0;
        axil_req       <= '0;
        axil_req_is_wr <= '0;
        axil_bvalid    <= '0;
        axil_rvalid    <= '0;
        axil_berr      <= '0;
        axil_rerr      <= '0;
    end else begin
        axil_aw_held  <= axil_aw_held_d;
        axil_w_held   <= axil_w_held_d;
        axil_ar_held  <= axil_ar_held_d;
        axil_aw_ready <= !axil_aw_held_d;
        axil_w_ready  <= !axil_w_held_d;
        axil_ar_ready <= !axil_ar_held_d;
        axil_take_rd  <= axil_issue_rd;
        axil_take_wr  <= axil_issue_wr;
        axil_req      <= (axil_req && !axil_taken) || axil_take_rd || axil_take_wr;
        if(axil_take_rd || axil_take_wr) begin
            axil_req_is_wr <= axil_take_wr;
        end
        if(axil_issue_rd || axil_issue_wr) begin
            axil_busy      <= '1;
            axil_last_rd   <= axil_issue_rd;
        end else if((axil_bvalid && {{cpuif.signal("bready")}})
                    || (axil_rvalid && {{cpuif.signal("rready")}})) begin
            axil_busy <= '0;
        end
        if(cpuif_wr_ack) begin
            axil_bvalid <= '1;
            axil_berr   <= cpuif_wr_err || hwif_wr_err;
        end else if({{cpuif.signal("bready")}}) begin
            axil_bvalid <= '0;
        end
        if(cpuif_rd_ack) begin
            axil_rvalid <= '1;
            axil_rerr   <= cpuif_rd_err;
        end else if({{cpuif.signal("rready")}}) begin
            axil_rvalid <= '0;
        end
    end
end

// Payload registers: a holding register follows its input while empty; the request's
// payload is loaded when it issues; the read data with the acknowledge.
always_ff @(posedge clk) begin
    if(!axil_aw_held) axil_awaddr <= {{cpuif.signal("awaddr")}};
    if(!axil_w_held) begin
        axil_wdata <= {{cpuif.signal("wdata")}};
        axil_wstrb <= {{cpuif.signal("wstrb")}};
    end
    if(!axil_ar_held) axil_araddr <= {{cpuif.signal("araddr")}};
    if(axil_take_rd) begin
        axil_req_addr  <= {axil_araddr[{{cpuif.addr_width-1}}:{{clog2(cpuif.data_width_bytes)}}], {{clog2(cpuif.data_width_bytes)}}'b0};
    end else if(axil_take_wr) begin
        axil_req_addr  <= {axil_awaddr[{{cpuif.addr_width-1}}:{{clog2(cpuif.data_width_bytes)}}], {{clog2(cpuif.data_width_bytes)}}'b0};
        axil_req_data  <= axil_wdata;
        for(int i=0; i<{{cpuif.data_width_bytes}}; i++) begin
            axil_req_biten[i*8 +: 8] <= {8{axil_wstrb[i]}};
        end
    end
    if(cpuif_rd_ack) axil_rdata <= cpuif_rd_data;
end

assign cpuif_req        = axil_req;
assign cpuif_req_is_wr  = axil_req_is_wr;
assign cpuif_addr       = axil_req_addr;
assign cpuif_wr_data    = axil_req_data;
assign cpuif_wr_biten   = axil_req_biten;

`ifdef IRNUC_ASSERT
// Each ready is the complement of its holding flag (a flop of its own, never a cycle
// behind it): a valid taken while the register holds one would overwrite it.
logic axil_armed;
always_ff {{get_always_ff_event(cpuif.reset)}} begin
    if({{get_resetsignal(cpuif.reset)}}) axil_armed <= '0;
    else axil_armed <= '1;
end
always_ff @(posedge clk) begin
    if(axil_armed) begin
        assert_aw_ready: assert(axil_aw_ready == !axil_aw_held)
            else $error("irnuc_axil_regblock: awready is not 'no write address held'");
        assert_w_ready: assert(axil_w_ready == !axil_w_held)
            else $error("irnuc_axil_regblock: wready is not 'no write data held'");
        assert_ar_ready: assert(axil_ar_ready == !axil_ar_held)
            else $error("irnuc_axil_regblock: arready is not 'no read address held'");
    end
end
`endif

assign {{cpuif.signal("awready")}} = axil_aw_ready;
assign {{cpuif.signal("wready")}}  = axil_w_ready;
assign {{cpuif.signal("arready")}} = axil_ar_ready;
assign {{cpuif.signal("bvalid")}}  = axil_bvalid;
assign {{cpuif.signal("bresp")}}   = axil_berr ? 2'b10 : 2'b00;  // SLVERR : OKAY
assign {{cpuif.signal("rvalid")}}  = axil_rvalid;
assign {{cpuif.signal("rdata")}}   = axil_rdata;
assign {{cpuif.signal("rresp")}}   = axil_rerr ? 2'b10 : 2'b00;
