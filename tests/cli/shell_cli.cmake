# `lighthouse shell`: bad input fails with one clear line and leaves no output behind; a good
# run writes a loadable volume and says how many voxels it kept.
lighthouse_cli_error(shell_random_bytes
  EXPECT "random[.]vdb.*VDB"
  ABSENT shell_random.vdb
  ARGS shell random.vdb -o shell_random.vdb)
lighthouse_cli_error(shell_output_not_vdb
  EXPECT "output 'shell[.]exr' must end in [.]vdb [(]the shell volume[)]"
  ABSENT shell.exr
  ARGS shell example.vdb -o shell.exr)
lighthouse_cli_error(shell_centre_outside_the_volume
  EXPECT "centre [(]100, 0, 0[)] lies outside the volume.*choose a point inside the room"
  ABSENT shell_outside.vdb
  ARGS shell example.vdb --centre 100,0,0 -o shell_outside.vdb)
lighthouse_cli_error(shell_centre_not_a_point
  EXPECT "--centre"
  ABSENT shell_nan.vdb
  ARGS shell example.vdb --centre 1,nan,0 -o shell_nan.vdb)
lighthouse_cli_ok(shell_example
  STDOUT "shell around [(]0, 0, 1[.]75[)] in .* s: [0-9]+ -> [0-9]+ active voxels -> shell_example[.]vdb [(]the medium the reference camera sees kept as it was[)]"
  FILES shell_example.vdb
  ARGS shell example.vdb -o shell_example.vdb)
lighthouse_cli_ok(shell_example_is_a_volume
  STDOUT "3 level[(]s[)]"
  ARGS info shell_example.vdb)
# A shell says it is one, and is not collapsed again: the layer has dropped what lay behind it.
lighthouse_cli_ok(shell_example_says_it_is_a_shell
  STDOUT "shell: the medium collapsed around [(]0, 0, 1[.]75[)]"
  ARGS info shell_example.vdb)
lighthouse_cli_error(shell_of_a_shell
  EXPECT "'shell_example[.]vdb' is already a shell, collapsed around [(]0, 0, 1[.]75[)].*the fog of 'lighthouse predict --no-shell'"
  ABSENT shell_again.vdb
  ARGS shell shell_example.vdb --centre 0.5,0,2 -o shell_again.vdb)
set_tests_properties(cli.ok.shell_example PROPERTIES FIXTURES_SETUP lighthouse_shell)
foreach(t cli.ok.shell_example_is_a_volume cli.ok.shell_example_says_it_is_a_shell
          cli.error.shell_of_a_shell)
  set_tests_properties(${t} PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_shell")
endforeach()
# A centre inside a wall (the example room's red wall, near x = -2.6) still runs, with a warning
# that says why the shell will be wrong and what to choose instead.
add_test(NAME cli.warning.shell_centre_inside_a_wall
  COMMAND bash -c "\"$0\" shell example.vdb --centre -2.6,0,3 -o shell_wall.vdb 2>&1 | grep -q 'warning: --centre .* lies inside the medium .*choose a point in the room.s free space'"
          ${LH_CLI_EXE})
lighthouse_cli_properties(cli.warning.shell_centre_inside_a_wall)
# A shell that does not record its centre (written before shells did) is recognised all the
# same: every voxel outside the camera's view holds the opaque layer.
add_test(NAME cli.unmarked_shell
  COMMAND bash ${LH_CLI_SCRIPTS}/unmarked_shell_test.sh ${LH_CLI_EXE} ${LH_CLI_WORK}/shell_example.vdb
          ${LH_CLI_WORK}/unmarked_shell)
set_tests_properties(cli.unmarked_shell PROPERTIES
  FIXTURES_REQUIRED "lighthouse_cli;lighthouse_shell" TIMEOUT 120 LABELS cli
  PASS_REGULAR_EXPRESSION "all cases passed")
