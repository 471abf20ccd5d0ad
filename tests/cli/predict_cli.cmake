# Command-line tests of `lighthouse predict`, `train` and `eval` (included by CMakeLists.txt
# when the network is built). The pair is the bundled demo pair; broken cameras files are
# derived from its cameras.json here.
set(LH_PAIR ${PROJECT_SOURCE_DIR}/data/demo_pair)
file(READ ${LH_PAIR}/cameras.json LH_PAIR_CAMERAS)
string(JSON LH_REF_CAMERA GET "${LH_PAIR_CAMERAS}" ref)
string(JSON LH_ZERO_BASELINE SET "${LH_PAIR_CAMERAS}" src "${LH_REF_CAMERA}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/pair_zero_baseline.json "${LH_ZERO_BASELINE}")
string(JSON LH_NO_RANGE REMOVE "${LH_PAIR_CAMERAS}" near)
string(JSON LH_NO_RANGE REMOVE "${LH_NO_RANGE}" far)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/pair_no_range.json "${LH_NO_RANGE}")
string(JSON LH_WIDE_BASELINE SET "${LH_PAIR_CAMERAS}" src cam_to_world 0 3 3.0)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/pair_wide_baseline.json "${LH_WIDE_BASELINE}")
string(JSON LH_TINY_NEAR SET "${LH_PAIR_CAMERAS}" near 1e-12)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/pair_tiny_near.json "${LH_TINY_NEAR}")
set(LH_PAIR_ARGS --ref ${LH_PAIR}/ref.png --src ${LH_PAIR}/src.png)
# libtorch reserves a lot of address space at start-up: allow it.
set(LH_TORCH_MB 16384)

lighthouse_cli_error(predict_zero_baseline
  EXPECT "same place [(]zero baseline[)]"
  ABSENT pred_bad1.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${CMAKE_CURRENT_BINARY_DIR}/pair_zero_baseline.json -o pred_bad1.vdb)
lighthouse_cli_error(predict_image_camera_mismatch
  EXPECT "reference image is 320x240 but cameras[.]json says 64x48"
  ABSENT pred_bad2.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras cameras_ok.json -o pred_bad2.vdb)
# An unwritable output folder is found before the network runs (no "predict:" progress).
lighthouse_cli_error(predict_output_folder_not_writable
  EXPECT "^lighthouse: error: cannot write '/sys/lh_pred[.]vdb': cannot create a file in the folder '/sys'"
  ABSENT /sys/lh_pred.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json -o /sys/lh_pred.vdb)
# OpenVDB's "nearly singular matrix" becomes a message about the cameras' depth range.
lighthouse_cli_error(predict_near_depth_implausibly_small
  EXPECT "the cameras' near depth is implausibly small"
  ABSENT pred_tiny_near.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${CMAKE_CURRENT_BINARY_DIR}/pair_tiny_near.json -o pred_tiny_near.vdb)
lighthouse_cli_error(predict_mantissa_bits_out_of_range
  EXPECT "--mantissa-bits must be in .1, 22., got 40"
  ABSENT pred_m40.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --mantissa-bits 40 -o pred_m40.vdb)
lighthouse_cli_error(predict_missing_image
  EXPECT "no_such_ref[.]png"
  ABSENT pred_bad3.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict --ref no_such_ref.png --src ${LH_PAIR}/src.png --cameras ${LH_PAIR}/cameras.json -o pred_bad3.vdb)
lighthouse_cli_error(predict_missing_model
  EXPECT "model file 'no_such_model[.]pt' not found"
  ABSENT pred_bad4.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --model no_such_model.pt -o pred_bad4.vdb)
lighthouse_cli_error(predict_not_a_model
  EXPECT "not a readable model file"
  ABSENT pred_bad5.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --model cameras_ok.json -o pred_bad5.vdb)
lighthouse_cli_error(predict_unknown_device
  EXPECT "unknown device"
  ABSENT pred_bad6.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --device tpu -o pred_bad6.vdb)
lighthouse_cli_error(predict_cuda_absent
  EXPECT "no CUDA"
  ABSENT pred_bad7.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --device cuda -o pred_bad7.vdb)
lighthouse_cli_error(predict_output_not_vdb
  EXPECT "must end in [.]vdb"
  ABSENT pred_bad8.png
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json -o pred_bad8.png)
lighthouse_cli_error(train_missing_data
  EXPECT "data directory 'no_such_dir' not found"
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS train --data no_such_dir -o train_bad.pt)
lighthouse_cli_error(train_unknown_config
  EXPECT "unknown configuration 'huge'"
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS train --data . --config huge -o train_bad.pt)
lighthouse_cli_error(train_irradiance_focus_out_of_range
  EXPECT "--irradiance-focus must be in .0, 4."
  ABSENT train_bad.pt
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS train --data . --irradiance-focus 9 -o train_bad.pt)
# lighthouse-net's parse errors are the same one line as lighthouse's.
lighthouse_cli_error(parse_unknown_option_of_train
  PARSE_ERROR EXPECT "not expected: --bogus.*run 'lighthouse train --help'"
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS train --data . --bogus)
lighthouse_cli_error(eval_not_a_data_set
  EXPECT "holds no examples"
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS eval --data . -o eval_bad)

if(EXISTS ${PROJECT_SOURCE_DIR}/models/standard.pt)
  # The bundled model, depth range from cameras.json and estimated from the pair.
  lighthouse_cli_ok(predict_bundled_model
    FILES pred_ok.vdb
    EXR pred_ok_000.exr
    PNG pred_ok_000.png
    ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --at 0.3,0.3,1.1 --png -o pred_ok.vdb)
  lighthouse_cli_ok(predict_estimated_range
    FILES pred_est.vdb
    ARGS predict ${LH_PAIR_ARGS} --cameras ${CMAKE_CURRENT_BINARY_DIR}/pair_no_range.json -o pred_est.vdb)
  # A source camera 3 m away runs, with a warning that names the likely mistake.
  add_test(NAME cli.warning.predict_implausible_baseline
    COMMAND bash -c "\"$0\" predict --ref \"$1\" --src \"$2\" --cameras \"$3\" -o pred_wide.vdb 2>&1 | grep -q 'warning: the source camera is 3 m from the reference'"
            ${LH_CLI_EXE} ${LH_PAIR}/ref.png ${LH_PAIR}/src.png ${CMAKE_CURRENT_BINARY_DIR}/pair_wide_baseline.json)
  lighthouse_cli_properties(cli.warning.predict_implausible_baseline)
  # The same photo as both views runs, with a warning that there is no parallax.
  add_test(NAME cli.warning.predict_identical_photos
    COMMAND bash -c "\"$0\" predict --ref \"$1\" --src \"$1\" --cameras \"$2\" -o pred_same.vdb 2>&1 | grep -q 'warning: the reference and source images are identical'"
            ${LH_CLI_EXE} ${LH_PAIR}/ref.png ${LH_PAIR}/cameras.json)
  lighthouse_cli_properties(cli.warning.predict_identical_photos)
  # An envmap point outside the predicted volume (here 100 m to the right) still renders, with
  # a warning that its envmap sees the volume from outside, as render-envmap warns.
  add_test(NAME cli.warning.predict_point_outside_the_volume
    COMMAND bash -c "\"$0\" predict --ref \"$1\" --src \"$2\" --cameras \"$3\" --at 100,0,1 -o pred_far.vdb 2>&1 | grep -q 'warning: point (100, 0, 1) lies outside every level of the volume' && test -s pred_far_000.exr"
            ${LH_CLI_EXE} ${LH_PAIR}/ref.png ${LH_PAIR}/src.png ${LH_PAIR}/cameras.json)
  lighthouse_cli_properties(cli.warning.predict_point_outside_the_volume)
  # A knee without a gain changes nothing: it runs, and says so.
  add_test(NAME cli.warning.predict_knee_without_gain
    COMMAND bash -c "\"$0\" predict --ref \"$1\" --src \"$2\" --cameras \"$3\" --highlight-knee 1.5 -o pred_knee_alone.vdb 2>&1 | grep -q 'warning: --highlight-knee changes nothing without a gain'"
            ${LH_CLI_EXE} ${LH_PAIR}/ref.png ${LH_PAIR}/src.png ${LH_PAIR}/cameras.json)
  lighthouse_cli_properties(cli.warning.predict_knee_without_gain)
  # An EXR photo pair of the example room (its lamps above 1): the bundled model reads it
  # clipped, and says so; the PNG pair has nothing above 1 and hears nothing of it.
  add_test(NAME cli.warning.predict_exr_photo_read_clipped
    COMMAND bash -c "\"$0\" render-view example.vdb --cameras cameras.json --view ref -o exr_ref.exr > /dev/null && \"$0\" render-view example.vdb --cameras cameras.json --view src -o exr_src.exr > /dev/null && \"$0\" predict --ref exr_ref.exr --src exr_src.exr --cameras cameras.json -o pred_exr.vdb 2>&1 | grep -q 'values above 1 ([0-9.]*% of them) are read clipped at 1, as the model was trained'"
            ${LH_CLI_EXE})
  lighthouse_cli_properties(cli.warning.predict_exr_photo_read_clipped)
  add_test(NAME cli.ok.predict_png_photo_says_nothing_of_clipping
    COMMAND bash -c "\"$0\" predict --ref \"$1\" --src \"$2\" --cameras \"$3\" -o pred_png_quiet.vdb > /dev/null 2> pred_png_quiet.log && grep -q '^predict: network' pred_png_quiet.log && ! grep -q 'above 1' pred_png_quiet.log"
            ${LH_CLI_EXE} ${LH_PAIR}/ref.png ${LH_PAIR}/src.png ${LH_PAIR}/cameras.json)
  lighthouse_cli_properties(cli.ok.predict_png_photo_says_nothing_of_clipping)
  lighthouse_cli_ok(predict_output_is_a_volume
    STDOUT "5 level[(]s[)]" "density_L4, color_L4, finest yes"
           "shell: the medium collapsed around [(]0, 0, [0-9.]+[)] [(]as predict does by default"
    ARGS info pred_ok.vdb)
  # --mantissa-bits 7 rounds the volume and the MPI: the same prediction in a smaller file.
  add_test(NAME cli.ok.predict_mantissa_bits_smaller
    COMMAND bash -c "\"$0\" predict --ref \"$1\" --src \"$2\" --cameras \"$3\" --mantissa-bits 7 -o pred_m7.vdb > /dev/null && test $(stat -c %s pred_m7.vdb) -lt $(stat -c %s pred_ok.vdb)"
            ${LH_CLI_EXE} ${LH_PAIR}/ref.png ${LH_PAIR}/src.png ${LH_PAIR}/cameras.json)
  lighthouse_cli_properties(cli.ok.predict_mantissa_bits_smaller)
  set_tests_properties(cli.ok.predict_mantissa_bits_smaller PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_predicted")
  # By default predict collapses the fog the camera did not see into an opaque shell (it says
  # so), and fewer than half of the voxels of the fog --no-shell writes remain.
  add_test(NAME cli.ok.predict_shell_fewer_voxels
    COMMAND bash -c "n=$(\"$0\" predict --ref \"$1\" --src \"$2\" --cameras \"$3\" -o pred_shell.vdb 2>&1 | sed -n 's/.* s; \\([0-9]*\\) active voxels.*collapsed into a shell.*/\\1/p') && m=$(\"$0\" predict --ref \"$1\" --src \"$2\" --cameras \"$3\" --no-shell -o pred_fog.vdb 2>&1 | grep -v 'collapsed into a shell' | sed -n 's/.* s; \\([0-9]*\\) active voxels.*/\\1/p') && test -n \"$n\" && test -n \"$m\" && test \"$n\" -lt $((m / 2))"
            ${LH_CLI_EXE} ${LH_PAIR}/ref.png ${LH_PAIR}/src.png ${LH_PAIR}/cameras.json)
  lighthouse_cli_properties(cli.ok.predict_shell_fewer_voxels)
  set_tests_properties(cli.ok.predict_shell_fewer_voxels PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_predicted")
  set_tests_properties(cli.ok.predict_bundled_model PROPERTIES FIXTURES_SETUP lighthouse_predicted)
  set_tests_properties(cli.ok.predict_output_is_a_volume PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_predicted")
endif()

# `lighthouse` hands the network's commands to `lighthouse-net` with every argument, global
# options included.
lighthouse_cli_ok(help_predict_through_lighthouse_net
  STDOUT "Usage:.*predict" "--ref" "--src" "--cameras" "--device"
  ARGS --threads 1 predict --help)

# The grammar in the network's commands: --threads on either side of the command word, train's
# -o and --half, predict's --at, --points and --png, and their old spellings.
if(EXISTS ${PROJECT_SOURCE_DIR}/models/standard.pt)
  set(LH_GRAMMAR_PAIR ${LH_PAIR})
else()
  set(LH_GRAMMAR_PAIR "")
endif()
add_test(NAME cli.grammar_net
  COMMAND bash ${LH_CLI_SCRIPTS}/grammar_net_test.sh ${LH_CLI_EXE} ${CMAKE_CURRENT_BINARY_DIR}/grammar_net
          "${LH_GRAMMAR_PAIR}")
set_tests_properties(cli.grammar_net PROPERTIES TIMEOUT 300 LABELS cli)
# A negative pruning threshold is refused by the option itself (negative means "the model's"
# only inside the library).
lighthouse_cli_error(predict_negative_prune_alpha
  EXPECT "--prune-alpha"
  ABSENT pred_negative_prune.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --prune-alpha -0.5 -o pred_negative_prune.vdb)
# A gain below 1 would dim the lamps: refused, nothing written.
lighthouse_cli_error(predict_highlight_gain_below_one
  EXPECT "--highlight-gain"
  ABSENT pred_dim.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --highlight-gain 0.5 -o pred_dim.vdb)
# A knee below white would expand the walls: refused, nothing written.
lighthouse_cli_error(predict_highlight_knee_below_white
  EXPECT "--highlight-knee"
  ABSENT pred_knee.vdb
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --highlight-gain 10 --highlight-knee 0.5 -o pred_knee.vdb)
lighthouse_cli_error(eval_negative_prune_alpha
  EXPECT "--prune-alpha"
  ABSENT eval_negative_prune
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS eval --data ${LH_PAIR} --prune-alpha -0.5 -o eval_negative_prune)

lighthouse_cli_error(eval_headroom_with_shard
  EXPECT "--headroom cannot be combined with --shard"
  ABSENT eval_headroom_shard
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS eval --data ${LH_PAIR} --headroom --shard 0/2 -o eval_headroom_shard)

# `lighthouse average-models`: the bundled model averaged with itself is written (half), and
# what would lose a model is refused: one model only, or an output that is one of the inputs.
if(EXISTS ${PROJECT_SOURCE_DIR}/models/standard.pt)
  lighthouse_cli_ok(average_models_bundled
    FILES averaged_standard.pt
    ARGS average-models ${PROJECT_SOURCE_DIR}/models/standard.pt
         ${PROJECT_SOURCE_DIR}/models/standard.pt --half --force -o averaged_standard.pt)
  lighthouse_cli_error(average_models_over_an_input
    EXPECT "output '.*standard[.]pt' [(]-o[)] is the input given as a model to average"
    MAX_MEMORY_MB ${LH_TORCH_MB}
    ARGS average-models ${PROJECT_SOURCE_DIR}/models/standard.pt
         ${PROJECT_SOURCE_DIR}/models/standard.pt -o ${PROJECT_SOURCE_DIR}/models/standard.pt)
endif()
lighthouse_cli_error(average_models_one_model
  EXPECT "models"
  ABSENT averaged_one.pt
  PARSE_ERROR
  MAX_MEMORY_MB ${LH_TORCH_MB}
  ARGS average-models only_one.pt -o averaged_one.pt)
