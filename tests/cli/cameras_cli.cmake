# `lighthouse cameras`: a COLMAP text model of the demo pair (written by the script) converted
# end to end and checked against the pair's true cameras, its bad inputs, and `predict` on the
# result when the network is built (cameras_cli.sh). It makes its own work folder.
add_test(NAME cli.cameras.end_to_end
  COMMAND bash ${LH_CLI_SCRIPTS}/cameras_cli.sh ${LH_CLI_EXE}
          ${CMAKE_CURRENT_BINARY_DIR}/cameras_work ${LH_CLI_SCRIPTS}
          ${PROJECT_SOURCE_DIR}/data/demo_pair)
set_tests_properties(cli.cameras.end_to_end PROPERTIES
  TIMEOUT 300 LABELS cli)
