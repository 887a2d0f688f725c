# The viewer: its GoogleTest binary and the `radview` command line under CTest (same style as
# cli_tests.cmake). Their inputs are files kept in tests/data, so that the viewer's tests and
# golden images do not change with the solver: a coarse Cornell result, made once by
#   radiosity solve scenes/cornell.json -o tests/data/cornell_coarse_result.ply
#       --max-element-edge 80 --max-patch-edge 160
# and a small scene meshed without solving it (a PLY without radiosity properties), made once by
#   radiosity mesh tests/data/good_small.json -o tests/data/good_small_mesh_only.ply
set(VIEWER_OUT ${CMAKE_CURRENT_BINARY_DIR}/viewer_out)
file(MAKE_DIRECTORY ${VIEWER_OUT})
set(VIEWER_INPUT ${CMAKE_CURRENT_SOURCE_DIR}/data/cornell_coarse_result.ply)
set(VIEWER_MESH_ONLY ${CMAKE_CURRENT_SOURCE_DIR}/data/good_small_mesh_only.ply)

add_executable(viewer_test viewer_test.cpp default_view_test.cpp)
target_link_libraries(viewer_test PRIVATE rad::viewer GTest::gtest_main nlohmann_json::nlohmann_json)
target_compile_definitions(viewer_test PRIVATE
  RAD_RADIOSITY_CLI="$<TARGET_FILE:radiosity_cli>"
  RAD_RADVIEW_CLI="$<TARGET_FILE:radview>"
  RAD_VIEWER_INPUT="${VIEWER_INPUT}"
  RAD_VIEWER_OUT="${VIEWER_OUT}"
  RAD_SCENES="${PROJECT_SOURCE_DIR}/scenes"
  RAD_GOLDEN_DIR="${CMAKE_CURRENT_SOURCE_DIR}/golden"
  RAD_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(viewer_test radview radiosity_cli)
gtest_discover_tests(viewer_test)

# name, expected exit code, stderr regex, output file or "", then the arguments ("OUT/" is the
# case's own folder).
function(viewer_cli_test name code regex output)
  add_cli_case(viewer_cli.${name} $<TARGET_FILE:radview> ${VIEWER_OUT}/cli/${name} ${code}
               "${regex}" "${output}" ${ARGN})
endfunction()

# Good runs write the picture.
viewer_cli_test(osmesa 0 "wrote" OUT/osmesa.png ${VIEWER_INPUT} -o OUT/osmesa.png)
viewer_cli_test(software_flat 0 "wrote" OUT/software_flat.png
                ${VIEWER_INPUT} -o OUT/software_flat.png --backend software --shade flat
                --width 200 --height 150)
viewer_cli_test(hdr 0 "wrote" OUT/hdr.hdr
                ${VIEWER_INPUT} -o OUT/hdr.png --hdr OUT/hdr.hdr --width 64 --height 64)
viewer_cli_test(wireframe_ssaa_camera 0 "wrote" OUT/wire.png
                ${VIEWER_INPUT} -o OUT/wire.png --wireframe --ssaa 2 --exposure 2
                --camera eye=278,273,-600,fov=50 --width 128 --height 128)
viewer_cli_test(software_wireframe 0 "wrote" OUT/software_wire.png
                ${VIEWER_INPUT} -o OUT/software_wire.png --backend software --wireframe
                --width 128 --height 96)
viewer_cli_test(help 0 "" "" --help)

# Bad input: exit 1, "radview: error: <where>: expected <what>, found <what>", no output.
viewer_cli_test(bad.missing_input 1
                "radview: error: .*nowhere.ply: expected a readable PLY file, found no such file"
                OUT/missing.png ${VIEWER_OUT}/nowhere.ply -o OUT/missing.png)
viewer_cli_test(bad.no_radiosity 1
                "radview: error: .*mesh_only.ply: expected a radiosity result .*found a PLY without vertex radiosity_r, vertex radiosity_g, vertex radiosity_b, face radiosity_r, face radiosity_g, face radiosity_b"
                OUT/no_radiosity.png ${VIEWER_MESH_ONLY} -o OUT/no_radiosity.png)
viewer_cli_test(bad.camera 1 "radview: error: --camera: expected eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=F.*found 2 number.s. for eye"
                OUT/bad_camera.png ${VIEWER_INPUT} -o OUT/bad_camera.png --camera eye=1,2)
viewer_cli_test(bad.camera_key 1 "radview: error: --camera: expected .*found the unknown key \"position\""
                OUT/bad_camera2.png ${VIEWER_INPUT} -o OUT/bad_camera2.png --camera position=1,2,3)
viewer_cli_test(bad.output_folder 1 "radview: error: .*no_such_folder/out.png: expected an output file in an existing folder"
                "" ${VIEWER_INPUT} -o OUT/no_such_folder/out.png)

# Usage errors: exit 2, no output.
viewer_cli_test(usage.unknown_flag 2 "--frobnicate" OUT/usage1.png
                ${VIEWER_INPUT} -o OUT/usage1.png --frobnicate)
viewer_cli_test(usage.missing_output 2 "output" "" ${VIEWER_INPUT})
viewer_cli_test(usage.missing_value 2 "width" OUT/usage2.png ${VIEWER_INPUT} -o OUT/usage2.png --width)
viewer_cli_test(usage.bad_shade 2 "shade" OUT/usage3.png ${VIEWER_INPUT} -o OUT/usage3.png --shade phong)

# Local-illumination mode (--mode local --scene SCENE.json): OpenGL lighting through OSMesa.
set(VIEWER_CORNELL_SCENE ${PROJECT_SOURCE_DIR}/scenes/cornell.json)
viewer_cli_test(local 0 "local lighting.*wrote" OUT/local.png
                --mode local --scene ${VIEWER_CORNELL_SCENE} -o OUT/local.png --width 128 --height 128)
viewer_cli_test(local_flat_wire_ssaa 0 "wrote" OUT/local_flat.png
                --mode local --scene ${VIEWER_CORNELL_SCENE} -o OUT/local_flat.png --width 96
                --height 64 --shade flat --wireframe --ssaa 2 --camera eye=278,273,-600,fov=50)
viewer_cli_test(bad.local_no_lights 1
                "radview: error: .*good_small.json: expected a scene with lights for --mode local, found none"
                OUT/no_lights.png --mode local --scene ${CMAKE_CURRENT_SOURCE_DIR}/data/good_small.json
                -o OUT/no_lights.png)
viewer_cli_test(bad.local_missing_scene 1 "radview: error: .*nowhere.json" OUT/local_missing.png
                --mode local --scene ${VIEWER_OUT}/nowhere.json -o OUT/local_missing.png)
viewer_cli_test(usage.local_without_scene 2 "--scene.*required with --mode local" OUT/usage5.png
                --mode local -o OUT/usage5.png)
viewer_cli_test(usage.local_with_result 2 "--mode local takes --scene" OUT/usage6.png
                --mode local --scene ${VIEWER_CORNELL_SCENE} ${VIEWER_INPUT} -o OUT/usage6.png)
viewer_cli_test(usage.local_software 2 "--mode local is OpenGL-only" OUT/usage7.png
                --mode local --scene ${VIEWER_CORNELL_SCENE} --backend software -o OUT/usage7.png)
viewer_cli_test(usage.local_hdr 2 "--hdr.*radiosity-only" OUT/usage8.png
                --mode local --scene ${VIEWER_CORNELL_SCENE} -o OUT/usage8.png --hdr OUT/usage8.hdr)
viewer_cli_test(usage.radiosity_without_result 2 "RESULT.ply is required" OUT/usage9.png -o OUT/usage9.png)
viewer_cli_test(usage.radiosity_with_scene 2 "--scene.*belongs to --mode local" OUT/usage10.png
                ${VIEWER_INPUT} --scene ${VIEWER_CORNELL_SCENE} -o OUT/usage10.png)

# Hybrid mode (--mode hybrid RESULT.ply --scene SCENE.json): radiosity plus specular, OSMesa.
viewer_cli_test(hybrid 0 "hybrid.*wrote" OUT/hybrid.png
                --mode hybrid ${VIEWER_INPUT} --scene ${VIEWER_CORNELL_SCENE} -o OUT/hybrid.png
                --width 96 --height 96 --shade flat --wireframe)
viewer_cli_test(usage.hybrid_without_scene 2 "--scene.*required with --mode hybrid" OUT/usage11.png
                --mode hybrid ${VIEWER_INPUT} -o OUT/usage11.png)
viewer_cli_test(usage.hybrid_software 2 "--mode hybrid is OpenGL-only" OUT/usage12.png
                --mode hybrid ${VIEWER_INPUT} --scene ${VIEWER_CORNELL_SCENE} --backend software
                -o OUT/usage12.png)
viewer_cli_test(bad.hybrid_no_surface 1
                "radview: error: .*mesh_only.ply: expected a radiosity result" OUT/hybrid_bad.png
                --mode hybrid ${VIEWER_MESH_ONLY} --scene ${VIEWER_CORNELL_SCENE} -o OUT/hybrid_bad.png)

# The realism ladder (--ladder RESULT.ply --scene SCENE.json): one 4x2 grid of tiles.
viewer_cli_test(ladder 0 "rendered 256x128 \\(ladder.*wrote" OUT/ladder.png
                ${VIEWER_INPUT} --scene ${VIEWER_CORNELL_SCENE} --ladder -o OUT/ladder.png
                --width 64 --height 64)
viewer_cli_test(usage.ladder_without_scene 2 "--scene.*required with --ladder" OUT/usage13.png
                ${VIEWER_INPUT} --ladder -o OUT/usage13.png)
viewer_cli_test(usage.ladder_wireframe 2 "--wireframe.*not with --ladder" OUT/usage14.png
                ${VIEWER_INPUT} --scene ${VIEWER_CORNELL_SCENE} --ladder --wireframe -o OUT/usage14.png)

# Back-face culling (--cull back, radiosity mode only): behind the box, the inside shows.
viewer_cli_test(cull_back 0 "wrote" OUT/cull.png
                ${VIEWER_INPUT} -o OUT/cull.png --cull back --camera eye=278,273,1200
                --width 96 --height 96)
viewer_cli_test(cull_back_software_wire 0 "wrote" OUT/cull_sw.png
                ${VIEWER_INPUT} -o OUT/cull_sw.png --cull back --backend software --wireframe
                --camera eye=278,273,1200 --width 96 --height 96)
viewer_cli_test(usage.bad_cull 2 "--cull" OUT/usage15.png
                ${VIEWER_INPUT} -o OUT/usage15.png --cull front)
viewer_cli_test(usage.cull_local 2 "--cull.*radiosity-only" OUT/usage16.png
                --mode local --scene ${VIEWER_CORNELL_SCENE} --cull back -o OUT/usage16.png)

# An output path nobody can write (a file under /proc): exit 1, nothing left behind.
viewer_cli_test(bad.unwritable_output 1 "radview: error: " ""
                ${VIEWER_INPUT} -o /proc/radview_cannot_write_here.png)

# Hostile result files: a property or an element twice, two index lists, a FIFO.
foreach(case property_twice two_index_lists face_element_twice)
  set(expect_property_twice "element face: expected each property once, found 'radiosity_r' twice")
  set(expect_two_index_lists "element face: expected each property once, found 'vertex_indices' twice")
  set(expect_face_element_twice "expected each element once, found 'face' twice")
  viewer_cli_test(bad.result_${case} 1 "radview: error: .*result_${case}.ply: ${expect_${case}}"
                  OUT/r.png ${CMAKE_CURRENT_SOURCE_DIR}/data/bad/result_${case}.ply -o OUT/r.png)
endforeach()
viewer_cli_test(bad.result_fifo 1 "radview: error: .*result.fifo: expected a readable PLY file .a regular file., found a FIFO"
                OUT/r.png ${CMAKE_CURRENT_BINARY_DIR}/cli_out/hostile/result.fifo -o OUT/r.png)
set_tests_properties(viewer_cli.bad.result_fifo PROPERTIES FIXTURES_REQUIRED hostile_files TIMEOUT 20)
