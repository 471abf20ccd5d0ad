# Command-line tests of `lighthouse synth` and `lighthouse oracle` (included by CMakeLists.txt).

lighthouse_cli_ok(help_synth
  STDOUT "Usage:.*synth" "--seed" "--count" "--split" "--envmap-size" "--lamp-layout"
  ARGS synth --help)
lighthouse_cli_ok(help_oracle
  STDOUT "Usage:.*oracle" "--levels" "--res" "--envmaps-out"
  ARGS oracle --help)

lighthouse_cli_error(synth_bad_split
  EXPECT "--split must be train or test"
  ABSENT syn_bad_split
  ARGS synth -o syn_bad_split --split validation --count 1)
lighthouse_cli_error(synth_bad_size
  EXPECT "--size must be between"
  ABSENT syn_bad_size
  ARGS synth -o syn_bad_size --size 10x10 --count 1)
lighthouse_cli_error(synth_bad_envmap_size
  EXPECT "--envmap-size must be W x H with W = 2 H"
  ABSENT syn_bad_env
  ARGS synth -o syn_bad_env --envmap-size 100x100 --count 1)
lighthouse_cli_error(synth_bad_lamp_layout
  PARSE_ERROR EXPECT "--lamp-layout: grid not in [{]random,room[}]"
  ABSENT syn_bad_layout
  ARGS synth -o syn_bad_layout --lamp-layout grid --count 1)
lighthouse_cli_error(synth_zero_count
  EXPECT "--count must be in"
  ABSENT syn_zero
  ARGS synth -o syn_zero --count 0)
lighthouse_cli_error(synth_missing_panoramas
  EXPECT "no panoramas.*no_such_hdri"
  ABSENT syn_no_hdri
  ARGS synth -o syn_no_hdri --count 1 --hdri-dir no_such_hdri)

# A tiny data set: the fixture of the oracle and compare tests below.
lighthouse_cli_ok(synth_tiny
  FILES syn_tiny/manifest.json syn_tiny/000001/cameras.json syn_tiny/000001/scene.json
  PNG syn_tiny/contact_sheet.png syn_tiny/000000/ref.png syn_tiny/000000/env_0_mask.png
  EXR syn_tiny/000000/ref.exr syn_tiny/000000/depth.exr syn_tiny/000000/env_0.exr
  ARGS synth --seed 3 --count 2 --size 48x36 --envmap-size 32x16 --envmaps 1 --supersample 1
       -o syn_tiny)
set_tests_properties(cli.ok.synth_tiny PROPERTIES FIXTURES_SETUP lighthouse_synth_tiny)

lighthouse_cli_ok(oracle_tiny
  FILES oracle_tiny.vdb
  EXR oracle_env/env_0.exr
  ARGS oracle syn_tiny/000000 -o oracle_tiny.vdb --levels 3 --res 16 --envmaps-out oracle_env)
lighthouse_cli_ok(compare_oracle_with_ground_truth
  STDOUT "1 envmap" "PSNR"
  ARGS compare --batch oracle_env syn_tiny/000000)
set_tests_properties(cli.ok.oracle_tiny PROPERTIES FIXTURES_SETUP lighthouse_oracle_tiny)
set_tests_properties(cli.ok.oracle_tiny PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_synth_tiny")
set_tests_properties(cli.ok.compare_oracle_with_ground_truth PROPERTIES
  FIXTURES_REQUIRED "lighthouse_cli;lighthouse_synth_tiny;lighthouse_oracle_tiny")

lighthouse_cli_error(oracle_not_a_directory
  EXPECT "'no_such_example' is not an example directory"
  ABSENT oracle_bad.vdb
  ARGS oracle no_such_example -o oracle_bad.vdb)
lighthouse_cli_error(oracle_directory_without_scene
  EXPECT "cannot open scene file.*adir/scene[.]json"
  ABSENT oracle_bad2.vdb
  ARGS oracle adir -o oracle_bad2.vdb)

# `lighthouse photo-clipping`: the clipped share of a data set's reference photos, as they are
# and metered for their highlights; folders without ref.exr are one clear error.
lighthouse_cli_ok(photo_clipping_tiny
  STDOUT "syn_tiny: 2 reference photos. [0-9.]+% of their pixels clip [(]per photo: median [0-9.]+%, largest [0-9.]+%[)]"
  ARGS photo-clipping syn_tiny)
lighthouse_cli_ok(photo_clipping_metered
  STDOUT "syn_tiny/000000: 1 reference photo, metered for their highlights. [0-9.]+% of their pixels clip"
  ARGS photo-clipping syn_tiny/000000 --max-photo-clipped 0.02)
set_tests_properties(cli.ok.photo_clipping_tiny cli.ok.photo_clipping_metered PROPERTIES
  FIXTURES_REQUIRED "lighthouse_cli;lighthouse_synth_tiny")
lighthouse_cli_error(photo_clipping_no_reference_views
  EXPECT "no ref[.]exr in 'adir'"
  ARGS photo-clipping adir)
lighthouse_cli_error(photo_clipping_missing_directory
  EXPECT "'no_such_data' is not a directory"
  ARGS photo-clipping no_such_data)
lighthouse_cli_error(photo_clipping_fraction_above_one
  PARSE_ERROR EXPECT "--max-photo-clipped"
  ARGS photo-clipping adir --max-photo-clipped 2)
