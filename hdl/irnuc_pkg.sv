// Shared types, layouts and constants of the irnuc RTL (docs/datapath.md, docs/rtl.md).
//
// The block between the irnuc-spec markers is generated from irnuc.nuc_fixed.rtl_spec, the
// one spec of what the RTL and Python share (constants, parameter ranges, mode encodings,
// word layouts): edit the spec and run `python -m irnuc.cosim.spec_files --write`;
// tests/test_rtl_spec.py fails while the block is stale. The functions below it are
// written by hand and mirrored by the spec's Python functions of the same names.
// Everything here is read back from the simulated RTL through cosim/hdl/irnuc_pkg_probe.sv
// (generated too) and compared with the spec by cocotb_tests/tb_pkg.py.
package irnuc_pkg;

  // irnuc-spec: begin (generated from irnuc.nuc_fixed.rtl_spec; do not edit)
  // Each module uses some of these: no warning for the others.
  /* verilator lint_off UNUSEDPARAM */
  // ---- constants
  // operand chunk of the multipliers (one DSP block per partial product)
  localparam int unsigned MulChunkBits = 17;
  // largest frame width and height, and line-buffer depth
  localparam int unsigned FrameDimMax = 65535;
  localparam int unsigned DpcRecipGuardBits = 6;  // DPC reciprocal shift K = OutBits + this
  localparam int unsigned SumBitsMax = 62;  // widest NUC sum (int64 golden model, one spare bit)
  localparam int unsigned RegMapId = 1230130755;  // ID register value
  localparam int unsigned RegMapMajor = 1;  // register map major version
  localparam int unsigned RegMapMinor = 2;  // register map minor version
  localparam int unsigned RegAddrBits = 12;  // AXI4-Lite address bits of the register window
  // 64-bit slots of the method registers (GAIN .. FFC_TARGET)
  localparam int unsigned RegSlotCount = 10;
  localparam int unsigned RegIdOffset = 0;  // ID: identifies irnuc_axis_top
  localparam int unsigned RegIdValueLsb = 0;  // ID.value
  localparam int unsigned RegIdValueBits = 32;  // ID.value width
  // VERSION: register map version and coefficient word layout version
  localparam int unsigned RegVersionOffset = 4;
  localparam int unsigned RegVersionMinorLsb = 0;  // VERSION.minor
  localparam int unsigned RegVersionMinorBits = 8;  // VERSION.minor width
  localparam int unsigned RegVersionMajorLsb = 8;  // VERSION.major
  localparam int unsigned RegVersionMajorBits = 8;  // VERSION.major width
  localparam int unsigned RegVersionCoefLayoutLsb = 16;  // VERSION.coef_layout
  localparam int unsigned RegVersionCoefLayoutBits = 8;  // VERSION.coef_layout width
  // CONFIG: widths and modes the core was built with (the pipeline configuration)
  localparam int unsigned RegConfigOffset = 8;
  localparam int unsigned RegConfigAdcBitsLsb = 0;  // CONFIG.adc_bits
  localparam int unsigned RegConfigAdcBitsBits = 8;  // CONFIG.adc_bits width
  localparam int unsigned RegConfigOutBitsLsb = 8;  // CONFIG.out_bits
  localparam int unsigned RegConfigOutBitsBits = 8;  // CONFIG.out_bits width
  localparam int unsigned RegConfigWordBitsLsb = 16;  // CONFIG.word_bits
  localparam int unsigned RegConfigWordBitsBits = 8;  // CONFIG.word_bits width
  localparam int unsigned RegConfigMethodLsb = 24;  // CONFIG.method
  localparam int unsigned RegConfigMethodBits = 3;  // CONFIG.method width
  localparam int unsigned RegConfigBlindDriftLsb = 27;  // CONFIG.blind_drift
  localparam int unsigned RegConfigFfcLsb = 28;  // CONFIG.ffc
  localparam int unsigned RegConfigRoundingLsb = 29;  // CONFIG.rounding
  localparam int unsigned RegConfigRoundingBits = 2;  // CONFIG.rounding width
  localparam int unsigned RegConfigOverflowLsb = 31;  // CONFIG.overflow
  // FORMAT: the gain and offset formats (compare with the memory image manifest)
  localparam int unsigned RegFormatOffset = 12;
  localparam int unsigned RegFormatGainIntBitsLsb = 0;  // FORMAT.gain_int_bits
  localparam int unsigned RegFormatGainIntBitsBits = 8;  // FORMAT.gain_int_bits width
  localparam int unsigned RegFormatGainFracBitsLsb = 8;  // FORMAT.gain_frac_bits
  localparam int unsigned RegFormatGainFracBitsBits = 8;  // FORMAT.gain_frac_bits width
  localparam int unsigned RegFormatOffsetIntBitsLsb = 16;  // FORMAT.offset_int_bits
  localparam int unsigned RegFormatOffsetIntBitsBits = 8;  // FORMAT.offset_int_bits width
  localparam int unsigned RegFormatOffsetFracBitsLsb = 24;  // FORMAT.offset_frac_bits
  localparam int unsigned RegFormatOffsetFracBitsBits = 8;  // FORMAT.offset_frac_bits width
  // FRAME_MAX: the largest frame the line buffers hold
  localparam int unsigned RegFrameMaxOffset = 16;
  localparam int unsigned RegFrameMaxWidthLsb = 0;  // FRAME_MAX.width
  localparam int unsigned RegFrameMaxWidthBits = 16;  // FRAME_MAX.width width
  localparam int unsigned RegFrameMaxHeightLsb = 16;  // FRAME_MAX.height
  localparam int unsigned RegFrameMaxHeightBits = 16;  // FRAME_MAX.height width
  localparam int unsigned RegCtrlOffset = 32;  // CTRL: what the core does with each frame
  localparam int unsigned RegCtrlNucEnLsb = 0;  // CTRL.nuc_en
  localparam int unsigned RegCtrlNucEnReset = 1;  // CTRL.nuc_en reset
  localparam int unsigned RegCtrlDpcEnLsb = 1;  // CTRL.dpc_en
  localparam int unsigned RegCtrlDpcEnReset = 1;  // CTRL.dpc_en reset
  localparam int unsigned RegCtrlCoefSyncLsb = 8;  // CTRL.coef_sync
  localparam int unsigned RegCtrlCoefSyncReset = 1;  // CTRL.coef_sync reset
  // FRAME_SIZE: frame size; a write of 0 or above FRAME_MAX is refused (SLVERR, register unchanged); a new size waits until the previous frame has left the core
  localparam int unsigned RegFrameSizeOffset = 36;
  localparam int unsigned RegFrameSizeWidthLsb = 0;  // FRAME_SIZE.width
  localparam int unsigned RegFrameSizeWidthBits = 16;  // FRAME_SIZE.width width
  localparam int unsigned RegFrameSizeHeightLsb = 16;  // FRAME_SIZE.height
  localparam int unsigned RegFrameSizeHeightBits = 16;  // FRAME_SIZE.height width
  localparam int unsigned RegCommandOffset = 40;  // COMMAND: commands (write only)
  localparam int unsigned RegCommandClearCountersLsb = 0;  // COMMAND.clear_counters
  // STATUS: framing errors (sticky until written 1) and the state of the input
  localparam int unsigned RegStatusOffset = 48;
  localparam int unsigned RegStatusSofEarlyLsb = 0;  // STATUS.sof_early
  localparam int unsigned RegStatusSofEarlyReset = 0;  // STATUS.sof_early reset
  localparam int unsigned RegStatusSofLateLsb = 1;  // STATUS.sof_late
  localparam int unsigned RegStatusSofLateReset = 0;  // STATUS.sof_late reset
  localparam int unsigned RegStatusEolEarlyLsb = 2;  // STATUS.eol_early
  localparam int unsigned RegStatusEolEarlyReset = 0;  // STATUS.eol_early reset
  localparam int unsigned RegStatusEolLateLsb = 3;  // STATUS.eol_late
  localparam int unsigned RegStatusEolLateReset = 0;  // STATUS.eol_late reset
  localparam int unsigned RegStatusCoefEarlyLsb = 4;  // STATUS.coef_early
  localparam int unsigned RegStatusCoefEarlyReset = 0;  // STATUS.coef_early reset
  localparam int unsigned RegStatusCoefLateLsb = 5;  // STATUS.coef_late
  localparam int unsigned RegStatusCoefLateReset = 0;  // STATUS.coef_late reset
  localparam int unsigned RegStatusCoreErrLsb = 8;  // STATUS.core_err
  localparam int unsigned RegStatusInFrameLsb = 16;  // STATUS.in_frame
  localparam int unsigned RegStatusPendingLsb = 17;  // STATUS.pending
  localparam int unsigned RegIrqEnableOffset = 52;  // IRQ_ENABLE: which IRQ_STATUS bits drive irq_o
  localparam int unsigned RegIrqEnableErrorLsb = 0;  // IRQ_ENABLE.error
  localparam int unsigned RegIrqEnableErrorReset = 0;  // IRQ_ENABLE.error reset
  localparam int unsigned RegIrqEnableFrameDoneLsb = 1;  // IRQ_ENABLE.frame_done
  localparam int unsigned RegIrqEnableFrameDoneReset = 0;  // IRQ_ENABLE.frame_done reset
  localparam int unsigned RegIrqEnableFfcDoneLsb = 2;  // IRQ_ENABLE.ffc_done
  localparam int unsigned RegIrqEnableFfcDoneReset = 0;  // IRQ_ENABLE.ffc_done reset
  localparam int unsigned RegIrqEnableFfcRequestLsb = 3;  // IRQ_ENABLE.ffc_request
  localparam int unsigned RegIrqEnableFfcRequestReset = 0;  // IRQ_ENABLE.ffc_request reset
  // IRQ_STATUS: interrupt causes (sticky until written 1); irq_o = the OR of the bits set in both IRQ_STATUS and IRQ_ENABLE, registered
  localparam int unsigned RegIrqStatusOffset = 56;
  localparam int unsigned RegIrqStatusErrorLsb = 0;  // IRQ_STATUS.error
  localparam int unsigned RegIrqStatusErrorReset = 0;  // IRQ_STATUS.error reset
  localparam int unsigned RegIrqStatusFrameDoneLsb = 1;  // IRQ_STATUS.frame_done
  localparam int unsigned RegIrqStatusFrameDoneReset = 0;  // IRQ_STATUS.frame_done reset
  localparam int unsigned RegIrqStatusFfcDoneLsb = 2;  // IRQ_STATUS.ffc_done
  localparam int unsigned RegIrqStatusFfcDoneReset = 0;  // IRQ_STATUS.ffc_done reset
  localparam int unsigned RegIrqStatusFfcRequestLsb = 3;  // IRQ_STATUS.ffc_request
  localparam int unsigned RegIrqStatusFfcRequestReset = 0;  // IRQ_STATUS.ffc_request reset
  // FRAMES_IN: frames started at s_axis_video (start of frame accepted); wraps
  localparam int unsigned RegFramesInOffset = 64;
  localparam int unsigned RegFramesInCountLsb = 0;  // FRAMES_IN.count
  localparam int unsigned RegFramesInCountBits = 32;  // FRAMES_IN.count width
  // FRAMES_OUT: frames whose last pixel left m_axis_video; wraps
  localparam int unsigned RegFramesOutOffset = 68;
  localparam int unsigned RegFramesOutCountLsb = 0;  // FRAMES_OUT.count
  localparam int unsigned RegFramesOutCountBits = 32;  // FRAMES_OUT.count width
  // PIXELS_IN: beats taken from s_axis_video, dropped ones included; wraps
  localparam int unsigned RegPixelsInOffset = 72;
  localparam int unsigned RegPixelsInCountLsb = 0;  // PIXELS_IN.count
  localparam int unsigned RegPixelsInCountBits = 32;  // PIXELS_IN.count width
  localparam int unsigned RegPixelsOutOffset = 76;  // PIXELS_OUT: beats sent on m_axis_video; wraps
  localparam int unsigned RegPixelsOutCountLsb = 0;  // PIXELS_OUT.count
  localparam int unsigned RegPixelsOutCountBits = 32;  // PIXELS_OUT.count width
  // DROPPED: beats of s_axis_video dropped (late markers); wraps
  localparam int unsigned RegDroppedOffset = 80;
  localparam int unsigned RegDroppedCountLsb = 0;  // DROPPED.count
  localparam int unsigned RegDroppedCountBits = 32;  // DROPPED.count width
  // PADDED: filler pixels inserted (early markers); wraps
  localparam int unsigned RegPaddedOffset = 84;
  localparam int unsigned RegPaddedCountLsb = 0;  // PADDED.count
  localparam int unsigned RegPaddedCountBits = 32;  // PADDED.count width
  // SOF_ERRORS: start-of-frame errors, each counted once; wrap
  localparam int unsigned RegSofErrorsOffset = 88;
  localparam int unsigned RegSofErrorsEarlyLsb = 0;  // SOF_ERRORS.early
  localparam int unsigned RegSofErrorsEarlyBits = 16;  // SOF_ERRORS.early width
  localparam int unsigned RegSofErrorsLateLsb = 16;  // SOF_ERRORS.late
  localparam int unsigned RegSofErrorsLateBits = 16;  // SOF_ERRORS.late width
  // EOL_ERRORS: end-of-line errors, each counted once; wrap
  localparam int unsigned RegEolErrorsOffset = 92;
  localparam int unsigned RegEolErrorsEarlyLsb = 0;  // EOL_ERRORS.early
  localparam int unsigned RegEolErrorsEarlyBits = 16;  // EOL_ERRORS.early width
  localparam int unsigned RegEolErrorsLateLsb = 16;  // EOL_ERRORS.late
  localparam int unsigned RegEolErrorsLateBits = 16;  // EOL_ERRORS.late width
  // COEF_ERRORS: coefficient stream errors (CTRL.coef_sync = 1), each counted once; wrap
  localparam int unsigned RegCoefErrorsOffset = 96;
  localparam int unsigned RegCoefErrorsEarlyLsb = 0;  // COEF_ERRORS.early
  localparam int unsigned RegCoefErrorsEarlyBits = 16;  // COEF_ERRORS.early width
  localparam int unsigned RegCoefErrorsLateLsb = 16;  // COEF_ERRORS.late
  localparam int unsigned RegCoefErrorsLateBits = 16;  // COEF_ERRORS.late width
  // FFC_CTRL: flat-field correction: FFC_CTRL.frames shutter frames from the next frame start; N of them (ffc_frames) are averaged into the FFC offsets (docs/integration.md, FFC)
  localparam int unsigned RegFfcCtrlOffset = 128;
  localparam int unsigned RegFfcCtrlStartLsb = 0;  // FFC_CTRL.start
  localparam int unsigned RegFfcCtrlFramesLsb = 16;  // FFC_CTRL.frames
  localparam int unsigned RegFfcCtrlFramesBits = 11;  // FFC_CTRL.frames width
  localparam int unsigned RegFfcStatusOffset = 132;  // FFC_STATUS: flat-field correction state
  localparam int unsigned RegFfcStatusBusyLsb = 0;  // FFC_STATUS.busy
  localparam int unsigned RegFfcStatusDoneLsb = 1;  // FFC_STATUS.done
  // FFC_PERIOD: FFC request period: IRQ_STATUS.ffc_request rises at the frame start where FFC_TRIGGER.since reaches it (docs/integration.md, FFC requests)
  localparam int unsigned RegFfcPeriodOffset = 136;
  localparam int unsigned RegFfcPeriodFramesLsb = 0;  // FFC_PERIOD.frames
  localparam int unsigned RegFfcPeriodFramesBits = 24;  // FFC_PERIOD.frames width
  localparam int unsigned RegFfcPeriodFramesReset = 0;  // FFC_PERIOD.frames reset
  // FFC_THRESHOLD: FFC request threshold: IRQ_STATUS.ffc_request rises at the frame start where |READING - FFC_REF.reading| reaches it (READING as the frame takes it; a build without the FPA reading reads 0 there: use the period)
  localparam int unsigned RegFfcThresholdOffset = 140;
  localparam int unsigned RegFfcThresholdCodesLsb = 0;  // FFC_THRESHOLD.codes
  localparam int unsigned RegFfcThresholdCodesBits = 24;  // FFC_THRESHOLD.codes width
  localparam int unsigned RegFfcThresholdCodesReset = 0;  // FFC_THRESHOLD.codes reset
  // FFC_TRIGGER: the FFC request's state, updated a few cycles after each frame start
  localparam int unsigned RegFfcTriggerOffset = 144;
  localparam int unsigned RegFfcTriggerSinceLsb = 0;  // FFC_TRIGGER.since
  localparam int unsigned RegFfcTriggerSinceBits = 24;  // FFC_TRIGGER.since width
  localparam int unsigned RegFfcTriggerPeriodLsb = 24;  // FFC_TRIGGER.period
  localparam int unsigned RegFfcTriggerThresholdLsb = 25;  // FFC_TRIGGER.threshold
  // FFC_REF: the FPA reading of the last FFC (of the frame its FFC_CTRL.start applied to)
  localparam int unsigned RegFfcRefOffset = 148;
  localparam int unsigned RegFfcRefReadingLsb = 0;  // FFC_REF.reading
  localparam int unsigned RegFfcRefReadingBits = 24;  // FFC_REF.reading width
  localparam int unsigned RegGainLoOffset = 256;  // GAIN.LO: one_point: the global gain, U Gi.Gf
  localparam int unsigned RegGainHiOffset = 260;  // GAIN.HI
  // LEVEL.LO: piecewise: the output at every pixel's knee
  localparam int unsigned RegLevelLoOffset = 264;
  localparam int unsigned RegLevelHiOffset = 268;  // LEVEL.HI
  // READING.LO: the FPA temperature sensor reading for the next frame
  localparam int unsigned RegReadingLoOffset = 272;
  localparam int unsigned RegReadingHiOffset = 276;  // READING.HI
  // T_REF.LO: tc_offset, tc_housing: the FPA reading at which the polynomials are centred
  localparam int unsigned RegTRefLoOffset = 280;
  localparam int unsigned RegTRefHiOffset = 284;  // T_REF.HI
  // BLIND_SUM.LO: blind_drift: the sum of the frame's blind pixel codes
  localparam int unsigned RegBlindSumLoOffset = 288;
  localparam int unsigned RegBlindSumHiOffset = 292;  // BLIND_SUM.HI
  // BLIND_REF.LO: blind_drift: the blind pixel sum at calibration
  localparam int unsigned RegBlindRefLoOffset = 296;
  localparam int unsigned RegBlindRefHiOffset = 300;  // BLIND_REF.HI
  // DRIFT_GAIN.LO: blind_drift: drift (ADC codes) per code of blind sum change, two's complement
  localparam int unsigned RegDriftGainLoOffset = 304;
  localparam int unsigned RegDriftGainHiOffset = 308;  // DRIFT_GAIN.HI
  // FFC_TARGET.LO: ffc: the output level the FFC flattens the shutter to
  localparam int unsigned RegFfcTargetLoOffset = 312;
  localparam int unsigned RegFfcTargetHiOffset = 316;  // FFC_TARGET.HI
  // HOUSING_READING.LO: the housing temperature sensor reading for the next frame
  localparam int unsigned RegHousingReadingLoOffset = 320;
  localparam int unsigned RegHousingReadingHiOffset = 324;  // HOUSING_READING.HI
  // H_REF.LO: tc_housing: the housing reading at which the polynomials are centred
  localparam int unsigned RegHRefLoOffset = 328;
  localparam int unsigned RegHRefHiOffset = 332;  // H_REF.HI
  // TABLE_READING[0]: table_interp: the reading of table k (strictly increasing); entries past the configured tables are reserved
  localparam int unsigned RegTableReadingOffset = 384;
  localparam int unsigned RegTableReadingStride = 4;  // TABLE_READING[k] spacing
  localparam int unsigned RegTableReadingCount = 16;  // TABLE_READING[k] entries
  // TABLE_SEL: table_interp: the table pair and weight interp_weight computed from the pending READING and TABLE_READING[k] (the next frame's; point the coefficient DMA at the pair image of tables j and j + 1)
  localparam int unsigned RegTableSelOffset = 448;
  localparam int unsigned RegTableSelWeightLsb = 0;  // TABLE_SEL.weight
  localparam int unsigned RegTableSelWeightBits = 24;  // TABLE_SEL.weight width
  localparam int unsigned RegTableSelJLsb = 24;  // TABLE_SEL.j
  localparam int unsigned RegTableSelJBits = 4;  // TABLE_SEL.j width
  localparam int unsigned RegTableSelValidLsb = 28;  // TABLE_SEL.valid
  localparam int unsigned RegTableSelErrorLsb = 29;  // TABLE_SEL.error
  // ---- legal parameter ranges (asserted by every module taking them)
  localparam int unsigned AdcBitsMin = 1;
  localparam int unsigned AdcBitsMax = 24;  // bits
  localparam int unsigned GainIntBitsMin = 0;
  localparam int unsigned GainIntBitsMax = 16;  // bits
  localparam int unsigned GainFracBitsMin = 0;
  localparam int unsigned GainFracBitsMax = 32;  // bits
  localparam int unsigned OffsetIntBitsMin = 1;
  localparam int unsigned OffsetIntBitsMax = 32;  // bits
  localparam int unsigned OffsetFracBitsMin = 0;
  localparam int unsigned OffsetFracBitsMax = 32;  // bits
  localparam int unsigned OutBitsMin = 1;
  localparam int unsigned OutBitsMax = 24;  // bits
  localparam int unsigned MaxWidthMin = 1;
  localparam int unsigned MaxWidthMax = 65535;  // pixels
  localparam int unsigned MaxHeightMin = 1;
  localparam int unsigned MaxHeightMax = 65535;  // pixels
  // ---- rounding of the NUC sum (module parameter Rounding)
  typedef enum logic [1:0] {
    RoundTruncate = 2'd0,  // floor: s >>> F
    RoundHalfUp = 2'd1,  // ties toward +infinity
    RoundHalfEven = 2'd2  // ties to the even integer
  } rounding_e;
  localparam int unsigned RoundingCount = 3;
  // ---- overflow of the NUC output (module parameter Overflow)
  typedef enum logic [0:0] {
    OverflowSaturate = 1'd0,  // clamp to 0 .. 2^B - 1
    OverflowWrap = 1'd1  // keep the low B bits
  } overflow_e;
  localparam int unsigned OverflowCount = 2;
  // ---- base correction method (parameter Method of the tops; the order of the registry, nuc_fixed.methods.BASES)
  typedef enum logic [2:0] {
    MethodOnePoint = 3'd0,  // per-pixel offset, global gain register
    MethodTwoPoint = 3'd1,  // per-pixel gain and offset
    MethodPiecewise = 3'd2,  // two gains meeting at a per-pixel knee
    MethodQuadratic = 3'd3,  // gain, offset and a quadratic term
    MethodTcOffset = 3'd4,  // coefficients polynomial in the FPA reading
    MethodTableInterp = 3'd5,  // two tables interpolated by a weight
    MethodTcHousing = 3'd6  // offset polynomial in the FPA and the housing readings
  } method_e;
  localparam int unsigned MethodCount = 7;
  // ---- coef_word, version 1: coefficient word of the two-point NUC, memory image version 1
  // (fields from bit 0 up: gain [GainBits], offset [OffsetBits], bad [1])
  function automatic int unsigned coef_word_bits(
    input int unsigned gain_bits,
    input int unsigned offset_bits);
    return gain_bits + offset_bits + 32'd1;
  endfunction
  function automatic int unsigned coef_word_gain_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned coef_word_offset_lsb(input int unsigned gain_bits);
    return gain_bits;
  endfunction
  function automatic int unsigned coef_word_bad_lsb(
    input int unsigned gain_bits,
    input int unsigned offset_bits);
    return gain_bits + offset_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class coef_word #(
    parameter int unsigned GainBits = 1,
    parameter int unsigned OffsetBits = 1
  );
    typedef struct packed {
      logic bad;  // defective-pixel flag
      logic [OffsetBits-1:0] offset;  // offset code, two's complement
      logic [GainBits-1:0] gain;  // gain code, unsigned
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- coef_one_point, version 2: coefficient word of one_point (the gain is a register)
  // (fields from bit 0 up: offset [OffsetBits], bad [1])
  function automatic int unsigned coef_one_point_bits(input int unsigned offset_bits);
    return offset_bits + 32'd1;
  endfunction
  function automatic int unsigned coef_one_point_offset_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned coef_one_point_bad_lsb(input int unsigned offset_bits);
    return offset_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class coef_one_point #(
    parameter int unsigned OffsetBits = 1
  );
    typedef struct packed {
      logic bad;  // defective-pixel flag
      logic [OffsetBits-1:0] offset;  // offset code, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- coef_piecewise, version 2: coefficient word of piecewise
  // (fields from bit 0 up: gain_lo [GainBits], gain_hi [GainBits], knee [KneeBits], bad [1])
  function automatic int unsigned coef_piecewise_bits(
    input int unsigned gain_bits,
    input int unsigned knee_bits);
    return gain_bits + gain_bits + knee_bits + 32'd1;
  endfunction
  function automatic int unsigned coef_piecewise_gain_lo_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned coef_piecewise_gain_hi_lsb(input int unsigned gain_bits);
    return gain_bits;
  endfunction
  function automatic int unsigned coef_piecewise_knee_lsb(input int unsigned gain_bits);
    return gain_bits + gain_bits;
  endfunction
  function automatic int unsigned coef_piecewise_bad_lsb(
    input int unsigned gain_bits,
    input int unsigned knee_bits);
    return gain_bits + gain_bits + knee_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class coef_piecewise #(
    parameter int unsigned GainBits = 1,
    parameter int unsigned KneeBits = 1
  );
    typedef struct packed {
      logic bad;  // defective-pixel flag
      logic [KneeBits-1:0] knee;  // knee, ADC codes, unsigned
      logic [GainBits-1:0] gain_hi;  // gain above the knee, unsigned
      logic [GainBits-1:0] gain_lo;  // gain at and below the knee, unsigned
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- quad_word, version 2: quadratic's second memory
  // (fields from bit 0 up: quad [QuadBits])
  function automatic int unsigned quad_word_bits(input int unsigned quad_bits);
    return quad_bits;
  endfunction
  function automatic int unsigned quad_word_quad_lsb();
    return 32'd0;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class quad_word #(
    parameter int unsigned QuadBits = 1
  );
    typedef struct packed {
      logic [QuadBits-1:0] quad;  // quadratic term at x = 2^A, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- tc_word1, version 2: tc_offset's offset polynomial of order 1
  // (fields from bit 0 up: tc1 [Tc1Bits])
  function automatic int unsigned tc_word1_bits(input int unsigned tc1_bits);
    return tc1_bits;
  endfunction
  function automatic int unsigned tc_word1_tc1_lsb();
    return 32'd0;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class tc_word1 #(
    parameter int unsigned Tc1Bits = 1
  );
    typedef struct packed {
      logic [Tc1Bits-1:0] tc1;  // offset change per v, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- tc_word2, version 2: tc_offset's offset polynomial of order 2
  // (fields from bit 0 up: tc1 [Tc1Bits], tc2 [Tc2Bits])
  function automatic int unsigned tc_word2_bits(
    input int unsigned tc1_bits,
    input int unsigned tc2_bits);
    return tc1_bits + tc2_bits;
  endfunction
  function automatic int unsigned tc_word2_tc1_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned tc_word2_tc2_lsb(input int unsigned tc1_bits);
    return tc1_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class tc_word2 #(
    parameter int unsigned Tc1Bits = 1,
    parameter int unsigned Tc2Bits = 1
  );
    typedef struct packed {
      logic [Tc2Bits-1:0] tc2;  // offset change per v^2, two's complement
      logic [Tc1Bits-1:0] tc1;  // offset change per v, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- tg_word1, version 2: tc_offset's gain polynomial of order 1 (tc_gain)
  // (fields from bit 0 up: tg1 [Tg1Bits])
  function automatic int unsigned tg_word1_bits(input int unsigned tg1_bits);
    return tg1_bits;
  endfunction
  function automatic int unsigned tg_word1_tg1_lsb();
    return 32'd0;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class tg_word1 #(
    parameter int unsigned Tg1Bits = 1
  );
    typedef struct packed {
      logic [Tg1Bits-1:0] tg1;  // gain change per v, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- tg_word2, version 2: tc_offset's gain polynomial of order 2 (tc_gain)
  // (fields from bit 0 up: tg1 [Tg1Bits], tg2 [Tg2Bits])
  function automatic int unsigned tg_word2_bits(
    input int unsigned tg1_bits,
    input int unsigned tg2_bits);
    return tg1_bits + tg2_bits;
  endfunction
  function automatic int unsigned tg_word2_tg1_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned tg_word2_tg2_lsb(input int unsigned tg1_bits);
    return tg1_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class tg_word2 #(
    parameter int unsigned Tg1Bits = 1,
    parameter int unsigned Tg2Bits = 1
  );
    typedef struct packed {
      logic [Tg2Bits-1:0] tg2;  // gain change per v^2, two's complement
      logic [Tg1Bits-1:0] tg1;  // gain change per v, two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- frame_tc_offset, version 2: tc_offset's frame word (method_dpc_top's s_pix_frame_i, read with the frame's first pixel)
  // (fields from bit 0 up: reading [ReadingBits], t_ref [ReadingBits])
  function automatic int unsigned frame_tc_offset_bits(input int unsigned reading_bits);
    return reading_bits + reading_bits;
  endfunction
  function automatic int unsigned frame_tc_offset_reading_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned frame_tc_offset_t_ref_lsb(input int unsigned reading_bits);
    return reading_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class frame_tc_offset #(
    parameter int unsigned ReadingBits = 1
  );
    typedef struct packed {
      logic [ReadingBits-1:0] t_ref;  // the reading the polynomials are centred at, unsigned
      logic [ReadingBits-1:0] reading;  // the frame's FPA reading, unsigned
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- housing_word, version 2: tc_housing's housing terms of the offset polynomial
  // (fields from bit 0 up: th1 [Th1Bits], thx [ThxBits], th2 [Th2Bits])
  function automatic int unsigned housing_word_bits(
    input int unsigned th1_bits,
    input int unsigned thx_bits,
    input int unsigned th2_bits);
    return th1_bits + thx_bits + th2_bits;
  endfunction
  function automatic int unsigned housing_word_th1_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned housing_word_thx_lsb(input int unsigned th1_bits);
    return th1_bits;
  endfunction
  function automatic int unsigned housing_word_th2_lsb(
    input int unsigned th1_bits,
    input int unsigned thx_bits);
    return th1_bits + thx_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class housing_word #(
    parameter int unsigned Th1Bits = 1,
    parameter int unsigned ThxBits = 1,
    parameter int unsigned Th2Bits = 1
  );
    typedef struct packed {
      logic [Th2Bits-1:0] th2;  // offset change per w'^2, two's complement
      logic [ThxBits-1:0] thx;  // offset change per v·w', two's complement
      logic [Th1Bits-1:0] th1;  // offset change per w', two's complement
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- frame_tc_housing, version 2: tc_housing's frame word (method_dpc_top's s_pix_frame_i, read with the frame's first pixel)
  // (fields from bit 0 up: reading [ReadingBits], t_ref [ReadingBits], housing_reading [HousingBits], h_ref [HousingBits])
  function automatic int unsigned frame_tc_housing_bits(
    input int unsigned reading_bits,
    input int unsigned housing_bits);
    return reading_bits + reading_bits + housing_bits + housing_bits;
  endfunction
  function automatic int unsigned frame_tc_housing_reading_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned frame_tc_housing_t_ref_lsb(input int unsigned reading_bits);
    return reading_bits;
  endfunction
  function automatic int unsigned frame_tc_housing_housing_reading_lsb(
    input int unsigned reading_bits);
    return reading_bits + reading_bits;
  endfunction
  function automatic int unsigned frame_tc_housing_h_ref_lsb(
    input int unsigned reading_bits,
    input int unsigned housing_bits);
    return reading_bits + reading_bits + housing_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class frame_tc_housing #(
    parameter int unsigned ReadingBits = 1,
    parameter int unsigned HousingBits = 1
  );
    typedef struct packed {
      logic [HousingBits-1:0] h_ref;  // the housing reading the polynomials are centred at, unsigned
      logic [HousingBits-1:0] housing_reading;  // the frame's housing reading, unsigned
      logic [ReadingBits-1:0] t_ref;  // the FPA reading the polynomials are centred at, unsigned
      logic [ReadingBits-1:0] reading;  // the frame's FPA reading, unsigned
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  // ---- frame_blind_drift, version 1: blind_drift's frame word in irnuc_axis_top (the framer's, taken at a frame start from the shadowed registers)
  // (fields from bit 0 up: base [BaseBits], blind_sum [SumBits], blind_ref [SumBits], drift_gain [DriftGainBits])
  function automatic int unsigned frame_blind_drift_bits(
    input int unsigned base_bits,
    input int unsigned sum_bits,
    input int unsigned drift_gain_bits);
    return base_bits + sum_bits + sum_bits + drift_gain_bits;
  endfunction
  function automatic int unsigned frame_blind_drift_base_lsb();
    return 32'd0;
  endfunction
  function automatic int unsigned frame_blind_drift_blind_sum_lsb(input int unsigned base_bits);
    return base_bits;
  endfunction
  function automatic int unsigned frame_blind_drift_blind_ref_lsb(
    input int unsigned base_bits,
    input int unsigned sum_bits);
    return base_bits + sum_bits;
  endfunction
  function automatic int unsigned frame_blind_drift_drift_gain_lsb(
    input int unsigned base_bits,
    input int unsigned sum_bits);
    return base_bits + sum_bits + sum_bits;
  endfunction
  /* verilator lint_off DECLFILENAME */  // a class in the package
  virtual class frame_blind_drift #(
    parameter int unsigned BaseBits = 1,
    parameter int unsigned SumBits = 1,
    parameter int unsigned DriftGainBits = 1
  );
    typedef struct packed {
      logic [DriftGainBits-1:0] drift_gain;  // drift per code of blind sum change, two's complement
      logic [SumBits-1:0] blind_ref;  // the blind pixel sum at calibration, unsigned
      logic [SumBits-1:0] blind_sum;  // the frame's blind pixel sum, unsigned
      logic [BaseBits-1:0] base;  // the base method's frame word (one_point's gain; two_point: one unused bit)
    } word_t;
  endclass
  /* verilator lint_on DECLFILENAME */
  /* verilator lint_on UNUSEDPARAM */
  // irnuc-spec: end

  // ---- multipliers ---------------------------------------------------------------------
  // Operands are cut into chunks of MulChunkBits bits: an unsigned chunk then fits the
  // signed 18x18 multiplier of an ECP5 (MULT18X18D) and the 25x18 one of a 7-series
  // (DSP48E1), so every partial product is one DSP block with registered inputs and a
  // registered output (irnuc_mul_parts).

  function automatic int unsigned mul_chunks(input int unsigned bits);
    return (bits + MulChunkBits - 32'd1) / MulChunkBits;
  endfunction

  function automatic int unsigned mul_parts(input int unsigned a_bits,
                                            input int unsigned b_bits);
    return mul_chunks(a_bits) * mul_chunks(b_bits);
  endfunction

  // ---- DPC -----------------------------------------------------------------------------
  // Frame and flush control of dpc_ctrl (see there).
  typedef enum logic [1:0] {
    DpcIdle  = 2'd0,  // no output owed; the next pixel starts a frame, its size is sampled
    DpcFrame = 2'd1,  // pixels of a frame are being taken
    DpcTail  = 2'd2,  // last pixel taken; W+1 outputs owed
    DpcFlush = 2'd3   // phantom items push the owed outputs out
  } dpc_state_e;

  // Division by n = 1..8 as (M * R[n]) >> K with K = B + DpcRecipGuardBits (6) and
  // R[n] = ceil(2^K / n): exact for every M < 2^(B+3) because
  // M * (R[n] n - 2^K) < 2^(B+3) * 8 = 2^K (cocotb_tests/test_dpc_core.py proves it for
  // every M and n; cocotb_tests/tb_pkg.py reads this table back from simulation).
  // R[0] = 0: n = 0 is never divided.
  function automatic int unsigned dpc_recip_shift(input int unsigned out_bits);
    return out_bits + DpcRecipGuardBits;
  endfunction

  function automatic longint unsigned dpc_recip(input int unsigned out_bits,
                                                input int unsigned n);
    longint unsigned num;
    if (n == 0) begin
      return 64'd0;
    end
    num = (64'd1 << dpc_recip_shift(out_bits)) + longint'(n) - 64'd1;
    return num / longint'(n);
  endfunction

  // ---- AXI ------------------------------------------------------------------------------
  // Response codes of BRESP and RRESP (the register file answers OKAY or SLVERR; EXOKAY is
  // not legal in AXI4-Lite; DECERR is the interconnect's).
  typedef enum logic [1:0] {
    AxiOkay   = 2'b00,
    AxiExOkay = 2'b01,
    AxiSlvErr = 2'b10,
    AxiDecErr = 2'b11
  } axi_resp_e;

  // The register file's byte lanes of a write strobe, and the bits of a value of `bits` bits
  // that lie in 32-bit word `word` (0: 31..0, 1: 63..32) of its register slot.
  function automatic logic [31:0] axil_byte_mask(input logic [3:0] strb);
    return {{8{strb[3]}}, {8{strb[2]}}, {8{strb[1]}}, {8{strb[0]}}};
  endfunction

  function automatic logic [31:0] axil_value_mask(input int unsigned bits,
                                                  input int unsigned word);
    int unsigned n;
    n = (bits > 32 * word) ? bits - 32 * word : 0;
    return (n >= 32) ? 32'hffff_ffff : (32'd1 << n) - 32'd1;
  endfunction

  // ---- AXI4-Stream framing (irnuc_axis_framer) ----------------------------------------
  // The video input: where the framer stands with respect to the programmed frame.
  typedef enum logic [1:0] {
    AxisWait  = 2'd0,  // no frame open; a beat with tuser[0] starts one (others are dropped)
    AxisFrame = 2'd1,  // inside a frame: beats are pixels
    AxisPad   = 2'd2,  // an early marker: filler pixels complete the line or the frame
    AxisDrop  = 2'd3   // a late end of line: beats are dropped up to the next tlast
  } axis_vid_state_e;

  // The coefficient input with CTRL.coef_sync: aligned to the pixels' frames by its tlast.
  typedef enum logic [1:0] {
    CoefNormal = 2'd0,  // one word per pixel
    CoefFill   = 2'd1,  // tlast came early: the frame's remaining pixels get the neutral word
    CoefSkip   = 2'd2   // no tlast on the frame's last word: words are dropped up to a tlast
  } axis_coef_state_e;

  // Bits of a count of items between the framer's output and the core's output (the
  // framer's items in flight, the FFC side's write-back words owed): fewer than the core's
  // window (max_width + 1) plus its registers; 256 is ample.
  function automatic int unsigned axis_flight_bits(input int unsigned max_width);
    return $clog2(max_width + 256 + 1);
  endfunction

  // ---- blind_drift ------------------------------------------------------------------------
  // Width of a frame's blind pixel sum: A + bit_length(blind_max) (Python:
  // PipelineConfig.blind_sum_bits), in blind_drift, method_drift_top and irnuc_axis_top.
  function automatic int unsigned blind_sum_bits(input int unsigned adc_bits,
                                                 input int unsigned blind_max);
    return adc_bits + $clog2(blind_max + 1);
  endfunction

endpackage
