// Brings a two's complement number into the code range of an OutBits-bit word
// (combinational): OUT of docs/datapath.md and SAT of the coefficient formats.
//
//   Overflow = saturate: unsigned target: 0 below 0, 2^OutBits - 1 above it; signed
//              target: -2^(OutBits-1) below it, 2^(OutBits-1) - 1 above it;
//   Overflow = wrap:     the low OutBits bits (the value modulo 2^OutBits).
// A value that always fits passes unchanged (sign extension where the target is wider).
module irnuc_clip #(
  parameter int unsigned InBits    = 8,
  parameter int unsigned OutBits   = 8,
  parameter bit          OutSigned = 1'b0,
  parameter int unsigned Overflow  = 0  // irnuc_pkg::overflow_e
) (
  input  logic [InBits-1:0]  v_i,
  output logic [OutBits-1:0] y_o
);

  localparam irnuc_pkg::overflow_e OverflowMode = irnuc_pkg::overflow_e'(Overflow);

`ifndef SYNTHESIS
  initial begin : p_param_ranges
    assert (InBits >= 2 && InBits <= 64 && OutBits >= 1 && OutBits <= 64)
      else $fatal(1, "irnuc_clip: InBits = %0d, OutBits = %0d outside 2..64, 1..64", InBits,
                  OutBits);
    assert (Overflow <= 1)
      else $fatal(1, "irnuc_clip: Overflow = %0d outside 0..1", Overflow);
  end
`endif

  logic neg;
  assign neg = v_i[InBits-1];

  if (OverflowMode == irnuc_pkg::OverflowWrap) begin : gen_wrap
    // The low bits; a narrower value is sign-extended (its value modulo 2^OutBits).
    assign y_o = OutBits'($signed(v_i));
    logic unused_neg;
    assign unused_neg = neg;
  end else if (!OutSigned) begin : gen_sat_unsigned
    logic too_big;
    if (InBits - 1 > OutBits) begin : gen_hi_check
      // Positive with a set bit at or above 2^OutBits.
      assign too_big = |v_i[InBits-2:OutBits];
    end else begin : gen_no_hi_check
      assign too_big = 1'b0;
    end
    always_comb begin : p_saturate
      if (neg) begin
        y_o = '0;
      end else if (too_big) begin
        y_o = '1;
      end else begin
        y_o = OutBits'(v_i[InBits-2:0]);
      end
    end
  end else begin : gen_sat_signed
    if (InBits > OutBits) begin : gen_check
      // Fits exactly when every bit from OutBits-1 up equals the sign.
      logic fits;
      assign fits = (v_i[InBits-1:OutBits-1] == '0) || (v_i[InBits-1:OutBits-1] == '1);
      always_comb begin : p_saturate
        if (fits) begin
          y_o = v_i[OutBits-1:0];
        end else if (neg) begin
          y_o = OutBits'(1) << (OutBits - 1);     // the most negative code
        end else begin
          y_o = ~(OutBits'(1) << (OutBits - 1));  // the most positive code
        end
      end
    end else begin : gen_extend
      assign y_o = OutBits'($signed(v_i));
      logic unused_neg;
      assign unused_neg = neg;
    end
  end

endmodule
