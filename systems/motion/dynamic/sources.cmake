# Dynamic walk (Barzel & Barr constraint forces); included by systems/motion/CMakeLists.txt.
list(APPEND ALOHA_MOTION_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/dense_solve.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dynamic_init.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dynamic_contacts.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dynamic_step.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dynamic_hook.cpp)
