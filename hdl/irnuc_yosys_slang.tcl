# Synthesis of irnuc_axis_top with Yosys through FuseSoC / edalize (hdl/irnuc.core, target
# synth): the RTL is SystemVerilog 2017 (packages, parameterised classes), read by the
# yosys-slang front end, not by read_verilog. edalize's procs (edalize_yosys_procs.tcl)
# give the files (read_verilog lines) and the parameters (chparam lines): here they are
# collected and handed to read_slang, which elaborates the top with them. Needs a Yosys
# with TCL and the slang plugin (OSS CAD Suite). irnuc's own flow is `irnuc synth`.
yosys -import
plugin -i slang
set irnuc_files {}
set irnuc_params {}
proc read_verilog {args} {
    global irnuc_files
    lappend irnuc_files [lindex $args end]
}
proc chparam {args} {
    global irnuc_params
    lappend irnuc_params -G [lindex $args 1]=[lindex $args 2]
}
proc verilog_defaults {args} {}
proc verilog_defines {args} {}
source edalize_yosys_procs.tcl
set_defines
read_files
set_params
read_slang -D SYNTHESIS --top irnuc_axis_top {*}$irnuc_params {*}$irnuc_files
hierarchy -top irnuc_axis_top
synth irnuc_axis_top
write_json irnuc_axis_top.json
