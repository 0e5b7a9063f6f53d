// Line buffer: a simple dual-port memory of Depth words, one write port and one read
// port whose data are registered twice (the read register and an output register), so
// that synthesis maps it to block RAM with its output register (xc7 RAMB18E1/RAMB36E1,
// ECP5 DP16KD) or, when small, to LUT RAM.
//
// Both read registers move when rd_en_i is high: rd_data_o is the word at the rd_addr_i of
// the rd_en_i before the last one (two reads later it is there), and holds while rd_en_i
// is low. Reading the address written in the same cycle gives an undefined word
// (no_rw_check: no collision logic is built); the user bypasses that case.
//
// ECP5 (`define IRNUC_ECP5, irnuc synth's ECP5 flow), 512 to 16384 words: DP16KD blocks are
// instantiated with the output register (REGMODE_B = OUTREG, clock enable OCEB), as Yosys
// maps block RAM without it; its clock-to-output without the register (5.8 ns at speed 6)
// would leave no time for the routing at 150 MHz. Port A writes, port B reads; one block
// per 18, 9, 4, 2 or 1 bits of the word for up to 1024, 2048, 4096, 8192 or 16384 words.
module irnuc_line_buffer
  import irnuc_pkg::*;
#(
  parameter int unsigned Depth    = 1024,
  parameter int unsigned DataBits = 30,
  // Derived, do not override.
  localparam int unsigned AddrBits = (Depth > 1) ? $clog2(Depth) : 1
) (
  input  logic                clk_i,
  input  logic                wr_en_i,
  input  logic [AddrBits-1:0] wr_addr_i,
  input  logic [DataBits-1:0] wr_data_i,
  input  logic                rd_en_i,
  input  logic [AddrBits-1:0] rd_addr_i,
  output logic [DataBits-1:0] rd_data_o
);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (Depth >= 1 && Depth <= FrameDimMax)
      else $fatal(1, "irnuc_line_buffer: Depth = %0d outside 1..%0d", Depth, FrameDimMax);
    assert (DataBits >= 1)
      else $fatal(1, "irnuc_line_buffer: DataBits = %0d must be at least 1", DataBits);
  end
`endif

`ifdef IRNUC_ECP5
  localparam bit UseDp16kd = (Depth >= 512) && (Depth <= 16384);
`else
  localparam bit UseDp16kd = 1'b0;
`endif

  if (UseDp16kd) begin : gen_dp16kd
    // Data width per block and the address shift of that width (DP16KD address pins).
    localparam int unsigned TileBits = (Depth <= 1024) ? 18 : (Depth <= 2048) ? 9 :
                                       (Depth <= 4096) ? 4 : (Depth <= 8192) ? 2 : 1;
    localparam int unsigned Shift    = (Depth <= 1024) ? 4 : (Depth <= 2048) ? 3 :
                                       (Depth <= 4096) ? 2 : (Depth <= 8192) ? 1 : 0;
    localparam int unsigned Tiles    = (DataBits + TileBits - 1) / TileBits;
    localparam int unsigned PadBits  = Tiles * TileBits;

    logic [13:0] ada, adb;
    // x18: address bits 1:0 are the write's byte enables (both bytes).
    assign ada = (14'(wr_addr_i) << Shift) | ((TileBits == 18) ? 14'd3 : 14'd0);
    assign adb = 14'(rd_addr_i) << Shift;

    logic [PadBits-1:0] wr_pad, rd_pad;
    assign wr_pad = PadBits'(wr_data_i);

    for (genvar t = 0; t < Tiles; t++) begin : gen_tile
      logic [17:0] di, doa, dob;  // port A only writes: doa is left open
      assign di = 18'(wr_pad[t*TileBits +: TileBits]);
      assign rd_pad[t*TileBits +: TileBits] = dob[TileBits-1:0];

      DP16KD #(
        .DATA_WIDTH_A       (TileBits),
        .DATA_WIDTH_B       (TileBits),
        .REGMODE_A          ("NOREG"),
        .REGMODE_B          ("OUTREG"),
        .RESETMODE          ("SYNC"),
        .ASYNC_RESET_RELEASE("SYNC"),
        .CSDECODE_A         ("0b000"),
        .CSDECODE_B         ("0b000"),
        .WRITEMODE_A        ("NORMAL"),
        .WRITEMODE_B        ("NORMAL"),
        .CLKAMUX            ("CLKA"),
        .CLKBMUX            ("CLKB"),
        .GSR                ("DISABLED")
      ) u_ram (
        .DIA0(di[0]), .DIA1(di[1]), .DIA2(di[2]), .DIA3(di[3]), .DIA4(di[4]), .DIA5(di[5]),
        .DIA6(di[6]), .DIA7(di[7]), .DIA8(di[8]), .DIA9(di[9]), .DIA10(di[10]),
        .DIA11(di[11]), .DIA12(di[12]), .DIA13(di[13]), .DIA14(di[14]), .DIA15(di[15]),
        .DIA16(di[16]), .DIA17(di[17]),
        .ADA0(ada[0]), .ADA1(ada[1]), .ADA2(ada[2]), .ADA3(ada[3]), .ADA4(ada[4]),
        .ADA5(ada[5]), .ADA6(ada[6]), .ADA7(ada[7]), .ADA8(ada[8]), .ADA9(ada[9]),
        .ADA10(ada[10]), .ADA11(ada[11]), .ADA12(ada[12]), .ADA13(ada[13]),
        .CEA(wr_en_i), .OCEA(1'b0), .CLKA(clk_i), .WEA(wr_en_i), .RSTA(1'b0), .CSA2(1'b0),
        .CSA1(1'b0), .CSA0(1'b0),
        .DOA0(doa[0]), .DOA1(doa[1]), .DOA2(doa[2]), .DOA3(doa[3]), .DOA4(doa[4]), .DOA5(doa[5]), .DOA6(doa[6]), .DOA7(doa[7]), .DOA8(doa[8]),
        .DOA9(doa[9]), .DOA10(doa[10]), .DOA11(doa[11]), .DOA12(doa[12]), .DOA13(doa[13]), .DOA14(doa[14]), .DOA15(doa[15]), .DOA16(doa[16]),
        .DOA17(doa[17]),
        .DIB0(1'b0), .DIB1(1'b0), .DIB2(1'b0), .DIB3(1'b0), .DIB4(1'b0), .DIB5(1'b0),
        .DIB6(1'b0), .DIB7(1'b0), .DIB8(1'b0), .DIB9(1'b0), .DIB10(1'b0), .DIB11(1'b0),
        .DIB12(1'b0), .DIB13(1'b0), .DIB14(1'b0), .DIB15(1'b0), .DIB16(1'b0), .DIB17(1'b0),
        .ADB0(adb[0]), .ADB1(adb[1]), .ADB2(adb[2]), .ADB3(adb[3]), .ADB4(adb[4]),
        .ADB5(adb[5]), .ADB6(adb[6]), .ADB7(adb[7]), .ADB8(adb[8]), .ADB9(adb[9]),
        .ADB10(adb[10]), .ADB11(adb[11]), .ADB12(adb[12]), .ADB13(adb[13]),
        .CEB(rd_en_i), .OCEB(rd_en_i), .CLKB(clk_i), .WEB(1'b0), .RSTB(1'b0), .CSB2(1'b0),
        .CSB1(1'b0), .CSB0(1'b0),
        .DOB0(dob[0]), .DOB1(dob[1]), .DOB2(dob[2]), .DOB3(dob[3]), .DOB4(dob[4]),
        .DOB5(dob[5]), .DOB6(dob[6]), .DOB7(dob[7]), .DOB8(dob[8]), .DOB9(dob[9]),
        .DOB10(dob[10]), .DOB11(dob[11]), .DOB12(dob[12]), .DOB13(dob[13]), .DOB14(dob[14]),
        .DOB15(dob[15]), .DOB16(dob[16]), .DOB17(dob[17])
      );
    end

    assign rd_data_o = rd_pad[DataBits-1:0];
  end else begin : gen_inferred
    (* no_rw_check *)
    logic [DataBits-1:0] mem_q [Depth];
    logic [DataBits-1:0] rd_data_q, out_q;

    always_ff @(posedge clk_i) begin : p_ram
      if (wr_en_i) begin
        mem_q[wr_addr_i] <= wr_data_i;
      end
      if (rd_en_i) begin
        rd_data_q <= mem_q[rd_addr_i];
        out_q     <= rd_data_q;
      end
    end

    assign rd_data_o = out_q;
  end

endmodule
