# `trackphys bake`, `info` on a map and `drive --map` end to end (included by CMakeLists.txt).
set(maps ${CMAKE_CURRENT_BINARY_DIR}/maps)
file(MAKE_DIRECTORY ${maps})

trackphys_cli_test(map.bake_default_track 0 "colliders +50, 302848 triangles"
                   bake --seed 7 --out ${maps}/seed7.tpmap)
trackphys_cli_test(map.bake_a_mesh 0 "colliders +[0-9]+, [0-9]+ triangles"
                   bake ${flat} --chunk 20 --out ${maps}/flat.tpmap)
set_tests_properties(map.bake_default_track map.bake_a_mesh PROPERTIES FIXTURES_SETUP baked_maps)

# The baked default track drives exactly as the track built at start (drive.pinned_state_hash).
trackphys_cli_test(map.drive_pinned_state_hash 0 "map .*seed7.tpmap.*state hash +b363d74e042e0fb1"
                   drive --map ${maps}/seed7.tpmap --seconds 10)
trackphys_cli_test(map.info 0 "format version 4.*colliders +50.*track +seed 7"
                   info ${maps}/seed7.tpmap)
# The generated track's surfaces, kept in the map: its road (0) and its walls (1).
trackphys_cli_test(map.info_lists_the_surfaces 0
                   "surfaces +0: 189280 triangles\n +1: 113568 triangles\n"
                   info ${maps}/seed7.tpmap)
trackphys_cli_test(map.drive_a_mesh_map_free 0 "map .*flat.tpmap.*state hash"
                   drive --map ${maps}/flat.tpmap --spawn 0,3,0 --seconds 1)
trackphys_cli_test(map.drive_a_mesh_map_needs_a_spawn 1 "baked from a mesh and has no centreline"
                   drive --map ${maps}/flat.tpmap --seconds 1)
set_tests_properties(map.drive_pinned_state_hash map.info map.info_lists_the_surfaces
                     map.drive_a_mesh_map_free
                     map.drive_a_mesh_map_needs_a_spawn PROPERTIES FIXTURES_REQUIRED baked_maps)

# race --map: the baked track races as the generated one (the same hash as race --seed 7);
# --seed with --map is an error naming both, as in drive.
trackphys_cli_test(map.race_pinned_state_hash 0 "map .*seed7.tpmap.*state hash +9af14d328ece090e"
                   race --map ${maps}/seed7.tpmap --cars 2 --seconds 2)
trackphys_cli_test(map.race_generated_state_hash 0 "seed 7.*state hash +9af14d328ece090e"
                   race --seed 7 --cars 2 --seconds 2)
trackphys_cli_test(map.race_a_mesh_map_needs_a_track 1 "baked from a mesh and has no centreline"
                   race --map ${maps}/flat.tpmap --cars 2 --seconds 1)
trackphys_cli_test(map.race_map_or_seed 1 "--seed picks a generated track, but this race is on the map '.*seed7.tpmap'"
                   race --map ${maps}/seed7.tpmap --seed 3 --cars 2 --seconds 1)
set_tests_properties(map.race_pinned_state_hash map.race_a_mesh_map_needs_a_track
                     map.race_map_or_seed PROPERTIES FIXTURES_REQUIRED baked_maps)

# info reads a file named .tpmap as a map: one without the magic is a bad map, not a mesh.
file(WRITE ${in}/garbage.tpmap "hello world, not a map")
trackphys_cli_test(map.info_rejects_a_tpmap_without_the_magic 1 "map '[^']*garbage.tpmap': wrong magic \\(not a trackphys map file\\)"
                   info ${in}/garbage.tpmap)
trackphys_cli_test(map.drive_rejects_a_device_as_map 1 "map '/dev/zero': not a regular file"
                   drive --map /dev/zero --seconds 1)
trackphys_cli_test(map.drive_rejects_a_folder_as_map 1 "map '[^']*a_folder.obj': is a folder, not a file"
                   drive --map ${in}/a_folder.obj --seconds 1)
trackphys_cli_test(map.drive_rejects_a_mesh_as_map 1 "map '.*flat_ground.obj': wrong magic"
                   drive --map ${flat} --seconds 1)
trackphys_cli_test(map.bake_mesh_or_seed 1 "give a mesh file or --seed"
                   bake ${flat} --seed 3 --out ${maps}/both.tpmap)
trackphys_cli_test(map.bake_needs_tpmap_name 1 "ends in .tpmap"
                   bake --seed 3 --out ${maps}/track.bin)
# bake's numbers are checked as drive's and race's are: named, shown as %g, one --threads range.
foreach(chunk IN ITEMS 0 -5 inf nan)
  trackphys_cli_test_leaves_nothing(map.bake_rejects_chunk_${chunk} 1 "--chunk must be finite and > 0 m, got ${chunk}"
                                    ${out}/bake_chunk_${chunk} bake ${flat} --chunk ${chunk} --out ${out}/bake_chunk_${chunk}/f.tpmap)
endforeach()
trackphys_cli_test_leaves_nothing(map.bake_rejects_too_many_threads 1
                                  "--threads must be in \\[0, 256\\] \\(0: the hardware's count\\), got 100000"
                                  ${out}/bake_threads bake --seed 3 --threads 100000 --out ${out}/bake_threads/t.tpmap)

# Scenario files name a map as track.map.
file(WRITE ${in}/scenario_map.json "{\"track\": {\"map\": \"${maps}/seed7.tpmap\"}, \"seconds\": 2}\n")
trackphys_cli_test(map.scenario_file 0 "map .*seed7.tpmap.*simulated +2.00 s"
                   drive --scenario ${in}/scenario_map.json)
set_tests_properties(map.scenario_file PROPERTIES FIXTURES_REQUIRED baked_maps)

# drive --mesh drives on the colliders bake makes: the same state hash as on the baked map,
# over a 300 m square of ground in 50 m squares (cells from the origin: 4 x 4 colliders).
set(grid_obj "")
foreach(i RANGE 0 6)
  foreach(j RANGE 0 6)
    math(EXPR x "${i} * 50 - 150")
    math(EXPR z "${j} * 50 - 150")
    string(APPEND grid_obj "v ${x} 0 ${z}\n")
  endforeach()
endforeach()
foreach(i RANGE 0 5)
  foreach(j RANGE 0 5)
    math(EXPR a "${i} * 7 + ${j} + 1")
    math(EXPR b "${a} + 1")
    math(EXPR c "${a} + 7")
    math(EXPR d "${c} + 1")
    string(APPEND grid_obj "f ${a} ${b} ${d}\nf ${a} ${d} ${c}\n")
  endforeach()
endforeach()
file(WRITE ${maps}/grid_300m.obj "${grid_obj}")
add_test(NAME map.drive_a_mesh_as_its_map
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/mesh_drives_as_its_map.sh $<TARGET_FILE:trackphys_app>
                 ${maps}/grid_300m.obj ${maps}/grid)
