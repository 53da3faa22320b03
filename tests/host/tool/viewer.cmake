# `aloha view`: camera and rule-editing maths (compiled in from host/tool), and the built tool run
# under Xvfb (window, overlay, --frames, --out, --validation) plus a bad-scene failure.
aloha_test(viewer_test
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/viewer_test.cpp
          ${PROJECT_SOURCE_DIR}/host/tool/viewer_camera.cpp
          ${PROJECT_SOURCE_DIR}/host/tool/viewer_rules.cpp
          ${PROJECT_SOURCE_DIR}/host/tool/viewer_pick.cpp
  LIBS aloha::scene aloha::gpu
  LABELS gpu)
if(TARGET aloha_tool)
  add_dependencies(viewer_test aloha_tool)
  target_compile_definitions(viewer_test PRIVATE ALOHA_TOOL_BINARY="$<TARGET_FILE:aloha_tool>")
endif()
