# Command-line tests of `lighthouse insert` (included by CMakeLists.txt). The photo is the
# fixture volume's own view from its reference camera.

lighthouse_cli_ok(insert_photo
  PNG photo.png
  ARGS render-view example.vdb --cameras cameras.json -o photo.png)
set_tests_properties(cli.ok.insert_photo PROPERTIES FIXTURES_SETUP lighthouse_insert_photo)

set(LH_INSERT_BASE example.vdb --image photo.png --cameras cameras.json)
lighthouse_cli_ok(insert_mirror_sphere
  PNG ins_mirror.png
  ARGS insert ${LH_INSERT_BASE} --object sphere --at 0,0.5,2.5 --scale 0.2 -o ins_mirror.png)
lighthouse_cli_ok(insert_three_objects_single_envmap
  EXR ins_single.exr
  PNG ins_single.png
  ARGS insert ${LH_INSERT_BASE} --object sphere --at 0,0.5,2.5 --object cube --at 0.5,0.5,2.5
       --object torus --at -0.5,0.5,2.5 --scale 0.15 --material glossy:0.3 --samples 4
       --single-envmap --png -o ins_single.exr)
lighthouse_cli_ok(insert_along_a_path
  PNG ins_path_000.png ins_path_002.png ins_path_sheet.png ins_path_epipolar.png
  ARGS insert ${LH_INSERT_BASE} --object sphere --at 0,0,1 --scale 0.1 --path points.txt
       -o ins_path.png)
foreach(t insert_mirror_sphere insert_three_objects_single_envmap insert_along_a_path)
  set_tests_properties(cli.ok.${t} PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_insert_photo")
endforeach()

lighthouse_cli_error(insert_image_camera_mismatch
  EXPECT "image is 320x240 but the camera is 64x48"
  ABSENT ins_bad1.png
  ARGS insert example.vdb --image photo.png --cameras cameras_ok.json --object sphere
       --at 0,0,1 -o ins_bad1.png)
lighthouse_cli_error(insert_unknown_material
  EXPECT "material 'gold'"
  ABSENT ins_bad2.png
  ARGS insert ${LH_INSERT_BASE} --object sphere --at 0,0,1 --material gold -o ins_bad2.png)
lighthouse_cli_error(insert_positions_per_object
  EXPECT "each --object needs its own --at"
  ABSENT ins_bad3.png
  ARGS insert ${LH_INSERT_BASE} --object sphere --object cube --at 0,0,1 -o ins_bad3.png)
lighthouse_cli_error(insert_unknown_object
  EXPECT "unknown built-in object 'teapot'"
  ABSENT ins_bad4.png
  ARGS insert ${LH_INSERT_BASE} --object teapot --at 0,0,1 -o ins_bad4.png)
lighthouse_cli_error(insert_missing_mesh_file
  EXPECT "mesh file 'no_such_mesh[.]obj' does not exist"
  ABSENT ins_bad5.png
  ARGS insert ${LH_INSERT_BASE} --object no_such_mesh.obj --at 0,0,1 -o ins_bad5.png)
lighthouse_cli_error(insert_bad_output_format
  EXPECT "must end in [.]exr or [.]png"
  ABSENT ins_bad6.bmp
  ARGS insert ${LH_INSERT_BASE} --object sphere --at 0,0,1 -o ins_bad6.bmp)
lighthouse_cli_error(insert_negative_scale
  EXPECT "--scale must be a positive number"
  ABSENT ins_bad7.png
  ARGS insert ${LH_INSERT_BASE} --object sphere --at 0,0,1 --scale -1 -o ins_bad7.png)
foreach(t insert_image_camera_mismatch insert_unknown_material insert_positions_per_object
          insert_unknown_object insert_missing_mesh_file insert_bad_output_format insert_negative_scale)
  set_tests_properties(cli.error.${t} PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_insert_photo")
endforeach()

# The speed-against-error report on the fixture volume (tiny, so that it stays fast).
lighthouse_cli_ok(bench_envmap_report
  STDOUT "paper-spheres" "openvdb-fixed-step" "ours" "Against the targets" "times faster"
         "not judged: this run rendered 16x8 envmaps" "Where the rays go" "voxels of medium per ray"
         "Rays that leave, by the transmittance they keep"
  FILES bench_out/speed_error.csv bench_out/speed_error.md bench_out/speed_error.svg
        bench_out/ray_budget.md
  ARGS bench-envmap example.vdb --count 1 --size 16x8 -o bench_out)
lighthouse_cli_error(bench_envmap_zero_repeats
  EXPECT "--repeats must be in [[]1, 100[]]"
  ARGS bench-envmap example.vdb --count 1 --size 16x8 --repeats 0 -o bench_out_bad)
set_tests_properties(cli.error.bench_envmap_zero_repeats PROPERTIES FIXTURES_REQUIRED lighthouse_cli)
lighthouse_cli_error(bench_envmap_coarse_reference
  EXPECT "the reference step must be in [[]0.005, 0.05[]] voxels"
  ARGS bench-envmap example.vdb --count 1 --size 16x8 --reference-step 0.1 -o bench_out_bad2)
set_tests_properties(cli.error.bench_envmap_coarse_reference PROPERTIES FIXTURES_REQUIRED lighthouse_cli)

# `lighthouse edit`: an emissive box added at +x shows up in a re-rendered envmap file.
lighthouse_cli_ok(edit_add_box_and_scale
  FILES edited.vdb
  ARGS edit example.vdb --add-box 1.0,-0.2,-0.2,1.4,0.2,0.2:5,0,0 --scale-radiance 2 --clamp-radiance 100
       -o edited.vdb)
lighthouse_cli_ok(edit_then_render
  EXR edited_env.exr
  ARGS render-envmap edited.vdb --at 0,0,0.5 --size 32x16 -o edited_env.exr)
# A fixture, not just an order: running edit_then_render alone (ctest -R) runs the edit first.
set_tests_properties(cli.ok.edit_add_box_and_scale PROPERTIES FIXTURES_SETUP lighthouse_edited)
set_tests_properties(cli.ok.edit_then_render PROPERTIES FIXTURES_REQUIRED "lighthouse_cli;lighthouse_edited")
lighthouse_cli_error(edit_nothing
  EXPECT "no edit given"
  ABSENT edited_none.vdb
  ARGS edit example.vdb -o edited_none.vdb)
lighthouse_cli_error(edit_bad_box
  EXPECT "--add-box.*expected 6 numbers"
  ABSENT edited_bad.vdb
  ARGS edit example.vdb --add-box 1,2,3:1,1,1 -o edited_bad.vdb)
lighthouse_cli_error(edit_inverted_box
  EXPECT "min < max"
  ABSENT edited_bad2.vdb
  ARGS edit example.vdb --erase-box 1,1,1,0,0,0 -o edited_bad2.vdb)
