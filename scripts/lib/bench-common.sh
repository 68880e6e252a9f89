# Shared by the benchmarks that measure igi-render against a pt reference
# (bench-converge.sh, bench-time-to-flip.sh); sourced from the repository root.

# Seconds igi-render reports on its summary line ("..., 1.234 s, ...").
seconds() { sed -n 's/.*, \([0-9.]*\) s, .*/\1/p'; }

# Where the pt reference of SCENE at SIZE and SPP is cached: one file the benchmarks share.
pt_reference() { echo "results/converge/$1-pt-$2-$3.exr"; }
