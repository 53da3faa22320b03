# Tests of the continuous skin pieces: body field and polygonisation, simplification, blend binding,
# surface correspondence and its closest-point grid.
aloha_test(body_skin_tests
  SOURCES
    ${CMAKE_CURRENT_LIST_DIR}/skin_field_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/blend_binding_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/blend_rest_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/triangle_grid_test.cpp
  LIBS aloha::geometry
  LABELS geometry)
