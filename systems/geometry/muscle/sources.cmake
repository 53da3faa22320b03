# Muscle layer of the geometric controller: super-ellipsoid maths, muscle layouts (JSON loader,
# per-bone fitting), shape and tessellation jobs.
list(APPEND ALOHA_GEOMETRY_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/superellipsoid.cpp
  ${CMAKE_CURRENT_LIST_DIR}/muscle_set.cpp
  ${CMAKE_CURRENT_LIST_DIR}/muscle_shape_job.cpp
  ${CMAKE_CURRENT_LIST_DIR}/superellipsoid_tables.cpp
  ${CMAKE_CURRENT_LIST_DIR}/muscle_tessellate_job.cpp
  ${CMAKE_CURRENT_LIST_DIR}/muscle_loader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/muscle_fit.cpp
  ${CMAKE_CURRENT_LIST_DIR}/muscle_retarget.cpp)
