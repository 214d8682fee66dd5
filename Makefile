# See Makefile.verilator for the targets (make deps, build, sim, test, lint, synth).
include Makefile.verilator
