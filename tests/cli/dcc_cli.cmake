# `lighthouse export` / `lighthouse import` (houdini_export/): bad input gives one error line,
# a non-zero exit and no output left behind; a good export writes its directory.

lighthouse_cli_error(export_missing_file
  EXPECT "no_such_volume[.]vdb.*does not exist"
  ABSENT exp_missing
  ARGS export no_such_volume.vdb --for blender -o exp_missing)
lighthouse_cli_error(export_random_bytes
  EXPECT "random[.]vdb.*VDB"
  ABSENT exp_random
  ARGS export random.vdb --for blender -o exp_random)
lighthouse_cli_error(export_unknown_program
  EXPECT "--for: expected 'blender' or 'houdini', got 'maya'"
  ABSENT exp_maya
  ARGS export example.vdb --for maya -o exp_maya)
lighthouse_cli_error(export_over_a_directory_that_is_not_an_export
  EXPECT "adir.*not a lighthouse export.*refusing to overwrite"
  ARGS export example.vdb --for blender -o adir)
lighthouse_cli_error(export_output_missing_directory
  EXPECT "no_such_dir.*does not exist"
  ABSENT no_such_dir/exp
  ARGS export example.vdb --for houdini -o no_such_dir/exp)
lighthouse_cli_error(export_needs_for
  PARSE_ERROR EXPECT "--for.*required"
  ARGS export example.vdb -o exp_nofor)

lighthouse_cli_error(import_missing_export
  EXPECT "no_such_export.*does not exist"
  ABSENT imported_missing.vdb
  ARGS import no_such_export --from blender -o imported_missing.vdb)
lighthouse_cli_error(import_directory_without_manifest
  EXPECT "adir.*not a lighthouse export.*manifest[.]json"
  ABSENT imported_adir.vdb
  ARGS import adir --from blender -o imported_adir.vdb)
lighthouse_cli_error(import_a_vdb_file
  EXPECT "example[.]vdb.*not an export directory"
  ABSENT imported_file.vdb
  ARGS import example.vdb --from houdini -o imported_file.vdb)
lighthouse_cli_error(import_output_not_vdb
  EXPECT "output 'imported[.]exr' must end in [.]vdb"
  ABSENT imported.exr
  ARGS import adir --from blender -o imported.exr)
lighthouse_cli_error(import_unknown_program
  EXPECT "--from: expected 'blender' or 'houdini'"
  ABSENT imported_maya.vdb
  ARGS import adir --from maya -o imported_maya.vdb)

lighthouse_cli_ok(export_houdini
  STDOUT "3 level file[(]s[)] for houdini" "exp_houdini/level_2[.]vdb: level 2 shell"
  FILES exp_houdini/manifest.json exp_houdini/level_0.vdb exp_houdini/level_1.vdb exp_houdini/level_2.vdb
  ARGS export example.vdb --for houdini -o exp_houdini)
lighthouse_cli_ok(import_houdini
  STDOUT "exp_houdini -> imported_houdini[.]vdb: 3 level[(]s[)]"
  FILES imported_houdini.vdb
  ARGS import exp_houdini --from houdini -o imported_houdini.vdb)
# Fixtures, not just an order: running an import test alone (ctest -R) runs the export first.
set_tests_properties(cli.ok.export_houdini PROPERTIES FIXTURES_SETUP lighthouse_houdini_export)
set_tests_properties(cli.ok.import_houdini PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_houdini_export")
lighthouse_cli_error(import_houdini_export_as_blender
  EXPECT "exp_houdini.*exported for 'houdini', not for 'blender'"
  ABSENT imported_wrong.vdb
  ARGS import exp_houdini --from blender -o imported_wrong.vdb)
set_tests_properties(cli.error.import_houdini_export_as_blender PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_houdini_export")

# import --strict: an export holding NaN, Inf or negative values (set_voxel_value puts them in,
# as an edit in a DCC program might) is refused; without --strict they are replaced, with a
# warning.
add_executable(set_voxel_value ${CMAKE_CURRENT_SOURCE_DIR}/set_voxel_value.cpp)
target_link_libraries(set_voxel_value PRIVATE OpenVDB::openvdb)
add_test(NAME cli.import_strict
  COMMAND bash ${LH_CLI_SCRIPTS}/import_strict_test.sh ${LH_CLI_EXE} $<TARGET_FILE:set_voxel_value>
          ${CMAKE_CURRENT_BINARY_DIR}/import_strict)
set_tests_properties(cli.import_strict PROPERTIES TIMEOUT 120 LABELS cli PASS_REGULAR_EXPRESSION "all cases passed")
