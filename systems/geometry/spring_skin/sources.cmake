# Fat springs, skin, OpenSubdiv refinement, geomorphing and peeled layers (part of aloha::geometry).
list(APPEND ALOHA_GEOMETRY_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/grid_sample.cpp
  ${CMAKE_CURRENT_LIST_DIR}/fat_spring.cpp
  ${CMAKE_CURRENT_LIST_DIR}/fat_spring_frame.cpp
  ${CMAKE_CURRENT_LIST_DIR}/skin_mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/peeled.cpp
  ${CMAKE_CURRENT_LIST_DIR}/subdivision.cpp
  ${CMAKE_CURRENT_LIST_DIR}/geomorph.cpp
  ${CMAKE_CURRENT_LIST_DIR}/strain_limit.cpp)
