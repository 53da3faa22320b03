# Motion controller core tests (clips, sampling, local-to-model, blending, controller, walk).
if(TARGET aloha_motion)
  aloha_test(motion_tests
    SOURCES
      ${CMAKE_CURRENT_LIST_DIR}/sampling_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/clip_quant_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/pose_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/controller_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/controller_wrap_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/controller_root_motion_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/root_motion_test.cpp
      ${CMAKE_CURRENT_LIST_DIR}/walk_test.cpp
    LIBS aloha::motion
    LABELS motion)
endif()
# Controller integration: host element order, parallel chunks, throttling spread (with IK and dynamic hooks).
if(TARGET aloha_motion)
  aloha_test(motion_integration_tests
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/controller_parallel_test.cpp
    LIBS aloha::motion
    LABELS motion)
endif()
# The BVH walk needs the asset loaders (engine/assets).
if(TARGET aloha_motion AND TARGET aloha_assets)
  aloha_test(motion_bvh_tests
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/bvh_walk_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/controller_overlay_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/motion_metrics_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/crowd_motion_meter_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/inertialize_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/foot_lock_test.cpp
            ${CMAKE_CURRENT_LIST_DIR}/controller_steady_test.cpp
    LIBS aloha::motion aloha::assets
    LABELS motion)
endif()
