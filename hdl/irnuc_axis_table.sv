// table_interp's per-frame selection in irnuc_axis_top (docs/integration.md "Methods"):
// interp_weight on the pending READING and TABLE_READING_k, computed again after every
// write of one of them, so that
//   * TABLE_SEL tells the host the pair of tables (j, j + 1) the next frame needs before
//     that frame starts (its coefficient DMA streams the pair image of j), and
//   * the frame word (the weight, method_dpc_top's s_pix_frame_i) is ready at the frame
//     start: hold_o keeps the framer from starting a frame while it is not.
// The register file raises write_i in the cycle of the write (the values change at its
// edge); stale_q remembers it until interp_weight is idle and (re)starts. interp_weight
// reads the table readings until done: a write meanwhile makes its result stale and starts
// it again when it is done. Non-increasing table readings (error): weight and j are 0 (the
// frame is corrected with the lower table of the pair the DMA sends, unweighted), flagged
// in TABLE_SEL.error. After reset nothing is computed (valid 0, weight and j 0) until a
// write. TABLE_SEL's fields read 0 while valid is 0.
module irnuc_axis_table
  import irnuc_pkg::*;
#(
  parameter int unsigned ReadingBits    = 14,
  parameter int unsigned Tables         = 3,
  parameter int unsigned WeightFracBits = 15,
  parameter int unsigned WeightRounding = 1,  // irnuc_pkg::rounding_e
  // Derived, do not override.
  localparam int unsigned NumTable      = RegTableReadingCount,
  localparam int unsigned IndexBits     = (Tables > 2) ? $clog2(Tables - 1) : 1,
  localparam int unsigned WBits         = WeightFracBits + 1
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  // The register file: a write of READING or TABLE_READING_k now, the pending values.
  input  logic                        write_i,
  input  logic [ReadingBits-1:0]      reading_i,
  input  logic [NumTable-1:0][31:0]   table_readings_i,
  // To the framer: no frame start in the next cycle (the weight would not be the pending
  // values'). From flops and write_i (itself from the register file's flops).
  output logic                        hold_o,
  input  logic                        start_i,  // a frame starts (the framer's start_o)
  // The frame word (the weight of table j + 1) and TABLE_SEL.
  output logic [WBits-1:0]            weight_o,
  output logic [31:0]                 table_sel_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (Tables >= 2 && Tables <= NumTable)
      else $fatal(1, "irnuc_axis_table: Tables = %0d outside 2..%0d", Tables, NumTable);
    assert (WBits <= RegTableSelWeightBits && IndexBits <= RegTableSelJBits)
      else $fatal(1, "irnuc_axis_table: weight (%0d bits) or j (%0d) wider than TABLE_SEL's",
                  WBits, IndexBits);
  end
`endif

  logic [Tables-1:0][ReadingBits-1:0] readings;
  for (genvar k = 0; k < Tables; k++) begin : gen_readings
    assign readings[k] = table_readings_i[k][ReadingBits-1:0];
  end

  logic                 iw_start, iw_busy, iw_done, iw_error;
  logic [IndexBits-1:0] iw_j;
  logic [WBits-1:0]     iw_weight;
  logic                 stale_q, valid;

  interp_weight #(
    .ReadingBits   (ReadingBits),
    .Tables        (Tables),
    .WeightFracBits(WeightFracBits),
    .WeightRounding(WeightRounding)
  ) u_weight (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .start_i         (iw_start),
    .reading_i       (reading_i),
    .table_readings_i(readings),
    .busy_o          (iw_busy),
    .done_o          (iw_done),
    .error_o         (iw_error),
    .j_o             (iw_j),
    .weight_o        (iw_weight)
  );

  // A write now wins over a start now (the start took the old reading).
  assign iw_start = stale_q && !iw_busy;

  always_ff @(posedge clk_i or negedge rst_ni) begin : p_stale
    if (!rst_ni) begin
      stale_q <= 1'b0;
    end else begin
      stale_q <= write_i || (stale_q && !iw_start);
    end
  end

  assign valid    = iw_done && !stale_q && !iw_busy;
  assign hold_o   = write_i || stale_q || iw_busy;
  assign weight_o = iw_error ? '0 : iw_weight;

  logic [IndexBits-1:0] j;
  assign j = iw_error ? '0 : iw_j;

  assign table_sel_o = !valid ? '0
                     : (32'(weight_o) << RegTableSelWeightLsb) | (32'(j) << RegTableSelJLsb)
                       | (32'(1) << RegTableSelValidLsb) | (32'(iw_error) << RegTableSelErrorLsb);

  // The table readings past the configured tables and their bits above the reading's width
  // are the register file's (reserved or 0).
  logic unused_tables;
  assign unused_tables = ^{table_readings_i, start_i};  // start_i: the assertions

`ifdef IRNUC_ASSERT
  //   a_start_held   no frame starts while the weight is not the pending values' (the
  //                  framer honours hold_o, a cycle ahead);
  //   a_weight_range the weight offered to a frame (valid) is at most 2^Wf; while the
  //                  division runs its partial quotient may exceed it when a reading is
  //                  written mid-division (irnuc formal, axis_top_table14), and no frame
  //                  takes it then (hold_o).
  logic armed_q;  // from the second edge after reset
  irnuc_assert_armed u_armed (.clk_i, .rst_ni, .armed_o(armed_q));
  always_ff @(posedge clk_i) begin : p_check
    if (armed_q) begin
      a_start_held: assert (!(start_i && (stale_q || iw_busy)))
        else $error("irnuc_axis_table: a frame started while its weight was computed");
      a_weight_range: assert (!valid || 64'(weight_o) <= (64'd1 << WeightFracBits))
        else $error("irnuc_axis_table: weight %0d above 2^%0d", weight_o, WeightFracBits);
    end
  end
`endif

endmodule
