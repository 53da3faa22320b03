# Tests of the muscle layer (included from tests/systems/geometry/CMakeLists.txt).
aloha_test(muscle_tests
  SOURCES
    ${CMAKE_CURRENT_LIST_DIR}/superellipsoid_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/muscle_jobs_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/muscle_loader_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/muscle_fit_test.cpp
  LIBS aloha::geometry
  LABELS geometry muscle)
