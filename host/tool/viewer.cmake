# Viewer sources of the aloha tool (`aloha view`: GLFW window + Dear ImGui overlay).
find_package(glfw3 3.3 CONFIG REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
target_sources(aloha_tool PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/cmd_view.cpp
  ${CMAKE_CURRENT_LIST_DIR}/viewer_camera.cpp
  ${CMAKE_CURRENT_LIST_DIR}/viewer_gui.cpp
  ${CMAKE_CURRENT_LIST_DIR}/viewer_overlay.cpp
  ${CMAKE_CURRENT_LIST_DIR}/viewer_pick.cpp
  ${CMAKE_CURRENT_LIST_DIR}/viewer_rules.cpp)
target_link_libraries(aloha_tool PRIVATE aloha::gpu_window PkgConfig::IMGUI glfw)
