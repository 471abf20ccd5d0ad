# `lighthouse sparsify` and `lighthouse bench-sparsity`: bad input fails with one clear line
# and leaves no output behind; a good run writes a smaller, loadable volume.
lighthouse_cli_error(sparsify_random_bytes
  EXPECT "random[.]vdb.*VDB"
  ABSENT sparse_random.vdb
  ARGS sparsify random.vdb -o sparse_random.vdb --tau 1e-3)
lighthouse_cli_error(sparsify_text_file
  EXPECT "text[.]vdb.*VDB"
  ABSENT sparse_text.vdb
  ARGS sparsify text.vdb -o sparse_text.vdb --tau 1e-3)
lighthouse_cli_error(sparsify_output_not_vdb
  EXPECT "output 'sparse[.]exr' must end in [.]vdb [(]the sparsified volume[)]"
  ABSENT sparse.exr
  ARGS sparsify example.vdb -o sparse.exr)
lighthouse_cli_error(sparsify_bad_tau
  EXPECT "tau must be in .0, 1."
  ABSENT sparse_badtau.vdb
  ARGS sparsify example.vdb -o sparse_badtau.vdb --tau 5)
lighthouse_cli_error(sparsify_bad_target
  EXPECT "--target-db must be in"
  ABSENT sparse_badtarget.vdb
  ARGS sparsify example.vdb -o sparse_badtarget.vdb --target-db -1)
lighthouse_cli_error(sparsify_bad_depth_range
  EXPECT "depth range needs finite 0 < near <= far"
  ABSENT sparse_baddepth.vdb
  ARGS sparsify example.vdb -o sparse_baddepth.vdb --tau 1e-3 --levels-from-depth 5,2)
lighthouse_cli_error(bench_sparsity_bad_taus
  EXPECT "--taus: expected numbers in .0, 1."
  ABSENT bench_sparsity_bad/memory_error.csv
  ARGS bench-sparsity example.vdb --taus 1e-3,abc -o bench_sparsity_bad)
lighthouse_cli_error(bench_sparsity_random_bytes
  EXPECT "random[.]vdb.*VDB"
  ABSENT bench_sparsity_random/memory_error.csv
  ARGS bench-sparsity random.vdb -o bench_sparsity_random)
# Floats unless --half, as every command that writes values.
lighthouse_cli_ok(sparsify_example
  STDOUT "active voxels" "sparse_example[.]vdb on disk [(]float"
  FILES sparse_example.vdb
  ARGS sparsify example.vdb -o sparse_example.vdb --tau 1e-3)
lighthouse_cli_ok(sparsify_example_half
  STDOUT "sparse_half[.]vdb on disk [(]half"
  FILES sparse_half.vdb
  ARGS sparsify example.vdb -o sparse_half.vdb --tau 1e-3 --half)
# Dense fog (every voxel has a little density, as predicted volumes do): bench-sparsity used
# to refuse it ("no empty space to put query points in"); it must now take the least dense
# points and write the full report. The fog is the fixture volume painted over with sigma 0.05.
lighthouse_cli_ok(sparsity_make_fog
  FILES fog.vdb
  ARGS edit example.vdb --add-box -100,-100,-100,100,100,100:0.4,0.3,0.2:0.05 -o fog.vdb)
lighthouse_cli_ok(bench_sparsity_fog
  STDOUT "unpruned" "tau 0[.]1" "where the bytes in memory go" "brightest colour 0[.]4"
         "Against the target, at the default bound tau 0[.]0001" "no row at that bound"
  FILES bench_sparsity_fog/memory_error.csv bench_sparsity_fog/memory_error.svg
        bench_sparsity_fog/memory_breakdown.md
  ARGS bench-sparsity fog.vdb --count 1 --size 16x8 --taus 1e-3,0.1 -o bench_sparsity_fog)
set_tests_properties(cli.ok.sparsity_make_fog PROPERTIES FIXTURES_SETUP lighthouse_fog)
set_tests_properties(cli.ok.bench_sparsity_fog PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_fog")
# Rounding to fewer mantissa bits: a bit count outside the range, or beyond what half floats
# keep, is refused before anything is written; a good run says what it stored.
lighthouse_cli_error(sparsify_mantissa_bits_out_of_range
  EXPECT "--mantissa-bits must be in .1, 22., got 30"
  ABSENT sparse_m30.vdb
  ARGS sparsify example.vdb -o sparse_m30.vdb --tau 1e-3 --mantissa-bits 30)
lighthouse_cli_error(sparsify_mantissa_bits_beyond_half
  EXPECT "--mantissa-bits must be in .1, 9. for half precision"
  ABSENT sparse_half_m10.vdb
  ARGS sparsify example.vdb -o sparse_half_m10.vdb --tau 1e-3 --half --mantissa-bits 10)
lighthouse_cli_error(bench_sparsity_half_and_mantissa_bits
  EXPECT "--half and --mantissa-bits each choose"
  ABSENT bench_sparsity_half_m7/memory_error.csv
  ARGS bench-sparsity example.vdb --half --mantissa-bits 7 -o bench_sparsity_half_m7)
lighthouse_cli_ok(sparsify_fog_mantissa_bits
  STDOUT "sparse_fog_m7[.]vdb on disk [(]float, 7-bit mantissas, Blosc"
  FILES sparse_fog_m7.vdb
  ARGS sparsify fog.vdb -o sparse_fog_m7.vdb --tau 1e-3 --mantissa-bits 7)
lighthouse_cli_ok(bench_sparsity_fog_mantissa_bits
  STDOUT "MB on disk [(]7-bit mantissas[)]" "floats rounded to 7 mantissa bits"
  FILES bench_sparsity_fog_m7/memory_error.csv
  ARGS bench-sparsity fog.vdb --count 1 --size 16x8 --taus 1e-4 --mantissa-bits 7
       -o bench_sparsity_fog_m7)
set_tests_properties(cli.ok.sparsify_fog_mantissa_bits cli.ok.bench_sparsity_fog_mantissa_bits
  PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_fog")
