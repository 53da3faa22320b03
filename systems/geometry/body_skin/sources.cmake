# Continuous skin (part of aloha::geometry): the implicit body field and its polygonisation,
# manifold-preserving simplification and relaxation, vertex-cache order (meshoptimizer), multi-muscle binding with blended fat springs, and
# surface-to-surface correspondence for geomorphing between skin resolutions.
list(APPEND ALOHA_GEOMETRY_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/skin_field.cpp
  ${CMAKE_CURRENT_LIST_DIR}/edge_collapse.cpp
  ${CMAKE_CURRENT_LIST_DIR}/skin_remesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/blend_binding.cpp
  ${CMAKE_CURRENT_LIST_DIR}/blend_rest.cpp
  ${CMAKE_CURRENT_LIST_DIR}/weight_smoothing.cpp
  ${CMAKE_CURRENT_LIST_DIR}/surface_map.cpp
  ${CMAKE_CURRENT_LIST_DIR}/triangle_grid.cpp)
