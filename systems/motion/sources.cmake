# Motion controller core: clips, sampling, local-to-model, blending, pose pool, walk, controller.
list(APPEND ALOHA_MOTION_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/clip.cpp
  ${CMAKE_CURRENT_LIST_DIR}/root_motion.cpp
  ${CMAKE_CURRENT_LIST_DIR}/clip_quant.cpp
  ${CMAKE_CURRENT_LIST_DIR}/clip_decode_avx2.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sampling.cpp
  ${CMAKE_CURRENT_LIST_DIR}/local_to_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/local_to_model_avx2.cpp
  ${CMAKE_CURRENT_LIST_DIR}/blend.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pose_pool.cpp)
list(APPEND ALOHA_MOTION_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/walk_rig.cpp
  ${CMAKE_CURRENT_LIST_DIR}/kinematic_walk.cpp
  ${CMAKE_CURRENT_LIST_DIR}/controller.cpp
  ${CMAKE_CURRENT_LIST_DIR}/controller_eval.cpp
  ${CMAKE_CURRENT_LIST_DIR}/controller_step.cpp
  ${CMAKE_CURRENT_LIST_DIR}/controller_steady.cpp
  ${CMAKE_CURRENT_LIST_DIR}/controller_overlay.cpp
  ${CMAKE_CURRENT_LIST_DIR}/motion_metrics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/crowd_motion_meter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/throttle_keys.cpp
  ${CMAKE_CURRENT_LIST_DIR}/foot_lock.cpp
  ${CMAKE_CURRENT_LIST_DIR}/inertialize.cpp)
