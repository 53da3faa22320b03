# Dynamic walk tests; included by tests/systems/motion/CMakeLists.txt.
aloha_test(dynamic_tests
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/dynamic_walk_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/dynamic_long_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/dynamic_hook_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/dynamic_push_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/dynamic_guard_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/dynamic_plaza_test.cpp
          ${CMAKE_CURRENT_LIST_DIR}/dynamic_skate_test.cpp
  LIBS aloha::motion aloha::assets
  LABELS motion dynamic)
