# Tests of fat springs, skin, subdivision, geomorphing and peeled layers.
aloha_test(skin_tests
  SOURCES
    ${CMAKE_CURRENT_LIST_DIR}/fat_spring_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/skin_mesh_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/peeled_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/subdivision_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/geomorph_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/grid_sample_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/strain_limit_test.cpp
  LIBS aloha::geometry aloha_opensubdiv
  LABELS geometry)
