# The `radiosity` command line under CTest: good runs, bad input (exit 1, a message that says
# where and what, no output file) and usage errors (exit 2).
set(CLI $<TARGET_FILE:radiosity_cli>)
set(DATA ${CMAKE_CURRENT_SOURCE_DIR}/data)
set(OUT_DIR ${CMAKE_CURRENT_BINARY_DIR}/cli_out)
file(MAKE_DIRECTORY ${OUT_DIR})

include(${CMAKE_CURRENT_SOURCE_DIR}/cli_case.cmake)

# name, expected exit code, stderr regex, output file or "", then the arguments ("OUT/" is the
# case's own folder under cli_out/).
function(cli_test name code regex output)
  add_cli_case(cli.${name} ${CLI} ${OUT_DIR}/${name} ${code} "${regex}" "${output}" ${ARGN})
endfunction()

# Every shipped scene loads, meshes and writes.
file(GLOB scenes ${PROJECT_SOURCE_DIR}/scenes/*.json)
foreach(scene ${scenes})
  get_filename_component(stem ${scene} NAME_WE)
  cli_test(info.${stem} 0 "" "" info ${scene})
  cli_test(mesh.${stem} 0 "wrote" OUT/${stem}.ply mesh ${scene} -o OUT/${stem}.ply)
endforeach()
cli_test(help 0 "" "" --help)
cli_test(mesh_help 0 "" "" mesh --help)

# Bad input: exit 1 with "radiosity: error: <file>: <path>: expected ..., found ...".
# (Brackets in a CMake list item would glue items together: the patterns use '.' for them.)
set(bad_cases
  unparseable          "parse error at line 4, column 11"
  unknown_top_key      "expected one of the keys version, units, .* found the unknown key \"colour\""
  unknown_material_key "materials.white: expected one of the keys reflectance, .*found the unknown key \"reflectence\""
  unknown_surface_key  "surfaces.0.: expected one of the keys .*found the unknown key \"twosided\""
  missing_material     "surfaces.0.: expected a \"material\" key, found none"
  unknown_material     "surfaces.0..material: expected a material defined in \"materials\" .white, lamp., found the string \"marble\""
  reflectance_one      "materials.white.reflectance.1.: expected a reflectance in .0, 1., found the number 1.0"
  negative_emission    "materials.lamp.emission.1.: expected a finite emission >= 0, found the number -1"
  infinite_emission    "line [0-9]+, column [0-9]+: expected finite numbers, found '1e999'"
  nan_coordinate       "line 30, column 6: expected finite numbers, found '1e999'"
  two_vertices         "surfaces.0..polygon: expected at least 3 vertices .x, y, z., found an array of 2 items"
  zero_area            "surfaces.0..polygon: expected a polygon of non-zero area, found area 0"
  hole_outside         "surfaces.0..holes.0..0.: expected a hole vertex inside its polygon, found a point outside it"
  missing_mesh_file    "surfaces.2..mesh: expected a readable mesh file, found no file at .*no_such_statue.obj"
  unparseable_mesh_file "surfaces.2..mesh: .*broken.off: line 5: expected a vertex x, found 'this'"
  version_two          "version: expected version 1, found the number 2"
  bad_light_type       "lights.0..type: expected \"directional\", \"point\" or \"spot\", found the string \"area\""
  bad_fog_mode         "fog.mode: expected \"linear\", \"exp\" or \"exp2\", found the string \"thick\""
  bad_preset           "materials.knob.preset: expected one of black_plastic, brass, .*found the string \"platinum\""
  bad_contrast         "solver.contrast: expected a number in .1e-6, 1., found the number 5"
  bad_adaptive         "solver.adaptive: expected true or false, found the string \"yes\""
  bad_quality          "solver.quality: expected \"draft\", \"default\" or \"final\", found the string \"best\""
  obj_index_past_end   "surfaces.2..mesh: .*obj_index_past_end.obj: line 4: expected vertex indices from 1 to 3 .or -1 to -3, counting back., found '9'"
  obj_index_before_start "surfaces.2..mesh: .*obj_index_before_start.obj: line 4: expected vertex indices from 1 to 3 .*found '-9'"
  obj_index_int_max    "surfaces.2..mesh: .*obj_index_int_max.obj: line 4: expected vertex indices from 1 to 3 .*found '2147483647'"
  obj_index_int_min    "surfaces.2..mesh: .*obj_index_int_min.obj: line 4: expected vertex indices from 1 to 3 .*found '-2147483648'"
  obj_nan_vertex       "surfaces.2..mesh: .*obj_nan_vertex.obj: line 2: expected finite numbers after 'v', found 'nan'"
  obj_nan_emission     "surfaces.2..mesh: .*obj_nan_emission.mtl: line 3: expected finite numbers after 'Ke', found 'nan'"
  off_billions         "surfaces.2..mesh: .*off_billions.off: line 2: expected a vertex count from 0 to 4, found '4000000000'"
  off_index_past_end   "surfaces.2..mesh: .*off_index_past_end.off: line 6: expected a vertex index from 0 to 2, found '7'"
  ply_billions         "surfaces.2..mesh: .*ply_billions.ply: element vertex: expected at most the 3 records the file's size allows, found 2000000000 announced"
  ply_bad_header       "surfaces.2..mesh: .*ply_bad_header.ply: expected a property with PLY scalar types .*found 'property list uchar float'"
  ply_index_past_end   "surfaces.2..mesh: .*ply_index_past_end.ply: face 0: vertex_indices: expected vertex indices from 0 to 2, found 3"
  off_fuzz_no_vertices "surfaces.2..mesh: .*off_fuzz_no_vertices.off: line [0-9]+: expected a face of the file's vertices, found a file without vertices"
  obj_face_300_corners "surfaces.2..mesh: .*obj_face_300_corners.obj: line 301: expected faces of at most 255 vertices, found 300"
  obj_index_llong_min  "surfaces.2..mesh: .*obj_index_llong_min.obj: line 4: expected vertex indices from 1 to 3 .*found '-9223372036854775808'"
  off_homogeneous      "surfaces.2..mesh: .*off_homogeneous.off: line 1: expected the 'OFF' keyword .*found '4OFF'"
  long_mesh_name       "surfaces.2..mesh: expected a readable mesh file, found no file at .*xxxx.obj .File name too long."
  huge_polygon         "surfaces.0. .floor.: expected coordinates within ±1e15 scene units .*found the point .0, 0, 1e.77.")
while(bad_cases)
  list(POP_FRONT bad_cases case regex)
  cli_test(bad.${case} 1 "radiosity: error: .*${case}.json: ${regex}" OUT/${case}.ply
           mesh ${DATA}/bad/${case}.json -o OUT/${case}.ply)
  cli_test(bad_info.${case} 1 "radiosity: error: " "" info ${DATA}/bad/${case}.json)
endwhile()
cli_test(bad.missing_scene 1 "radiosity: error: .*nowhere.json: expected a readable scene file, found no such file"
         OUT/nowhere.ply mesh ${DATA}/nowhere.json -o OUT/nowhere.ply)
cli_test(bad.output_folder 1 "radiosity: error: .*no_such_folder/out.ply: expected an output file in an existing folder"
         "" mesh ${DATA}/good_small.json -o OUT/no_such_folder/out.ply)

# Usage errors: exit 2, no output.
cli_test(usage.unknown_flag 2 "--frobnicate" OUT/usage1.ply
         mesh ${DATA}/good_small.json -o OUT/usage1.ply --frobnicate)
cli_test(usage.missing_output 2 "output" "" mesh ${DATA}/good_small.json)
cli_test(usage.missing_value 2 "max-element-edge" OUT/usage2.ply
         mesh ${DATA}/good_small.json -o OUT/usage2.ply --max-element-edge)
cli_test(usage.negative_edge 2 "max-element-edge" OUT/usage3.ply
         mesh ${DATA}/good_small.json -o OUT/usage3.ply --max-element-edge -1)
cli_test(usage.unknown_quality 2 "--quality: best not in .draft,default,final." OUT/usage4.ply
         mesh ${DATA}/good_small.json -o OUT/usage4.ply --quality best)
cli_test(usage.no_command 2 "" "")

# formfactors: JSON on stdout; bad surface names are bad input, missing choices usage errors.
add_test(NAME cli.formfactors.from_light
         COMMAND ${CMAKE_COMMAND} "-DCOMMAND=${CLI}|formfactors|${PROJECT_SOURCE_DIR}/scenes/cornell_empty.json|--from|light|--hemicube|64"
                 -DEXPECT_CODE=0 "-DEXPECT_STDOUT=\"from\": \"light\".*\"sky\": 0\\.1[0-9]+.*\"name\": \"floor\",.*\"exact\": 0\\.24"
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/run_cli.cmake)
cli_test(formfactors.point 0 "" "" formfactors ${PROJECT_SOURCE_DIR}/scenes/cube.json --point 0.5,0,0.5 --normal 0,1,0)
cli_test(bad.formfactors_surface 1 "radiosity: error: --from: expected the name of a surface of .*found \"nope\""
         "" formfactors ${PROJECT_SOURCE_DIR}/scenes/cube.json --from nope)
cli_test(bad.formfactors_normal 1 "radiosity: error: --normal: expected a non-zero finite vector"
         "" formfactors ${PROJECT_SOURCE_DIR}/scenes/cube.json --point 0.5,0,0.5 --normal 0,0,0)
cli_test(usage.formfactors_nothing 2 "--from or --point" "" formfactors ${PROJECT_SOURCE_DIR}/scenes/cube.json)
cli_test(usage.formfactors_both 2 "excludes" "" formfactors ${PROJECT_SOURCE_DIR}/scenes/cube.json --from floor --point 0,0,0 --normal 0,1,0)
cli_test(usage.formfactors_odd_hemicube 2 "even" "" formfactors ${PROJECT_SOURCE_DIR}/scenes/cube.json --from floor --hemicube 65)
cli_test(usage.formfactors_point_without_normal 2 "normal" "" formfactors ${PROJECT_SOURCE_DIR}/scenes/cube.json --point 0,0,0)

# solve: the main job, on a small scene; a scene without emitters is bad input for solve only.
cli_test(solve.small 0 "progressive start [0-9]+ shots.*final gather at [0-9]+ vertices \\([0-9]+ added by refinement, [0-9]+ where gathering vertices near them differed; [0-9]+ others took their light\\): hemicubes [0-9.]+ s \\(beside the rays and shots\\)" OUT/small.ply
         solve ${DATA}/good_small.json -o OUT/small.ply --report OUT/small.json --hemicube 64)
cli_test(solve.shot_limit 0 "progressive start 3 shots .*max_shots" OUT/limited.ply
         solve ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/limited.ply --max-shots 3 --hemicube 32)
cli_test(bad.solve_no_emitter 1 "no_emitter.json: surfaces: expected at least one surface whose material has an emission, found none"
         OUT/no_emitter.ply solve ${DATA}/no_emitter.json -o OUT/no_emitter.ply)
cli_test(info.no_emitter 0 "" "" info ${DATA}/no_emitter.json)
cli_test(bad.solve_report_folder 1 "no_such_folder/r.json: expected an output file in an existing folder"
         OUT/r.ply solve ${DATA}/good_small.json -o OUT/r.ply --report OUT/no_such_folder/r.json --hemicube 32)
cli_test(usage.solve_overshoot 2 "overshoot" OUT/o.ply solve ${DATA}/good_small.json -o OUT/o.ply --overshoot 3)
cli_test(solve.fixed_point_direct 0 "progressive start .*final gather" OUT/ref.ply
         solve ${PROJECT_SOURCE_DIR}/scenes/parallel_squares.json -o OUT/ref.ply --fixed-point direct --hemicube 64)
cli_test(bad.solve_fixed_point_mismatch 1 "small.ply: expected a result of the same scene and mesh settings"
         OUT/mismatch.ply solve ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/mismatch.ply
         --fixed-point ${OUT_DIR}/solve.small/small.ply --hemicube 32)
set_tests_properties(cli.bad.solve_fixed_point_mismatch PROPERTIES DEPENDS cli.solve.small)

# The independent reference, and the true error measured against it.
cli_test(reference.cube 0 "20 points, .* paths .*wrote" OUT/ref.csv
         reference ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/ref.csv --count 20 --paths 4000)
cli_test(reference.points 0 "2 points" OUT/ref.csv
         reference ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/ref.csv --points ${DATA}/cube_points.txt --paths 1000)
cli_test(reference.squares 0 "wrote" OUT/ref.csv
         reference ${PROJECT_SOURCE_DIR}/scenes/parallel_squares.json -o OUT/ref.csv --count 20 --paths 2000)
cli_test(solve.true_error 0 "true error .RMS of the relative error at [0-9]+ channel values of 20 points" OUT/t.ply
         solve ${PROJECT_SOURCE_DIR}/scenes/parallel_squares.json -o OUT/t.ply --report OUT/t.json --hemicube 32
         --reference ${OUT_DIR}/reference.squares/ref.csv)
set_tests_properties(cli.solve.true_error PROPERTIES DEPENDS cli.reference.squares)
cli_test(convergence.small 0 "Gauss-Seidel.*front .*true error" OUT/conv.svg
         convergence ${PROJECT_SOURCE_DIR}/scenes/parallel_squares.json -o OUT/conv.svg --csv OUT/conv.csv
         --hemicube 32 --tolerance 1e-3 --reference ${OUT_DIR}/reference.squares/ref.csv)
set_tests_properties(cli.convergence.small PROPERTIES DEPENDS cli.reference.squares)
cli_test(bad.solve_reference_ply 1 "--reference direct: expected a reference CSV written by 'radiosity reference' .for the distance to the direct solution of the same mesh and factors, use --fixed-point."
         OUT/r.ply solve ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/r.ply --reference direct)
cli_test(bad.solve_reference_columns 1 "bad_reference.csv: line 3: expected 15 comma-separated columns, found 3"
         OUT/r.ply solve ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/r.ply --reference ${DATA}/bad/bad_reference.csv)
cli_test(bad.solve_reference_missing 1 "no_such.csv: expected a readable reference file .CSV., found no such file"
         OUT/r.ply solve ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/r.ply --reference ${DATA}/no_such.csv)
cli_test(bad.reference_points_line 1 "bad_points.txt: line 2: expected x y z nx ny nz .tag., six finite numbers, found '0.5 0 0.5 0 1'"
         OUT/r.csv reference ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/r.csv --points ${DATA}/bad/bad_points.txt)
cli_test(bad.reference_point_off_surface 1 "off_surface_points.txt: line 1: expected a point on a surface"
         OUT/r.csv reference ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/r.csv --points ${DATA}/bad/off_surface_points.txt)
cli_test(bad.reference_no_emitter 1 "no_emitter.json: surfaces: expected at least one surface whose material has an emission, found none"
         OUT/r.csv reference ${DATA}/no_emitter.json -o OUT/r.csv)
cli_test(usage.reference_paths_and_error 2 "excludes" OUT/r.csv
         reference ${PROJECT_SOURCE_DIR}/scenes/cube.json -o OUT/r.csv --paths 100 --relative-error 0.1)

# Adaptive subdivision: its flags, and their bad values.
cli_test(solve.adaptive_flags 0 "final gather at" OUT/adaptive.ply
         solve ${DATA}/good_small.json -o OUT/adaptive.ply --adaptive true --min-element-edge 0.05
         --contrast 0.05 --vertex-direct true)
cli_test(solve.uniform 0 "final gather at" OUT/uniform.ply
         solve ${DATA}/good_small.json -o OUT/uniform.ply --adaptive false --vertex-direct false)
cli_test(solve.without_gather 0 "converged after [0-9]+ shots" OUT/ungathered.ply
         solve ${DATA}/good_small.json -o OUT/ungathered.ply --final-gather false)
cli_test(solve.without_clusters 0 "converged after [0-9]+ shots" OUT/unclustered.ply
         solve ${DATA}/good_small.json -o OUT/unclustered.ply --final-gather false --cluster-shooters false)
cli_test(usage.cluster_shooters_not_bool 2 "cluster-shooters" OUT/cs.ply
         solve ${DATA}/good_small.json -o OUT/cs.ply --cluster-shooters maybe)
cli_test(solve.every_shot_at_one_resolution 0 "converged after [0-9]+ shots" OUT/one_resolution.ply
         solve ${DATA}/good_small.json -o OUT/one_resolution.ply --final-gather false --resolution-follows-power false)
cli_test(usage.resolution_follows_power_not_bool 2 "resolution-follows-power" OUT/rfp.ply
         solve ${DATA}/good_small.json -o OUT/rfp.ply --resolution-follows-power often)
cli_test(usage.contrast_range 2 "contrast" OUT/c.ply solve ${DATA}/good_small.json -o OUT/c.ply --contrast 2)
cli_test(usage.adaptive_not_bool 2 "adaptive" OUT/a.ply solve ${DATA}/good_small.json -o OUT/a.ply --adaptive maybe)
cli_test(usage.min_edge_negative 2 "min-element-edge" OUT/m.ply
         solve ${DATA}/good_small.json -o OUT/m.ply --min-element-edge -1)
cli_test(bad.solve_reference_other_scene 1 "ref.csv: point 1: expected a surface of .*parallel_squares.json, found '.*' .a reference of another scene..."
         OUT/r.ply solve ${PROJECT_SOURCE_DIR}/scenes/parallel_squares.json -o OUT/r.ply --hemicube 32
         --reference ${OUT_DIR}/reference.cube/ref.csv)
set_tests_properties(cli.bad.solve_reference_other_scene PROPERTIES DEPENDS cli.reference.cube)

# Hostile files: FIFOs and a 2 GiB zero-filled file are refused at once, naming the file.
set(HOSTILE ${OUT_DIR}/hostile)
add_test(NAME cli.hostile_files COMMAND ${CMAKE_COMMAND} -DDIR=${HOSTILE} -DSOURCE=${PROJECT_SOURCE_DIR}
         -P ${CMAKE_CURRENT_SOURCE_DIR}/hostile_files.cmake)
set_tests_properties(cli.hostile_files PROPERTIES FIXTURES_SETUP hostile_files)
cli_test(bad.scene_fifo 1 "scene.fifo: expected a readable scene file .a regular file., found a FIFO .named pipe."
         OUT/f.ply mesh ${HOSTILE}/scene.fifo -o OUT/f.ply)
cli_test(bad.scene_folder 1 "bad: expected a readable scene file .a regular file., found a folder"
         OUT/f.ply mesh ${DATA}/bad -o OUT/f.ply)
cli_test(bad.mesh_fifo 1 "surfaces.2..mesh: .*mesh_fifo.obj: expected a readable mesh file .a regular file., found a FIFO"
         OUT/f.ply mesh ${HOSTILE}/names_mesh_fifo.obj.json -o OUT/f.ply)
cli_test(bad.mesh_zeros 1 "surfaces.2..mesh: .*zeros.obj: expected a Wavefront OBJ file .text., found a NUL byte at offset 0"
         OUT/f.ply mesh ${HOSTILE}/names_zeros.obj.json -o OUT/f.ply)
cli_test(bad.scene_zeros 1 "zeros.json: expected a readable scene file of at most 64 MiB, found a file of 2048 MiB"
         OUT/f.ply mesh ${HOSTILE}/zeros.json -o OUT/f.ply)
cli_test(bad.reference_fifo 1 "reference.fifo: expected a readable reference file .CSV. .a regular file., found a FIFO"
         OUT/f.ply solve ${DATA}/good_small.json -o OUT/f.ply --reference ${HOSTILE}/reference.fifo)
cli_test(bad.fixed_point_fifo 1 "result.fifo: expected a readable PLY file .a regular file., found a FIFO"
         OUT/f.ply solve ${DATA}/good_small.json -o OUT/f.ply --hemicube 16 --fixed-point ${HOSTILE}/result.fifo)
foreach(case scene_fifo mesh_fifo mesh_zeros scene_zeros reference_fifo fixed_point_fifo)
  set_tests_properties(cli.bad.${case} PROPERTIES FIXTURES_REQUIRED hostile_files TIMEOUT 20)
endforeach()
cli_test(bad.element_cap 1 "solver.max_element_edge .--max-element-edge.: expected an element edge giving at most 2000000 elements .raise the edge, or the cap solver.max_elements .--max-elements.., found 0.001 .about .*e.12 elements."
         OUT/f.ply mesh ${PROJECT_SOURCE_DIR}/scenes/cornell.json -o OUT/f.ply --max-element-edge 0.001)
cli_test(bad.element_cap_raised 1 "found 0.001 .about .*e.12 elements."
         OUT/f.ply mesh ${PROJECT_SOURCE_DIR}/scenes/cornell.json -o OUT/f.ply --max-element-edge 0.001 --max-elements 3000000)
cli_test(bad.element_cap_mesh_faces 1 "box_on_floor.json: solver.max_element_edge .--max-element-edge.: expected an element edge giving at most 10 elements"
         OUT/f.ply mesh ${DATA}/box_on_floor.json -o OUT/f.ply --max-elements 10)

# Faces that point away from the light (issue 30): the room wound outwards is turned round, said
# once, naming the surface and the flag that keeps the file's facing.
cli_test(info.inverted_room 0 "surface 'room' .white. faces away from the light: all 6 of its faces.*--fix-facing" ""
         info ${DATA}/inverted_room.json)
# The reference finds points in a 0.5 mm gap (under 1e-3 of the scene's size).
cli_test(reference.narrow_gap 0 "2 points, .* wrote" OUT/gap.csv
         reference ${DATA}/floor_under_panel.json -o OUT/gap.csv --points ${DATA}/gap_points.txt --paths 64)
