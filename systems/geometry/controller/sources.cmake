# Geometric controller (part of aloha::geometry): per character type geometry, per-level slot
# storage, level switches with geomorphing, per-frame update per method, fidelity reference.
list(APPEND ALOHA_GEOMETRY_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/body_texture.cpp
  ${CMAKE_CURRENT_LIST_DIR}/character_geometry.cpp
  ${CMAKE_CURRENT_LIST_DIR}/skin_layer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/skin_bake.cpp
  ${CMAKE_CURRENT_LIST_DIR}/generated_mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gltf_character_mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/slot_store.cpp
  ${CMAKE_CURRENT_LIST_DIR}/geometry_controller.cpp
  ${CMAKE_CURRENT_LIST_DIR}/controller_update.cpp
  ${CMAKE_CURRENT_LIST_DIR}/level_fades.cpp
  ${CMAKE_CURRENT_LIST_DIR}/simplified_indices.cpp
  ${CMAKE_CURRENT_LIST_DIR}/surface_distance.cpp
  ${CMAKE_CURRENT_LIST_DIR}/fat_regions.cpp
  ${CMAKE_CURRENT_LIST_DIR}/controller_reference.cpp)
