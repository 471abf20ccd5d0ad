# Requests that would do nothing, or something other than what was asked, are errors with one
# clear line, never "applied" (fixture: example.vdb, whose levels lie within [-10, 10]^3).
lighthouse_cli_error(edit_erase_box_outside_the_volume
  EXPECT "--erase-box 100,100,100,101,101,101 lies wholly outside the volume" "change nothing"
  ABSENT edit_outside.vdb
  ARGS edit example.vdb --erase-box 100,100,100,101,101,101 -o edit_outside.vdb)
lighthouse_cli_error(edit_add_sphere_outside_the_volume
  EXPECT "--add-sphere 50,0,0,1 lies wholly outside the volume"
  ABSENT edit_outside_sphere.vdb
  ARGS edit example.vdb --add-sphere 50,0,0,1:1,1,1 -o edit_outside_sphere.vdb)
lighthouse_cli_error(edit_clamp_density_zero
  EXPECT "--clamp-density must be a positive density"
  ABSENT edit_clamp0.vdb
  ARGS edit example.vdb --clamp-density 0 -o edit_clamp0.vdb)
lighthouse_cli_error(edit_clamp_radiance_negative
  EXPECT "--clamp-radiance must be a positive radiance"
  ABSENT edit_clampneg.vdb
  ARGS edit example.vdb --clamp-radiance=-2 -o edit_clampneg.vdb)
lighthouse_cli_error(edit_output_with_an_image_name
  EXPECT "edit[.]exr.*must end in [.]vdb"
  ABSENT edit.exr
  ARGS edit example.vdb --scale-radiance 2 -o edit.exr)
lighthouse_cli_error(sparsify_tau_zero
  EXPECT "--tau must be positive"
  ABSENT sparse_tau0.vdb
  ARGS sparsify example.vdb --tau 0 -o sparse_tau0.vdb)
lighthouse_cli_error(sparsify_tau_negative
  EXPECT "--tau must be positive"
  ABSENT sparse_tauneg.vdb
  ARGS sparsify example.vdb --tau=-0.5 -o sparse_tauneg.vdb)

# Inputs are never overwritten, existing exports are kept unless --force, long names write.
add_test(NAME cli.no_lost_input
  COMMAND bash ${LH_CLI_SCRIPTS}/no_lost_input.sh ${LH_CLI_EXE} ${CMAKE_CURRENT_BINARY_DIR}/no_lost_input)
set_tests_properties(cli.no_lost_input PROPERTIES TIMEOUT 120 LABELS cli)
# Requests that work but may not be what was meant say so with a warning line.
add_test(NAME cli.warnings
  COMMAND bash ${LH_CLI_SCRIPTS}/warnings_test.sh ${LH_CLI_EXE} ${CMAKE_CURRENT_BINARY_DIR}/warnings)
set_tests_properties(cli.warnings PROPERTIES TIMEOUT 120 LABELS cli)

# A folder that cannot be written (/sys refuses new files, even to root) is named as such,
# with the reason, not as the encoder's failure.
lighthouse_cli_error(output_folder_not_writable
  EXPECT "cannot create a file in the folder '/sys'" "write permission is needed"
  ABSENT /sys/lh_env.png
  ARGS render-envmap example.vdb --at 0,0,1 --size 16x8 -o /sys/lh_env.png)
