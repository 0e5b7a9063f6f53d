// Data integrity of a first-in first-out stream element (a spill register, a buffer): every
// item taken in leaves, unchanged and in order, and the element never holds more than Depth
// items nor sends one it was not given. For `irnuc formal` (docs/formal.md); FORMAL only.
//
// One item is followed at a time, picked by the free input pick_i when it is taken in (the
// solver chooses which: a proof covers every item): its data and the number of items ahead
// of it are recorded, the count steps down as items leave, and when it leaves its data is
// compared.
//   a_capacity   items inside <= Depth
//   a_no_phantom an item leaves only when one is inside
//   a_order      the followed item leaves with its data, after exactly the items ahead of it
module irnuc_fv_order #(
  parameter int unsigned DataBits = 1,
  parameter int unsigned Depth    = 2
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic                pick_i,  // free: follow the item taken now
  input logic                in_valid_i,
  input logic                in_ready_i,
  input logic [DataBits-1:0] in_data_i,
  input logic                out_valid_i,
  input logic                out_ready_i,
  input logic [DataBits-1:0] out_data_i
);

`ifdef FORMAL
  localparam int unsigned CountBits = $clog2(Depth + 2);

  logic                 in_fire, out_fire, track_q;
  logic [CountBits-1:0] count_q, ahead_q;
  logic [DataBits-1:0]  data_q;

  assign in_fire  = in_valid_i && in_ready_i;
  assign out_fire = out_valid_i && out_ready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_count
    if (!rst_ni) begin
      count_q <= '0;
      track_q <= 1'b0;
      ahead_q <= '0;
    end else begin
      count_q <= count_q + CountBits'(in_fire) - CountBits'(out_fire);
      if (track_q && out_fire) begin
        if (ahead_q == '0) begin
          track_q <= 1'b0;
        end else begin
          ahead_q <= ahead_q - CountBits'(1);
        end
      end else if (!track_q && in_fire && pick_i) begin
        track_q <= 1'b1;
        ahead_q <= count_q - CountBits'(out_fire);
      end
    end
  end

  always_ff @(posedge clk_i) begin : p_data
    if (!track_q && in_fire && pick_i) begin
      data_q <= in_data_i;
    end
  end

  always_comb begin : p_check
    if (rst_ni) begin
      a_capacity: assert (32'(count_q) <= Depth);
      if (out_fire) begin
        a_no_phantom: assert (count_q != '0);
      end
      if (track_q && out_fire && ahead_q == '0) begin
        a_order: assert (out_data_i == data_q);
      end
    end
  end
`else
  logic unused_ports;
  assign unused_ports = ^{clk_i, rst_ni, pick_i, in_valid_i, in_ready_i, in_data_i,
                          out_valid_i, out_ready_i, out_data_i};
`endif

endmodule
