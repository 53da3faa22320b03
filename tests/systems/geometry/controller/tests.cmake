# Tests of the geometric controller (included from tests/systems/geometry/CMakeLists.txt).
aloha_test(geomctl_tests
  SOURCES
    ${CMAKE_CURRENT_LIST_DIR}/controller_levels_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/controller_memory_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/slot_store_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/controller_morph_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/reference_springs_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/level_fades_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/controller_threads_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/controller_gltf_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/body_texture_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/continuous_skin_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/body_scale_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/controller_layers_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/muscle_volume_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/simplified_indices_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/surface_distance_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/skin_bake_test.cpp
  LIBS aloha::geometry aloha::assets aloha::motion
  LABELS geometry)
# Fat springs driven by the characters' world motion, through the frame glue (GeometryUpdateJob).
aloha_test(fat_world_tests
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/fat_world_test.cpp
  LIBS aloha::geometry aloha::assets aloha::motion aloha::frame
  LABELS geometry)
